"""Integer IK against the float oracle over dense sweeps of the workspace, and FK(IK(p)) = p.

Goal (issue 2): every joint within 0.02 degree of the exact answer for the same integer
foot position, including within 0.1 mm of full extension and of the minimum reach; the
forward kinematics of the answer returns the point within 0.1 mm (one unit) per axis.

One singular set is left out: with femur == tibia the minimum reach is zero, and a foot
closer than 0.1 mm to the femur joint leaves the femur angle undefined (any theta2 reaches
it), so no solver can be "accurate" there; the round trip is still checked for it.
"""

import math
import random

import pytest

from hexapod.leg import OK, Leg
from hexapod_host.testing import reference

OPEN = (-18000, 18000, -18000, 18000, -18000, 18000)

# (coxa, femur, tibia, femur_offset) in 0.1 mm
GEOMETRIES = {
    "seed003": (300, 450, 620, 0),
    "seed004": (300, 850, 1250, 320),
    "seed001": (150, 800, 1300, 0),
    "max-250+250": (500, 2500, 2500, 0),
    "max-coxa-offset": (1500, 2500, 2500, 1500),
    "long-femur": (400, 2500, 900, -600),
    "tiny": (0, 100, 120, 0),
}


def sweep_points(coxa, femur, tibia, off, seed):
    """A regular grid over the reach plus thin random shells at both reach limits."""
    reach, lo = femur + tibia, abs(femur - tibia)
    pts = set()
    for t1 in range(-180, 180, 6):
        a = math.radians(t1 + 0.37)
        for i in range(41):
            for k in range(41):
                h = -reach + 2 * reach * i / 40
                v = -reach + 2 * reach * k / 40
                r = h + coxa
                if r >= 0:
                    pts.add((round(r * math.cos(a)), round(r * math.sin(a)), round(v + off)))
    rnd = random.Random(seed)
    for n in range(24000):
        c = reach - rnd.uniform(0, 1.0) if n % 2 else max(lo, 1.0) + rnd.uniform(0, 1.0)
        a, p = rnd.uniform(-math.pi, math.pi), rnd.uniform(-math.pi / 2, math.pi / 2)
        r = c * math.cos(p) + coxa
        if r >= 0:
            pts.add((round(r * math.cos(a)), round(r * math.sin(a)), round(c * math.sin(p) + off)))
    return sorted(pts)


@pytest.mark.parametrize("name", sorted(GEOMETRIES))
def test_ik_matches_float_oracle_and_round_trips(name):
    coxa, femur, tibia, off = GEOMETRIES[name]
    leg = Leg(coxa=coxa, femur=femur, tibia=tibia, femur_offset=off, limits=OPEN)
    out, foot = [0, 0, 0], [0, 0, 0]
    worst, worst_fk, solved, near_edge = 0.0, 0, 0, 0
    for x, y, z in sweep_points(coxa, femur, tibia, off, seed=len(name)):
        ref = reference.ik(x, y, z, coxa, femur, tibia, off)
        code = leg.ik(x, y, z, out)
        c = math.hypot(math.hypot(x, y) - coxa, z - off)
        if ref is None:
            assert code != OK, (x, y, z)
            continue
        assert code == OK, (x, y, z, code, leg.excess)
        solved += 1
        near_edge += c > femur + tibia - 1 or c < abs(femur - tibia) + 1
        leg.fk(out[0], out[1], out[2], foot)
        worst_fk = max(worst_fk, abs(foot[0] - x), abs(foot[1] - y), abs(foot[2] - z))
        if c < 1.0:
            continue
        for got, want in zip(out, ref, strict=True):
            err = abs(got / 100 - want)
            worst = max(worst, min(err, 360 - err))
    assert solved > 40000 and near_edge > 5000, (solved, near_edge)
    assert worst <= 0.02, "%s: worst joint error %.4f deg" % (name, worst)
    assert worst_fk <= 1, "%s: FK(IK(p)) off by %d x 0.1 mm" % (name, worst_fk)


def test_exact_full_extension_and_folded_points():
    leg = Leg(coxa=300, femur=850, tibia=1250, femur_offset=320, limits=OPEN)
    out = [0, 0, 0]
    assert leg.ik(300 + 2100, 0, 320, out) == OK and out == [0, 0, 0]
    assert leg.ik(0, 300 + 2100, 320, out) == OK and out == [9000, 0, 0]
    assert leg.ik(300, 0, 320 - 2100, out) == OK and out == [0, -9000, 0]
    # Folded: the foot 40 mm (the minimum reach) straight out; tibia back along the femur.
    assert leg.ik(300 + 400, 0, 320, out) == OK and out[2] == -18000


def test_two_solvers_agree_on_forward_kinematics():
    """mithi's habit: golden cases checked by two solvers (closed form and DH matrices)."""
    rnd = random.Random(5)
    for _ in range(2000):
        t = (rnd.uniform(-90, 90), rnd.uniform(-90, 90), rnd.uniform(-179, -1))
        if 30 + 85 * math.cos(math.radians(t[1])) + 125 * math.cos(math.radians(t[1] + t[2])) <= 0:
            continue  # foot behind the coxa axis: IK answers with the coxa turned round instead
        a = reference.fk(*t, 30, 85, 125, 32)
        b = reference.fk_dh(*t, 30, 85, 125, 32)
        assert max(abs(p - q) for p, q in zip(a, b, strict=True)) < 1e-9
        back = reference.ik(*a, 30, 85, 125, 32)
        assert max(abs(p - q) for p, q in zip(back, t, strict=True)) < 1e-6
