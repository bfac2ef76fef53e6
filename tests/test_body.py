"""Body pose and the body-frame -> leg-frame transform, against a float reference.

The firmware side is tests/scenarios/body.py."""

import math

import pytest

POSES = [
    (0, 0, 0, 0, 0, 0, 0, 0, 0),
    (300, -200, 150, 0, 0, 0, 0, 0, 0),
    (0, 0, 0, 1200, 0, 0, 0, 0, 0),
    (0, 0, 0, 0, -900, 0, 0, 0, 0),
    (0, 0, 0, 0, 0, 1500, 0, 0, 0),
    (120, 40, -90, 700, -500, 1100, 0, 0, 0),
    (0, 0, 0, 800, 600, -400, 1500, -700, -800),
    (-400, 400, 400, -1500, 1500, -1500, -2000, 2000, 2000),
]

FEET = ((2000, -1500, -800), (-1700, 1900, -600), (0, 2300, -1000))  # body frame, 0.1 mm


def reference(geometry, pose, i, foot):
    """The same transform in floats: R^T (F - c - t) + c, then into leg i's frame."""
    tx, ty, tz, roll, pitch, yaw, cx, cy, cz = pose
    r, p, w = (math.radians(a / 100) for a in (roll, pitch, yaw))
    x, y, z = foot[0] - cx - tx, foot[1] - cy - ty, foot[2] - cz - tz
    x, y = x * math.cos(w) + y * math.sin(w), -x * math.sin(w) + y * math.cos(w)
    x, z = x * math.cos(p) - z * math.sin(p), x * math.sin(p) + z * math.cos(p)
    y, z = y * math.cos(r) + z * math.sin(r), -y * math.sin(r) + z * math.cos(r)
    x, y, z = x + cx, y + cy, z + cz
    a = math.radians(geometry.mount_angle[i] / 100)
    dx, dy = x - geometry.mount_x[i], y - geometry.mount_y[i]
    return (dx * math.cos(a) + dy * math.sin(a), -dx * math.sin(a) + dy * math.cos(a), z)


def test_transform_matches_float_reference(rt):
    import robots.default as d
    from hexapod import geometry

    g = geometry.load(d)
    rows = rt.call("scenarios.body:transform", POSES, FEET)
    assert len(rows) == len(POSES) * 6 * len(FEET)
    k = 0
    worst = 0
    for pose in POSES:
        for i in range(6):
            for foot in FEET:
                want = reference(g, pose, i, foot)
                worst = max(worst, *(abs(rows[k][j] - want[j]) for j in range(3)))
                k += 1
    assert worst <= 1.5  # 0.15 mm: Q15 sines over lever arms of up to 0.4 m


def test_pose_signs(rt):
    # Roll lowers the right side: a right foot ends up relatively higher (z up) in the body frame.
    poses = [[0] * 9, [0, 0, 0, 1000, 0, 0, 0, 0, 0], [0, 0, 0, 0, 1000, 0, 0, 0, 0], [0, 0, 100, 0, 0, 0, 0, 0, 0]]
    got = rt.call("scenarios.body:pose_signs", poses)
    level, rolled, pitched, raised = got
    assert level == [-800, -800]
    assert rolled[0] > -800  # right side down: the right foot is higher relative to the body
    assert pitched[1] > -800  # nose down: the front foot is higher relative to the body
    assert raised == [-900, -900]  # body up 10 mm: feet 10 mm further down
    # By hand, z' = z cos(a) - y sin(a) (roll) or z cos(a) + x sin(a) (pitch), a = 10 degrees:
    # rolled: -80 cos a + 207.5 sin a = -42.75 mm, -80 cos a + 170 sin a = -49.26 mm;
    # pitched: -80 cos a = -78.78 mm, -80 cos a + 180 sin a = -47.53 mm. Within 0.1 mm (Q15 sines).
    for got_z, want_z in zip(rolled + pitched, [-427.5, -492.6, -787.8, -475.3], strict=True):
        assert abs(got_z - want_z) <= 1, (rolled, pitched)


def test_slew_is_bounded_per_tick(rt):
    steps = rt.call("scenarios.body:slew", [400, -400, 300, 1500, -1500, 1000, 2000, -2000, 500])
    n, worst, pose_step, angle_step, settled, pose = steps
    assert settled and pose == [400, -400, 300, 1500, -1500, 1000, 2000, -2000, 500]
    assert worst == [pose_step, angle_step]
    assert n == max(2000 // pose_step, 1500 // angle_step)


BAD_POSES = [
    ([0] * 8, "need 9 values"),
    ([401, 0, 0, 0, 0, 0, 0, 0, 0], "pose x: 401"),
    ([0, -401, 0, 0, 0, 0, 0, 0, 0], "pose y"),
    ([0, 0, 0, 1501, 0, 0, 0, 0, 0], "pose roll: 1501 cdeg"),
    ([0, 0, 0, 0, -1501, 0, 0, 0, 0], "pose pitch"),
    ([0, 0, 0, 0, 0, 99999, 0, 0, 0], "pose yaw"),
    ([0, 0, 0, 0, 0, 0, 2001, 0, 0], "pose centre x"),
    ([0, 0, 0, 0, 0, 0, 0, 0, -2001], "pose centre z"),
    ([0, 0, 1.5, 0, 0, 0, 0, 0, 0], "pose z: need a whole number"),
    ([0, 0, 0, True, 0, 0, 0, 0, 0], "pose roll: need a whole number"),
    ([0, "1", 0, 0, 0, 0, 0, 0, 0], "pose y: need a whole number"),
]


@pytest.mark.parametrize("pose,message", BAD_POSES)
def test_bad_pose_is_refused_and_changes_nothing(pose, message):
    import robots.default as d
    from hexapod import geometry
    from hexapod.body import Body

    b = Body(geometry.load(d))
    b.set_target([10, 0, 0, 0, 0, 0, 0, 0, 0])
    with pytest.raises(ValueError, match=message):
        b.set_target(pose)
    assert list(b.target) == [10, 0, 0, 0, 0, 0, 0, 0, 0]
