"""The papers' kinematics tables, reproduced by the integer solver.

Seed 003 Table I uses coxa 3, femur 4.5, tibia 6.2 (cm), no femur offset, x sideways, y
along the leg and z pointing down; its (theta1, theta2, gamma) are our (theta1, theta2,
gamma - 180). Seed 004 Tables 4-9 list seven foot points per leg for Table 3's DH leg.
"""

import json
import math
import os

import pytest

from hexapod.leg import DEFAULT_LIMITS, OK, Leg
from hexapod_host.testing import reference

# x, y, z (cm) -> theta1, theta2, gamma (degrees, "Calculation Results" column)
SEED003_TABLE1 = [
    ((0, 13.7, 0), (0, 0, 180)),
    ((0, 12, -1), (0, 44.81, 114.69)),
    ((0, 11, 2), (0, 33.81, 99.6)),
    ((0, 10, 3), (0, 31.29, 89.29)),
    ((0, 9, 4), (0, 24.91, 83.11)),
    ((-5, 7, 2), (-35.54, 51.62, 65.31)),
    ((-8, 5, 3), (-57.99, 34.99, 81.45)),
    ((-6, 6, 4), (-45, 26.73, 76.95)),
    ((-5, 4, 9), (-51.34, -38.5, 127.4)),
    ((-8, 5, 7), (-57.99, -14.96, 124.63)),
]
SEED003_LEG = (300, 450, 620, 0)  # 0.1 mm

# Seed 004 Tables 4-9 (tests/data/seed004_tables.json), per leg: each axis's row of desired foot
# points (cm), of measured ones and of errors, exactly as printed, one column per point; a leg's
# i-th point is (X desired[i], Y desired[i], Z desired[i]). DH: Table 3's leg, cm.
with open(os.path.join(os.path.dirname(__file__), "data", "seed004_tables.json"), encoding="utf-8") as f:
    _SEED004 = json.load(f)
SEED004_DH = _SEED004["DH"]
SEED004_TABLES = {int(leg): table for leg, table in _SEED004["TABLES"].items()}


def seed004_points(leg):
    """The seven desired foot points of one leg, in cm."""
    t = SEED004_TABLES[leg]
    return list(zip(t["X"][0], t["Y"][0], t["Z"][0], strict=True))


# The one printed value the geometry does not give: row (-8, 5, 3), theta2 = 34.99.
# The exact solve is 34.731 deg; test_seed003_misprint_shown_by_forward_kinematics proves it.
SEED003_MISPRINTS = {(6, 1)}


def seed003_to_ours(p):
    """Seed 003 (x sideways, y out, z down) in cm -> our leg frame in 0.1 mm."""
    x, y, z = p
    return round(y * 100), round(x * 100), round(-z * 100)


@pytest.mark.parametrize("row", range(len(SEED003_TABLE1)))
def test_seed003_table1_row(row):
    p, paper = SEED003_TABLE1[row]
    leg = Leg(coxa=300, femur=450, tibia=620)
    out = [0, 0, 0]
    assert leg.ik(*seed003_to_ours(p), out) == OK
    ours = (out[0] / 100, out[1] / 100, out[2] / 100 + 180)
    exact = reference.ik(*seed003_to_ours(p), *SEED003_LEG)
    exact = (exact[0], exact[1], exact[2] + 180)
    for k in range(3):
        # Ours against the exact solve of the same geometry: the project's bound.
        assert abs(ours[k] - exact[k]) <= 0.02, (row, k, ours, exact)
        if (row, k) in SEED003_MISPRINTS:
            continue
        # The paper's printed two decimals are the exact solve, rounded (half a step).
        assert abs(paper[k] - exact[k]) <= 0.005 + 1e-9, (row, k, paper, exact)
        # Hence ours and the paper agree within both bounds.
        assert abs(ours[k] - paper[k]) <= 0.025, (row, k, ours, paper)


def test_seed003_misprint_shown_by_forward_kinematics():
    """FK of the printed angles misses the target by ~0.3 mm; ours lands on it."""
    (p, paper), row = SEED003_TABLE1[6], 6
    target = seed003_to_ours(p)
    leg = Leg(coxa=300, femur=450, tibia=620)
    out, foot = [0, 0, 0], [0, 0, 0]
    assert leg.ik(*target, out) == OK
    leg.fk(out[0], out[1], out[2], foot)
    assert max(abs(foot[k] - target[k]) for k in range(3)) <= 1
    printed = reference.fk(paper[0], paper[1], paper[2] - 180, *SEED003_LEG)
    miss = math.dist(printed, target)
    assert miss > 2.0, "printed angles land %.2f x 0.1 mm away" % miss  # more than 0.2 mm off
    assert abs(out[1] / 100 - 34.73) <= 0.01 and abs(paper[1] - 34.99) < 1e-9, row


def test_seed004_every_table_point_round_trips():
    g = SEED004_DH
    leg = Leg(coxa=300, femur=850, tibia=1250, femur_offset=320)
    out, foot = [0, 0, 0], [0, 0, 0]
    seen = 0
    for n in SEED004_TABLES:
        for p in seed004_points(n):
            target = tuple(round(v * 100) for v in p)
            assert leg.ik(*target, out) == OK, (n, p, leg.excess)
            leg.fk(out[0], out[1], out[2], foot)
            assert tuple(foot) == target or max(abs(foot[k] - target[k]) for k in range(3)) <= 1, (n, p, foot)
            exact = reference.ik(*p, g["a1"], g["a2"], g["a3"], g["d1"])
            assert max(abs(out[k] / 100 - exact[k]) for k in range(3)) <= 0.02
            # The exact angles land on the point by both forward solvers (seed 004 eq. 1-7).
            for fk in (reference.fk, reference.fk_dh):
                assert math.dist(fk(*exact, g["a1"], g["a2"], g["a3"], g["d1"]), p) < 1e-9
            assert all(DEFAULT_LIMITS[2 * k] <= out[k] <= DEFAULT_LIMITS[2 * k + 1] for k in range(3))
            seen += 1
    assert seen == 42


# Cells whose printed error is not |desired - test|: (leg, axis, column). Leg 3's X test
# row reads one centimetre high from column 3 on; leg 5's Z column 4 lost its minus sign.
SEED004_ERROR_MISPRINTS = {(3, "X", 2), (3, "X", 3), (3, "X", 4), (3, "X", 5), (3, "X", 6)}
SEED004_ERROR_MISPRINTS |= {(3, "Z", 5), (4, "Z", 2), (5, "Z", 3)}


def test_seed004_printed_errors_are_desired_minus_test():
    bad = set()
    for n, table in SEED004_TABLES.items():
        for axis, (desired, measured, error) in table.items():
            for k in range(7):
                if abs(abs(desired[k] - measured[k]) - error[k]) > 1e-9:
                    bad.add((n, axis, k))
    assert bad == SEED004_ERROR_MISPRINTS
