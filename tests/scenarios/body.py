"""hexapod.body on robots/default.py: the body-frame -> leg-frame transform, pose signs, the slew."""

import robots.default as d
from hexapod import geometry
from hexapod.body import ANGLE_STEP, POSE_STEP, Body


def transform(poses, feet):
    """to_leg (0.1 mm) of each foot (0.1 mm, body frame) for each leg at each pose, in that order."""
    b = Body(geometry.load(d))
    out = [0, 0, 0]
    rows = []
    for pose in poses:
        b.set_target(list(pose))
        b.jump()
        for i in range(6):
            for foot in feet:
                b.to_leg(i, foot[0] << 4, foot[1] << 4, foot[2] << 4, out, 0)
                rows.append(list(out))
    return rows


def pose_signs(poses):
    """[right middle foot's z, right front foot's z] in their leg frames at each pose (feet 80 mm down)."""
    rows = transform(poses, [(0, -2075, -800), (1800, -1700, -800)])
    # transform's 12 rows a pose: leg i's two feet at 2i, 2i + 1. Leg 1 is the right middle one
    # (its foot the first), leg 0 the right front (its foot the second).
    return [[rows[12 * p + 2][2], rows[12 * p + 1][2]] for p in range(len(poses))]


def slew(target):
    """[slew steps to target, [largest step of x/y/z/centre, of roll/pitch/yaw], POSE_STEP, ANGLE_STEP,
    settled, the pose at the end]."""
    b = Body(geometry.load(d))
    b.set_target(list(target))
    prev = list(b.pose)
    worst = [0, 0]
    n = 0
    while b.slew():
        n += 1
        for k in range(9):
            step = abs(b.pose[k] - prev[k])
            j = 1 if 3 <= k < 6 else 0
            worst[j] = max(worst[j], step)
        prev = list(b.pose)
    return [n, worst, POSE_STEP, ANGLE_STEP, b.settled(), list(b.pose)]
