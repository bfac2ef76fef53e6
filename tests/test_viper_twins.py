"""The viper twins follow one rule (docs/viper.md): MODULE's twin is _MODULE_viper.py beside it; only
the twins (and the rp2 sender, flash.RP2_ONLY) hold viper code; a plain module imports viper code in
one form only, at its top; and every constant a twin copies by hand names its source after its # and
still equals it. Whether each twin computes what its plain code does is the equality tests' job
(tests/test_leg_viper.py, test_tick_viper.py, test_rescale.py, test_pca9685_viper.py)."""

import ast
import importlib
import os
import re

from hexapod_host import FIRMWARE, ROOT
from hexapod_host.serial import flash

# NAME = const(VALUE)  # SOURCE: a hand copy; SOURCE is hexapod.mod.NAME, or an expression of such names.
COPY = re.compile(r"^(\w+) = const\((.+)\)  # ((?:hexapod|drivers)\.\w+\.\w+.*)$")


def sources():
    """{board path: text} of every .py under firmware/."""
    out = {}
    for root, _, files in os.walk(FIRMWARE):
        for f in files:
            if f.endswith(".py"):
                path = os.path.join(root, f)
                with open(path) as fh:
                    out[os.path.relpath(path, FIRMWARE).replace(os.sep, "/")] = fh.read()
    return out


def twins(files):
    return sorted(p for p in files if re.fullmatch(r"(\w+/)?_\w+_viper\.py", p))


def test_each_twin_lies_beside_its_module_and_only_twins_hold_viper_code():
    files = sources()
    found = twins(files)
    assert len(found) >= 6, found  # fixmath, leg, body, walk, tick; drivers/pca9685
    for twin in found:
        folder, name = os.path.split(twin)
        plain = os.path.join(folder, name[1:-9] + ".py").replace(os.sep, "/")
        assert plain in files, (twin, plain)
    viper = sorted(p for p, text in files.items() if "@micropython.viper" in text)
    assert viper == sorted(found + list(flash.RP2_ONLY))
    # flash keeps exactly these off CircuitPython drives
    assert sorted(flash.VIPER) == viper


def _names(imports):
    return {a.asname or a.name for n in imports for a in n.names}


def _is_fallback(node, bound):
    """The one form: `if sys.implementation.name == "micropython":` holding only `try:` blocks of
    from-imports, each with one `except Exception:` that sets the names it imports back to None
    (all but those bound already by the module's imports: walk.py's sin stands in for fixmath's)."""
    if not isinstance(node, ast.If) or node.orelse:
        return False
    if ast.unparse(node.test) != "sys.implementation.name == 'micropython'":
        return False
    for t in node.body:
        if not isinstance(t, ast.Try) or t.orelse or t.finalbody or len(t.handlers) != 1:
            return False
        if not all(isinstance(s, ast.ImportFrom) for s in t.body):
            return False
        h = t.handlers[0]
        if ast.unparse(h.type) != "Exception" or len(h.body) != 1:
            return False
        unbound = _names(t.body) - bound  # none: the plain function stays (`pass`)
        if _sets_none(h.body[0]) != unbound or not unbound and not isinstance(h.body[0], ast.Pass):
            return False
    return True


def _sets_none(node):
    """The names of `a = b = None`, else an empty set."""
    if isinstance(node, ast.Assign) and ast.unparse(node.value) == "None":
        return {ast.unparse(t) for t in node.targets}
    return set()


def test_plain_modules_import_viper_code_in_one_form_at_their_top():
    files = sources()
    found = twins(files)
    viper_modules = {p[:-3].replace("/", ".") for p in found + list(flash.RP2_ONLY)}
    users = []
    for path, text in sorted(files.items()):
        if path in found or path in flash.RP2_ONLY:
            continue  # the twins import each other plainly: they run only where viper does
        tree = ast.parse(text)
        uses = [n for n in ast.walk(tree) if isinstance(n, ast.ImportFrom) and n.module in viper_modules]
        if not uses:
            continue
        users.append(path)
        body = tree.body
        k = next(k for k, n in enumerate(body) if isinstance(n, ast.If))  # the module's first if
        head = body[: k - 1]  # before it: the docstring and the imports only, then `a = b = None`
        for n in head:
            docstring = isinstance(n, ast.Expr) and isinstance(n.value, ast.Constant)
            assert docstring or isinstance(n, (ast.Import, ast.ImportFrom)), (path, ast.unparse(n))
        bound = _names(n for n in body[:k] if isinstance(n, ast.ImportFrom))
        assert _is_fallback(body[k], bound), path
        inside = [n for n in ast.walk(body[k]) if isinstance(n, ast.ImportFrom)]
        assert all(n in inside for n in uses), path  # every import of viper code is in it
        assert _sets_none(body[k - 1]) == _names(inside) - bound, path
    assert users == [
        "drivers/pca9685.py",
        "drivers/stream.py",
        "hexapod/gaitswitch.py",
        "hexapod/leg.py",
        "hexapod/stability.py",
        "hexapod/tick.py",
        "hexapod/walk.py",
    ], users


def _value(node, names):
    """An int expression: literals, + - * << >> and (in a source) dotted names looked up in names."""
    if isinstance(node, ast.Constant) and isinstance(node.value, int):
        return node.value
    if isinstance(node, ast.Attribute):
        return names(ast.unparse(node))
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
        return -_value(node.operand, names)
    if isinstance(node, ast.BinOp):
        ops = {ast.Add: int.__add__, ast.Sub: int.__sub__, ast.Mult: int.__mul__}
        ops.update({ast.LShift: int.__lshift__, ast.RShift: int.__rshift__})
        return ops[type(node.op)](_value(node.left, names), _value(node.right, names))
    raise AssertionError("not a constant expression: " + ast.unparse(node))


def _lookup(dotted):
    module, name = dotted.rsplit(".", 1)
    value = getattr(importlib.import_module(module), name)  # CPython keeps even _private consts
    assert isinstance(value, int) and not isinstance(value, bool), dotted
    return value


def test_hand_copied_constants_equal_their_sources():
    files = sources()
    copies = []
    for path, text in sorted(files.items()):
        for line in text.splitlines():
            m = COPY.match(line)
            if m:
                name, value, source = m.groups()
                copies.append((path, name, value, source))
            elif path in twins(files) and re.match(r"\w+ = const\(", line):
                raise AssertionError("%s: %r copies a constant without naming its source" % (path, line))
    assert len(copies) >= 31, copies  # _leg_viper 18, _walk_viper 10, _tick_viper 3
    wrong = []
    for path, name, value, source in copies:
        mine = _value(ast.parse(value, mode="eval").body, None)
        theirs = _value(ast.parse(source, mode="eval").body, _lookup)
        if mine != theirs:
            wrong.append((path, name, mine, source, theirs))
    assert not wrong, wrong


def test_a_changed_source_is_caught(monkeypatch):
    from hexapod import walk

    monkeypatch.setattr(walk, "REPLAN_STEP", walk.REPLAN_STEP + 1)
    try:
        test_hand_copied_constants_equal_their_sources()
    except AssertionError as e:
        assert "_REPLAN" in str(e)
    else:
        raise AssertionError("a changed REPLAN_STEP went unnoticed")


def test_docs_list_every_twin_with_a_test_that_exists():
    with open(os.path.join(ROOT, "docs", "viper.md")) as f:
        text = f.read()
    rows = {}
    for line in text.splitlines():
        m = re.match(r"\| `([\w/]+\.py)` \|", line)
        if m:
            rows[m.group(1)] = line
    assert sorted(rows) == twins(sources())
    for twin, row in rows.items():
        named = re.findall(r"`(tests/test_\w+\.py)`", row)
        assert named, twin
        for test in named:
            assert os.path.isfile(os.path.join(ROOT, test)), (twin, test)
