"""Property tests (hypothesis) of the command line at its edges.

Random text, raw bytes, huge and tiny numbers, unicode digits and signs go into every
subcommand's parser. The rule (README "Command line"): never a traceback, exit status 0 all
solved, 1 some refused, 2 bad input (3 is an internal error: always a bug, so never seen
here). For ik and fk every input must give the same bytes and status on CPython and inside
the MicroPython VM; the VM runs once per example, on a whole list of inputs.
"""

import argparse
import ast
import contextlib
import io
import os
import sys
import tempfile

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from hexapod_host import mpvm
from hexapod_host.commands import cli
from hexapod_host.commands import kin as cmd_kin
from hexapod_host.testing.runtimes import micropython_missing
from hexapod_host.vm import kin

VM_DIR = os.path.dirname(os.path.abspath(kin.__file__))
SETTINGS = {"deadline": None, "derandomize": True, "suppress_health_check": [HealthCheck.too_slow]}

signs = st.sampled_from(["", "", "-", "+", "\u2212", "\uff0d", "--", "+-", "-."])
ascii_number = st.one_of(
    st.integers(-4000, 4000).map(str),
    st.integers(-(10**40), 10**40).map(str),
    st.decimals(allow_nan=True, allow_infinity=True).map(str),
    st.floats().map(repr),  # '1e+16', 'nan', 'inf', '-0.0'
    st.floats().map(str),
    st.integers(1, 1500).map(lambda n: "9" * n),  # past the 1000-byte cut, and just under it
    st.integers(1, 1200).map(lambda n: "0" * n + "1.5"),
    st.integers(1, 40).map(lambda n: "0." + "0" * n + "5"),
    st.sampled_from(["3000", "-3000", "3000.05", "2999.95", "360", "-360.005", ".5", "5.", ".", "-", "1_000"]),
)
unicode_digits = st.text(st.characters(categories=["Nd"]), min_size=1, max_size=6)
word = st.one_of(
    ascii_number,
    st.tuples(signs, ascii_number).map("".join),
    st.tuples(signs, unicode_digits).map("".join),
    st.text(max_size=12),
    st.binary(max_size=12).map(lambda b: b.decode("utf-8", "surrogateescape")),  # argv bytes, as Python sees them
    st.tuples(ascii_number, st.sampled_from(["e6", "E-3", "\u00a0", " ", "\t", "\ufeff", "\x00", "\\"])).map("".join),
)
triple = st.lists(word, min_size=0, max_size=4).filter(lambda ws: all("\0" not in w for w in ws))
line = st.one_of(
    st.lists(word, min_size=0, max_size=4).map(lambda ws: " ".join(ws).encode("utf-8", "surrogateescape")),
    st.binary(max_size=30),
    st.sampled_from([b"", b"  \t\r", b"\xef\xbb\xbf140 0 -80", b"140 0 -80", b"0 95 -10", b"\xed\xa0\x80 1 2"]),
)
GEOMETRY = ["30", "85", "125", "32"]  # the CLI's default leg


def engine_argv(kind, batch, as_json):
    words = [kind + ("-batch" if batch else ""), "1" if as_json else "0"]
    args = argparse.Namespace(coxa="30", femur="85", tibia="125", femur_offset="32", limits=None)
    return words + cmd_kin.geometry_words(args)


def stdin_of_words(words):
    return b"".join(cmd_kin._word_bytes(w) + b"\0" for w in words)


DRIVER = """
import io
import sys

sys.path.append(%r)
import kin

for argv, data in CASES:
    out = io.StringIO()
    err = io.StringIO()
    try:
        status = kin.run(argv, io.BytesIO(data), out, err)
    except Exception as exc:
        status = "raised %%s: %%s" %% (type(exc).__name__, exc)
    print(repr((status, out.getvalue(), err.getvalue())))
"""


def both_runtimes(cases):
    """[(status, stdout, stderr)] of each (argv, stdin bytes) case on CPython and in one VM run."""
    here = []
    for argv, data in cases:
        out, err = io.StringIO(), io.StringIO()
        here.append((kin.run(argv, io.BytesIO(data), out, err), out.getvalue(), err.getvalue()))
    with tempfile.NamedTemporaryFile("w", suffix=".py", delete=False) as f:
        f.write("CASES = %r\n%s" % (cases, DRIVER % VM_DIR))
    try:
        text = mpvm.run(script=f.name, heapsize="16m", timeout=120)
    finally:
        os.unlink(f.name)
    there = [ast.literal_eval(row) for row in text.splitlines()]
    return here, there


def check_rule(status, out, err, lines_out):
    assert status in (0, 1, 2), (status, err)
    assert "Traceback" not in err and "internal error" not in err
    assert len(out.splitlines()) == lines_out(status)
    assert out.isascii() and err.isascii()  # escaped, so the bytes cannot depend on an encoding


@settings(max_examples=12, **SETTINGS)
@given(st.lists(st.tuples(st.sampled_from(["ik", "fk"]), st.booleans(), triple), min_size=20, max_size=40))
def test_ik_fk_words_same_bytes_and_status_on_both_runtimes(cases):
    if micropython_missing():
        return
    runs = [(engine_argv(kind, False, as_json), stdin_of_words(words)) for kind, as_json, words in cases]
    here, there = both_runtimes(runs)
    assert here == there
    for (_, as_json, _), (status, out, err) in zip(cases, here, strict=True):
        # a usage error (2) says so on stderr; under --json also as one {"error": ...} line on stdout
        check_rule(status, out, err, lambda s, j=as_json: 0 if s == 2 and not j else 1)
        assert (err == "") == (status != 2)


@settings(max_examples=12, **SETTINGS)
@given(
    st.lists(
        st.tuples(st.sampled_from(["ik", "fk"]), st.booleans(), st.lists(line, max_size=12), st.booleans()),
        min_size=4,
        max_size=10,
    )
)
def test_batches_same_bytes_and_status_on_both_runtimes(cases):
    if micropython_missing():
        return
    runs = []
    for kind, as_json, lines, final_newline in cases:
        data = b"\n".join(lines) + (b"\n" if final_newline and lines else b"")
        runs.append((engine_argv(kind, True, as_json), data))
    here, there = both_runtimes(runs)
    assert here == there
    for (argv, data), (status, out, err) in zip(runs, here, strict=True):
        answered = len(out.splitlines())
        check_rule(status, out, err, lambda s, n=answered: n)
        records = data.split(b"\n")
        assert answered <= len(records)
        # 2 if any line was bad, else 1 if any refused, else 0 (README's batch rule).
        bad = err.count("\n")
        refused = sum(1 for r in out.splitlines() if r.startswith(("unreachable", "beyond limit")) or '": false' in r)
        assert status == (2 if bad else 1 if refused else 0)
        if argv[1] == "1":
            import json

            assert all(isinstance(json.loads(r), dict) for r in out.splitlines())


# The whole CLI in-process: subcommands, options and random words in any order.
# fmt: off
VOCABULARY = [
    "ik", "fk", "bench", "plot", "sim", "gait", "kinematics", "ik", "i2c", "tick", "--batch", "--json",
    "--runtime", "cpython", "micropython", "--coxa", "--femur", "--tibia", "--femur-offset", "--limits", "--out",
    "--gait", "--speed", "--turn", "--help", "--version", "-h", "tripod", "all", "wave", "1", "-90", "90", "0", "-180",
]
# fmt: on
safe_word = word.filter(lambda w: not w.lstrip().startswith(("/", "~")) and ".." not in w and "\0" not in w)
argvs = st.lists(st.one_of(st.sampled_from(VOCABULARY), safe_word), min_size=0, max_size=10)


def fast_parser(build):
    """The real parser with the long jobs (benches, simulations, drawing) replaced by stubs."""
    parser = build()
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            sim = action.choices["sim"]
            for sub in sim._actions:
                if isinstance(sub, argparse._SubParsersAction):
                    for kind in sub.choices.values():
                        kind.set_defaults(func=lambda args: 0)
    return parser


@settings(max_examples=400, **SETTINGS)
@given(argvs, st.binary(max_size=200))
def test_every_command_line_follows_the_exit_rule(argv, stdin):
    from unittest import mock

    from hexapod_host.commands import bench as cmd_bench
    from hexapod_host.commands import plot as cmd_plot

    cwd = os.getcwd()
    with tempfile.TemporaryDirectory() as tmp, contextlib.ExitStack() as stack:
        os.chdir(tmp)  # --out directories land here
        stack.callback(os.chdir, cwd)
        stack.enter_context(mock.patch.object(cli, "build_parser", lambda b=cli.build_parser: fast_parser(b)))
        stack.enter_context(mock.patch.dict(cmd_bench.BENCHES, {k: (lambda args: {}) for k in cmd_bench.BENCHES}))
        for name in ("_trajectory", "_phases", "_top"):
            stack.enter_context(mock.patch.object(cmd_plot, name, lambda *a: "x.png"))
        stack.enter_context(mock.patch.object(cmd_plot, "record", lambda *a, **k: (None, None, [])))
        stack.enter_context(mock.patch.object(mpvm, "run_script_status", lambda *a, **k: (10, "", "")))
        stack.enter_context(mock.patch.object(sys, "stdin", io.TextIOWrapper(io.BytesIO(stdin))))
        out, err = io.StringIO(), io.StringIO()
        stack.enter_context(contextlib.redirect_stdout(out))
        stack.enter_context(contextlib.redirect_stderr(err))
        try:
            status = cli.main(list(argv))
        except SystemExit as exc:
            status = exc.code or 0
    assert status in (0, 1, 2), (argv, status, err.getvalue())
    assert "Traceback" not in err.getvalue()
    if status == 2:
        assert err.getvalue().count("hexapod: ") >= 1 or "error" in err.getvalue(), (argv, err.getvalue())


@settings(max_examples=500, **SETTINGS)
@given(st.one_of(st.binary(max_size=12), st.text(max_size=6).map(lambda t: t.encode("utf-8", "surrogatepass"))))
def test_utf8_check_agrees_with_cpythons_strict_codec(data):
    try:
        data.decode("utf-8")
        strict = True
    except UnicodeDecodeError:
        strict = False
    assert kin.utf8_ok(data) == strict


class ShortReads(io.BytesIO):
    """A stream that hands out at most `step` bytes per read, as a pipe may."""

    def __init__(self, data, step):
        super().__init__(data)
        self.step = step

    def read(self, n=-1):
        return super().read(min(n, self.step))


@settings(max_examples=200, **SETTINGS)
@given(
    st.lists(st.binary(max_size=40).map(lambda b: b.replace(b"\n", b"")), max_size=8),
    st.booleans(),
    st.integers(1, 50),
    st.integers(1, 30),
)
def test_records_split_like_bytes_split_and_cut_at_the_limit(lines, final, step, limit):
    data = b"\n".join(lines) + (b"\n" if final and lines else b"")
    want = data.split(b"\n")
    if want and want[-1] == b"":
        want.pop()  # a last newline ends the last line; it does not start an empty one
    got = list(kin.records(ShortReads(data, step), b"\n", limit))
    assert got == [(w[:limit], len(w)) for w in want]
