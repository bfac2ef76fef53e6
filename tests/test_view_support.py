"""The view's support polygon and centre of mass (view/support.py) against hand-worked cases,
and where the scene puts them in the world."""

import math

import pytest
from test_view import DESCRIBED, hand_snapshot

from hexapod_host.view.scene import geometry
from hexapod_host.view.support import MASSES, centre_of_mass, support

ORIGIN = (0.0, 0.0, 0.0)


def still_legs(feet):
    """Legs whose four points all sit at their foot: only the foot's place counts."""
    return [[f, f, f, f] for f in feet]


def test_the_robot_files_masses():
    # robots/default.py: body 600 g, six coxa servos of 55 g in it; links 15, 20, 25 g, foot 2 g.
    assert MASSES == (930, (15, 55, 20, 55, 25, 2.0))


def test_centre_of_mass_of_one_leg_out_by_hand():
    # Leg 1 from the origin: femur joint 30 mm out, knee 100 mm out, foot 100 mm below the knee;
    # the other legs folded onto the origin. Moments about x (g mm): coxa link 15 x 15, femur
    # servo 55 x 30, femur link 20 x 65, tibia servo 55 x 100, tibia link 25 x 100, foot 2 x 100
    # = 11375; about z: tibia link 25 x -50, foot 2 x -100 = -1450. Mass 930 + 6 x 172 = 1962 g.
    leg1 = [ORIGIN, (30.0, 0.0, 0.0), (100.0, 0.0, 0.0), (100.0, 0.0, -100.0)]
    x, y, z = centre_of_mass([leg1] + still_legs([ORIGIN] * 5))
    assert x == pytest.approx(11375 / 1962, abs=1e-9)  # 5.7977 mm
    assert y == 0.0
    assert z == pytest.approx(-1450 / 1962, abs=1e-9)  # -0.7390 mm


# A tripod (legs 1, 3, 5 down; 1 RF, 3 RR, 5 LM: clockwise seen from above) and three feet up.
TRIPOD = [True, False, True, False, True, False]
FEET = [(200.0, -100.0, 0.0), (0.0, -250.0, 30.0), (-200.0, -100.0, 0.0)]
FEET += [(-150.0, 150.0, 30.0), (0.0, 200.0, 0.0), (150.0, 150.0, 30.0)]


def test_a_tripods_margin_by_hand():
    # Body 900 g at the origin, each foot 50 g (nothing else): the centre of mass is
    # 50 x (sum of the six feet) / 1200 = (0, 50 x 50 / 1200) = (0, 2.0833) mm. The nearest edge
    # is leg 1 -> leg 3, the line y = -100: 102.08 mm (the firmware's 0.1 mm: 102.1). The edge
    # 3 -> 5 is farther: |200 x 102.083 - 300 x 200| / sqrt(200^2 + 300^2) = 109.8 mm.
    s = support(still_legs(FEET), TRIPOD, weights=(900, (0, 0, 0, 0, 0, 50)))
    assert s["com"][0] == 0.0 and s["com"][1] == pytest.approx(2.0833, abs=1e-4)
    assert s["margin_mm"] == 102.1 and s["state"] == "ok"
    assert s["polygon"] == [[200.0, -100.0], [-200.0, -100.0], [0.0, 200.0]]


@pytest.mark.parametrize(
    "edge_y, margin, state",
    [(-10.0, 10.0, "near"), (-19.9, 19.9, "near"), (-20.0, 20.0, "ok"), (10.0, -10.0, "out")],
)
def test_near_the_edge_and_outside(edge_y, margin, state):
    # The body's mass alone at the origin; the back edge of the triangle edge_y away.
    feet = [(200.0, edge_y, 0.0), ORIGIN, (-200.0, edge_y, 0.0), ORIGIN, (0.0, 300.0, 0.0), ORIGIN]
    s = support(still_legs(feet), TRIPOD, weights=(1000, (0,) * 6))
    assert s["margin_mm"] == margin and s["state"] == state


def test_two_feet_down_is_no_support():
    s = support(still_legs(FEET), [True, False, False, False, True, False], weights=(1000, (0,) * 6))
    assert s["margin_mm"] is None and s["state"] == "none" and len(s["polygon"]) == 2


def test_the_scene_puts_the_support_on_the_ground_in_the_world():
    # test_view's hand snapshot: the body at (1000, 500) mm facing +y, only feet 1 and 5 down.
    g = geometry(DESCRIBED, hand_snapshot())
    sup = g["support"]
    assert sup["state"] == "none"
    # Leg 1's foot, body frame (87.5 + 73.26486, -77.5 - 73.26486) -> world (1000 - y, 500 + x).
    assert sup["polygon"][0] == pytest.approx([1150.76486, 660.76486, 0.0], abs=1e-3)
    x, y, z = sup["com"]
    bx, by, bz = centre_of_mass(hand_snapshot()["legs"])
    assert [x, y, z] == pytest.approx([1000 - by, 500 + bx, 50.5 + bz], abs=1e-9)
    assert sup["com_ground"] == pytest.approx([x, y, 0.0], abs=1e-9)


def test_a_standing_robot_holds_its_centre_of_mass_well_inside():
    # The simulator's robot standing on six feet: the robot file is left-right mirrored, so the
    # centre of mass is on the body's x axis; every edge is farther than NEAR_MM.
    from hexapod_host.view.sim import SimSource
    from hexapod_host.wall import world

    src = SimSource(world.load("wall"), 12, seed=0, disturb=False)
    try:
        snap = src.snapshot()  # frame 0: standing at the robot file's height
    finally:
        src.close()
    s = support(snap["legs"], snap["stance"])
    assert all(snap["stance"]) and s["state"] == "ok" and s["margin_mm"] > 50
    assert math.isclose(s["com"][1], 0.0, abs_tol=0.05)
