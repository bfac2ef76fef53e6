"""`hexapod ik` / `hexapod fk`: output format, JSON, batch, both runtimes, and bad input."""

import json
import os
import subprocess
import sys

import pytest

from hexapod.leg import OK, Leg
from hexapod.units import format_fixed
from hexapod_host.commands import cli

HEXAPOD = os.path.join(os.path.dirname(sys.executable), "hexapod")


def run(capsys, *argv, stdin=None, monkeypatch=None):
    if stdin is not None:
        import io

        data = stdin if isinstance(stdin, bytes) else stdin.encode()
        monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BytesIO(data)))
    try:
        status = cli.main(list(argv))
    except SystemExit as exc:
        status = exc.code
    out = capsys.readouterr()
    return status, out.out, out.err


def test_ik_prints_three_angles_with_two_decimals(capsys):
    status, out, _ = run(capsys, "ik", "140", "0", "-80")
    leg = Leg(coxa=300, femur=850, tibia=1250, femur_offset=320)
    angles = [0, 0, 0]
    assert leg.ik(1400, 0, -800, angles) == OK
    assert status == 0
    assert out == " ".join(format_fixed(a, 2) for a in angles) + "\n"


def test_fk_inverts_ik(capsys):
    status, out, _ = run(capsys, "ik", "120", "-35.5", "-60.2")
    t = out.split()
    status, out, _ = run(capsys, "fk", *t)
    assert status == 0
    assert [float(v) for v in out.split()] == pytest.approx([120, -35.5, -60.2], abs=0.11)


def test_json_and_geometry_options(capsys):
    status, out, _ = run(
        capsys, "ik", "0", "137", "0", "--coxa", "30", "--femur", "45", "--tibia", "62", "--femur-offset", "0"
    )
    assert status == 0 and out.split() == ["90.00", "0.00", "0.00"]
    status, out, _ = run(
        capsys, "ik", "0", "137", "0", "--coxa=30", "--femur=45", "--tibia=62", "--femur-offset=0", "--json"
    )
    assert json.loads(out) == {"reachable": True, "theta1_deg": 90.0, "theta2_deg": 0.0, "theta3_deg": 0.0}
    status, out, _ = run(capsys, "fk", "10", "20", "-30", "--json")
    assert set(json.loads(out)) == {"within_limits", "x_mm", "y_mm", "z_mm"}


def test_unreachable_is_status_1_with_the_reason(capsys):
    status, out, _ = run(capsys, "ik", "400", "0", "0")
    assert status == 1 and out.startswith("unreachable: too far: ") and "mm beyond the reach" in out
    status, out, _ = run(capsys, "ik", "34", "0", "32")
    assert status == 1 and "too close" in out
    status, out, _ = run(capsys, "ik", "-100", "10", "-50")
    assert status == 1 and out == "unreachable: coxa above its limit by 84.29 deg\n"
    status, out, _ = run(capsys, "ik", "150", "0", "-100", "--limits", "-90", "90", "-5", "90", "-180", "0")
    assert status == 1 and out == "unreachable: femur below its limit by 3.30 deg\n"
    status, out, _ = run(capsys, "fk", "0", "95", "-10")
    assert status == 1 and out == "beyond limit: femur above its limit by 5.00 deg\n"
    status, out, _ = run(capsys, "fk", "0", "95", "-10", "--json")
    assert json.loads(out) == {"within_limits": False, "reason": "femur above its limit by 5.00 deg"}
    status, out, _ = run(capsys, "ik", "400", "0", "0", "--json")
    assert json.loads(out)["reachable"] is False


BAD = [
    (("ik", "ten", "0", "0"), "x: 'ten' is not a number"),
    (("ik", "1", "2"), "need 3 numbers (x y z), got 2"),
    (("ik", "1", "2", "3", "4"), "need 3 numbers (x y z), got 4"),
    (("ik",), "need 3 numbers (x y z), got 0"),
    (("ik", "1", "NaN", "3"), "y: 'NaN' is not a number"),
    (("ik", "1", "2", "inf"), "z: 'inf' is not a number"),
    (("ik", "1", "2", "1e3"), "z: '1e3' is not a number: exponents are not accepted"),
    (("ik", "1", "2", "2.5E+03"), "z: '2.5E+03' is not a number: exponents are not accepted"),
    (("ik", "3000.05", "2", "3"), "x: '3000.05' is outside the accepted -3000..3000 mm"),
    (("ik", "1", "-99999", "3"), "y: '-99999' is outside the accepted -3000..3000 mm"),
    (("ik", "214751365", "0", "0"), "x: '214751365' is outside the accepted -3000..3000 mm"),
    (("ik", "1073741823", "0", "0"), "x: '1073741823' is outside the accepted -3000..3000 mm"),
    (("ik", "9" * 100000, "0", "0"), "x: '99999999999999999999...' is longer than 1000 bytes"),
    (("ik", "9" * 999, "0", "0"), "x: '99999999999999999999...' is outside the accepted -3000..3000 mm"),
    (("ik", "\uff11\uff14\uff10", "0", "-80"), "x: '\\uff11\\uff14\\uff10' is not a number: only ASCII digits"),
    (("ik", "\udcff", "0", "-80"), "x: '\\xff' is not UTF-8 text"),
    (("ik", "\u22125", "0", "-80"), "x: '\\u22125' is not a number: only ASCII digits"),
    (("fk", "0", "360.005", "0"), "theta2: '360.005' is outside the accepted -360..360 deg"),
    (("fk", "1", "2", "3", "--batch"), "--batch reads stdin"),
    (("ik", "1", "2", "3", "--femur", "-85"), "--femur: -85 mm is outside the allowed 10..250 mm"),
    (("ik", "1", "2", "3", "--tibia", "0"), "--tibia: 0 mm is outside"),
    (("ik", "1", "2", "3", "--coxa", "-1"), "--coxa: -1 mm is outside"),
    (("ik", "1", "2", "3", "--coxa", "x"), "--coxa: 'x' is not a number"),
    (("ik", "1", "2", "3", "--coxa", "9" * 30), "--coxa: 99999999999999999999... mm is outside the allowed 0..150 mm"),
    (("ik", "1", "2", "3", "--coxa", "150.05"), "--coxa: 150.05 mm is outside the allowed 0..150 mm"),
    (("ik", "1", "2", "3", "--femur-offset", "999"), "--femur-offset: 999 mm is outside"),
    (
        ("ik", "1", "2", "3", "--limits", "10", "-10", "-90", "90", "-180", "0"),
        "coxa min 10.00 deg is above its max -10.00",
    ),
    (("ik", "1", "2", "3", "--limits", "-90", "90", "-90", "90", "-190", "0"), "--limits: -190 deg is outside"),
    (("ik", "1", "2", "3", "--limits", "a", "90", "-90", "90", "-180", "0"), "--limits: 'a' is not a number"),
    (("fk", "1", "x", "3"), "theta2: 'x' is not a number"),
    (("fk", "1", "2"), "need 3 numbers (theta1 theta2 theta3), got 2"),
    (("ik", "--batch", "1", "2", "3"), "--batch reads stdin"),
    (("ik", "1", "2", "3", "--runtime", "pypy"), "invalid choice: 'pypy'"),
]


@pytest.mark.parametrize("argv,message", BAD, ids=[" ".join(a)[:40] for a, _ in BAD])
def test_bad_input_exits_2_naming_the_value(capsys, argv, message):
    status, out, err = run(capsys, *argv)
    assert status == 2
    assert message in err, err
    assert out == ""


def test_batch_reports_bad_lines_and_carries_on(capsys, monkeypatch):
    stdin = "140 0 -80\nfoo 1 2\n400 0 0\n1 2\n\n \t \r\n120 10 -70\n"
    status, out, err = run(capsys, "ik", "--batch", stdin=stdin, monkeypatch=monkeypatch)
    rows = out.splitlines()
    assert status == 2 and len(rows) == 5  # the blank lines 5 and 6 are skipped
    assert rows[1] == "error: line 2: x: 'foo' is not a number"
    assert rows[2].startswith("unreachable: too far")
    assert rows[3] == "error: line 4: need 3 numbers (x y z), got 2"
    assert len(rows[4].split()) == 3 and "line 2" in err and "line 4" in err and "line 5" not in err


@pytest.mark.parametrize(
    "stdin,status",
    [
        ("140 0 -80\n120 10 -70", 0),  # all solved (no newline at the end is fine)
        ("140 0 -80\n400 0 0\n", 1),  # one refused
        ("140 0 -80\n400 0 0\nx 0 0\n", 2),  # refused and bad: bad wins
        ("x 0 0\n140 0 -80\n", 2),
        ("", 0),  # nothing asked, nothing refused
        ("\n\n", 0),
    ],
)
def test_batch_exit_status_rule(capsys, monkeypatch, stdin, status):
    assert run(capsys, "ik", "--batch", stdin=stdin, monkeypatch=monkeypatch)[0] == status


def test_batch_strips_a_bom_and_reads_crlf(capsys, monkeypatch):
    stdin = b"\xef\xbb\xbf140 0 -80\r\n140 0 -80\r\n\xef\xbb\xbf140 0 -80\n"
    status, out, _ = run(capsys, "ik", "--batch", stdin=stdin, monkeypatch=monkeypatch)
    rows = out.splitlines()
    assert rows[:2] == ["0.00 6.99 -85.16"] * 2  # README's example answer
    # Only a BOM at the start of the input is one; later it is a character like any other.
    assert (
        status == 2
        and rows[2] == "error: line 3: x: '\\ufeff140' is not a number: only ASCII digits 0-9, '-' and '.' are accepted"
    )


def test_batch_json_every_line_is_an_object(capsys, monkeypatch):
    stdin = b'140 0 -80\n400 0 0\n\n\xff\xfe 1 2\nfoo"\\ 1 2\n'
    status, out, err = run(capsys, "ik", "--batch", "--json", stdin=stdin, monkeypatch=monkeypatch)
    rows = [json.loads(r) for r in out.splitlines()]
    assert status == 2
    assert rows[0] == {"line": 1, "reachable": True, "theta1_deg": 0.0, "theta2_deg": 6.99, "theta3_deg": -85.16}
    assert rows[1]["line"] == 2 and rows[1]["reachable"] is False and rows[1]["reason"].startswith("too far")
    assert rows[2] == {"line": 4, "error": "'\\xff\\xfe 1 2' is not UTF-8 text"}
    assert rows[3] == {"line": 5, "error": "x: 'foo\"\\\\' is not a number"}
    assert "hexapod: line 4: '\\xff\\xfe 1 2' is not UTF-8 text" in err


def test_fk_batch(capsys, monkeypatch):
    stdin = "0 6.99 -85.16\n0 95 -10\n0 400 0\n"
    status, out, _ = run(capsys, "fk", "--batch", stdin=stdin, monkeypatch=monkeypatch)
    rows = out.splitlines()
    assert status == 2 and len(rows) == 3
    assert [float(v) for v in rows[0].split()] == pytest.approx([140, 0, -80], abs=0.11)
    assert rows[1] == "beyond limit: femur above its limit by 5.00 deg"
    assert rows[2] == "error: line 3: theta2: '400' is outside the accepted -360..360 deg"


def test_input_domain_edges_are_exact(capsys):
    # 3000 mm (and 2999.95, which rounds to it) is in; the next 0.1 mm step is out.
    for x in ("3000", "-3000", "2999.95", "3000.04", "0003000.0"):
        status, out, _ = run(capsys, "ik", x, "0", "0")
        assert status == 1 and out.startswith("unreachable: too far"), x
    for x in ("3000.05", "-3000.1", "3001"):
        assert run(capsys, "ik", "0", "0", x)[0] == 2, x
    for t in ("360", "-360", "360.004"):
        assert run(capsys, "fk", t, "0", "0")[0] == 1, t
    assert run(capsys, "fk", "0", "0", "-360.005")[0] == 2


def test_version(capsys):
    from importlib.metadata import version

    with pytest.raises(SystemExit) as exc:
        cli.main(["--version"])
    assert exc.value.code == 0 and capsys.readouterr().out == "hexapod %s\n" % version("hexapod")


def test_a_crash_is_status_3_in_one_line(capsys, monkeypatch):
    from hexapod_host.vm import kin

    def boom(*a):
        raise ZeroDivisionError("division by zero")

    monkeypatch.setattr(kin, "run", boom)
    status, out, err = run(capsys, "ik", "1", "2", "3")
    assert status == 3 and out == ""
    assert err == "hexapod: internal error: ZeroDivisionError: division by zero (a bug: please report it)\n"


def test_a_vm_crash_is_status_3_not_1(capsys, monkeypatch):
    from hexapod_host import mpvm

    # MicroPython exits 1 on an uncaught exception: that must not read as "refused".
    monkeypatch.setattr(mpvm, "run_script_status", lambda *a, **k: (1, "", "Traceback ...\nMemoryError: \n"))
    status, out, err = run(capsys, "ik", "1", "2", "3", "--runtime", "micropython")
    assert status == 3 and out == "" and "internal error" in err and "MemoryError" in err


def batch_input(n):
    lines = []
    for k in range(n):
        lines.append("%d.%d %d -%d.%d" % (60 + k % 130, k % 10, (k * 7) % 160 - 80, 20 + k % 100, k % 7))
    return "".join(line + "\n" for line in lines)


def hexapod(*argv, stdin=""):
    return subprocess.run([HEXAPOD, *argv], input=stdin, capture_output=True, text=True, timeout=120)


@pytest.mark.parametrize(
    "argv",
    [
        ("ik", "140", "0", "-80"),
        ("ik", "140", "0", "-80", "--json"),
        ("ik", "500", "0", "0"),
        ("fk", "12.5", "-30", "-100.25"),
        ("ik", "1", "zz", "3"),
        ("ik", "214751365", "0", "0"),
        ("ik", "\uff11\uff14\uff10", "0", "-80"),
        ("ik", "1" * 100000, "0", "0"),
        ("fk", "0", "95", "-10", "--json"),
    ],
    ids=lambda a: " ".join(a)[:30],
)
def test_micropython_runtime_prints_byte_identical_output(argv, mp):
    a = hexapod(*argv)
    b = hexapod(*argv, "--runtime", "micropython")
    assert (a.returncode, a.stdout, a.stderr) == (b.returncode, b.stdout, b.stderr)
    assert a.stdout or a.stderr


@pytest.mark.parametrize("kind", ["ik", "fk"])
def test_nasty_batch_identical_in_both_runtimes(mp, kind):
    stdin = (
        b"\xef\xbb\xbf140 0 -80\n\n\xff\xfe 1 2\n\xed\xa0\x80 0 0\n\xc0\x80 1 1\n\xf4\x90\x80\x80 1 1\n"
        + "\uff11\uff14\uff10 0 -80\n1e6 0 0\n214751365 0 0\n".encode()
        + b"1" * 100000
        + b" 0 0\n0 95 -10\n400 0 0\n\t\r\n\x00 1 2\n1 2\n1\x1c 2 3\n-0 -0.0 +0.04\n"
    )
    for extra in ((), ("--json",)):
        a = subprocess.run([HEXAPOD, kind, "--batch", *extra], input=stdin, capture_output=True, timeout=120)
        b = subprocess.run(
            [HEXAPOD, kind, "--batch", *extra, "--runtime", "micropython"],
            input=stdin,
            capture_output=True,
            timeout=120,
        )
        assert (a.returncode, a.stdout, a.stderr) == (b.returncode, b.stdout, b.stderr)
        assert a.returncode == 2 and len(a.stdout.splitlines()) == 15 and b"Traceback" not in a.stderr


def test_broken_pipe_exits_quietly(mp):
    stdin = "140 0 -80\n" * 20000  # 340 KB of answers: more than a pipe holds
    for runtime in ("cpython", "micropython"):
        p = subprocess.run(
            "%s ik --batch --runtime %s | head -1; echo ${PIPESTATUS[0]}" % (HEXAPOD, runtime),
            shell=True,
            executable="/bin/bash",
            input=stdin,
            capture_output=True,
            text=True,
            timeout=120,
        )
        assert p.stdout == "0.00 6.99 -85.16\n141\n" and p.stderr == "", (runtime, p.stderr)


def test_ten_thousand_line_batch_identical_in_both_runtimes(mp):
    stdin = batch_input(10000)
    a = hexapod("ik", "--batch", stdin=stdin)
    b = hexapod("ik", "--batch", "--runtime", "micropython", stdin=stdin)
    assert a.returncode == b.returncode and a.stdout == b.stdout
    rows = a.stdout.splitlines()
    assert len(rows) == 10000
    solved = [r for r in rows if not r.startswith("unreachable")]
    assert len(solved) > 5000 and all(len(r.split()) == 3 for r in solved)


@pytest.mark.parametrize(
    "argv, error",
    [
        (("ik", "abc", "0", "0"), "x: 'abc' is not a number"),
        (("fk", "0", "0"), "need 3 numbers (theta1 theta2 theta3), got 2"),
        (("ik", "1", "2", "3", "--coxa", "q"), "--coxa: 'q' is not a number"),
    ],
)
def test_bad_input_under_json_is_a_json_error_object(capsys, argv, error):
    # main: nothing on stdout, the message on stderr only
    status, out, err = run(capsys, *argv, "--json")
    assert status == 2 and json.loads(out) == {"error": error}
    assert err == "hexapod: error: %s\n" % error


def test_json_error_object_identical_in_both_runtimes(mp):
    a = hexapod("ik", "abc", "0", "0", "--json")
    b = hexapod("ik", "abc", "0", "0", "--json", "--runtime", "micropython")
    assert (a.returncode, a.stdout, a.stderr) == (b.returncode, b.stdout, b.stderr)
    assert a.stdout == '{"error": "x: \'abc\' is not a number"}\n'
