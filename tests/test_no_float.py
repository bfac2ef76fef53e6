"""No float anywhere in the core (a MicroPython float is a heap object), nor in the drivers the
tick calls: no float literal, no true division, no float(), no math module."""

import ast
import glob
import os

from hexapod_host import FIRMWARE

# The CircuitPython backends wrap Adafruit libraries that speak floats; they are not the tick.
EXEMPT = {"cp_pca9685.py", "cp_hcsr04.py"}
# cp_clock's sleeps hand time.sleep seconds (CircuitPython has no integer sleep); its ticks are integer
# (tests/test_cp_clock.py checks every intermediate stays a small int). The PulseIn ranger is not exempt.
EXEMPT.add("cp_clock.py")


def floats_in(path):
    with open(path) as f:
        tree = ast.parse(f.read(), path)
    found = []
    for node in ast.walk(tree):
        where = "%s:%d" % (os.path.relpath(path, FIRMWARE), getattr(node, "lineno", 0))
        if isinstance(node, ast.Constant) and isinstance(node.value, float | complex):
            found.append("%s float literal %r" % (where, node.value))
        elif isinstance(node, ast.BinOp | ast.AugAssign) and isinstance(node.op, ast.Div):
            found.append("%s true division" % where)
        elif isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "float":
            found.append("%s float()" % where)
        elif isinstance(node, ast.Import | ast.ImportFrom):
            names = [a.name for a in node.names] + [getattr(node, "module", None) or ""]
            if "math" in names or "cmath" in names:
                found.append("%s imports math" % where)
    return found


def test_core_and_tick_drivers_have_no_float():
    files = glob.glob(os.path.join(FIRMWARE, "hexapod", "*.py")) + glob.glob(os.path.join(FIRMWARE, "drivers", "*.py"))
    files += [os.path.join(FIRMWARE, "runner.py")]
    files = [f for f in files if os.path.basename(f) not in EXEMPT]
    assert len(files) > 15
    found = [hit for f in sorted(files) for hit in floats_in(f)]
    assert not found, "\n".join(found)


def test_the_scan_sees_floats(tmp_path):
    bad = tmp_path / "bad.py"
    bad.write_text("import math\nx = 1.5\ny = 3 / 2\nz = float(3)\nw = 4\nw /= 2\n")
    assert len(floats_in(str(bad))) == 5
