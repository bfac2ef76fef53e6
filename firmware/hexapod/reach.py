"""Reach discs: how far each foot may go from its neutral point, found by leg IK.

A foot's disc is the largest circle around its neutral point (body frame, under a body
pose) on which the leg solves, joint limits included, at ground height, half the lift and
the full lift: 12 directions at 3 heights per try, a bisection on the radius, then a 6 %
margin. The walker keeps every foot inside its disc. This runs when a pose, height or walk
parameter is set (it costs up to about 1,700 IK solves), never in the tick.
"""

from micropython import const

from hexapod.body import FINE_SHIFT
from hexapod.fixmath import cos, mul_q15, sin
from hexapod.leg import OK
from hexapod.trajectory import swing_shape, swing_stroke

RHO_CAP = const(1000)  # no disc is searched beyond this radius, 0.1 mm
_UNREACHABLE = const(1048576)  # a "joint change" that marks a swing the leg cannot make


def disc_radii(walker, body, lift, out):
    """Reach disc radius (0.1 mm) of each of walker's neutral feet under `body`'s pose and a lift (0.1 mm), into out."""
    legs = walker.geometry.legs
    buf = [0, 0, 0, 0, 0, 0]
    for i in range(6):
        lo = 0
        hi = RHO_CAP
        if not _disc_ok(walker, body, legs[i], i, 0, lift, buf):
            out[i] = 0
            continue
        while hi - lo > 8:
            mid = (lo + hi) >> 1
            if _disc_ok(walker, body, legs[i], i, mid, lift, buf):
                lo = mid
            else:
                hi = mid
        out[i] = lo - (lo >> 4)  # keep a 6 % margin inside the last radius that passed
    return out


def _disc_ok(walker, body, leg, i, r, lift, buf):
    """True when leg i solves (IK, joint limits) on 12 points of the circle r at 3 heights."""
    z1 = walker.ground + (lift << FINE_SHIFT)
    for k in range(12):
        a = k * 3000
        x = walker.nx[i] + ((r * cos(a) + 1024) >> 11)  # r (0.1 mm) * Q15 -> fine units
        y = walker.ny[i] + ((r * sin(a) + 1024) >> 11)
        for z in (walker.ground, (walker.ground + z1) >> 1, z1):
            body.to_leg(i, x, y, z, buf, 0)
            if leg.ik(buf[0], buf[1], buf[2], buf, 3) != OK:
                return False
    return True


def servo_radii(walker, body, swing, stance, lift, limit, caps, out):
    """How far (0.1 mm, half a stance) each foot may step before its swing asks a joint to turn
    more than `limit` cdeg in one tick, for swings of `swing` ticks after stances of `stance`
    ticks at a lift (0.1 mm); into out, each at most caps[i] (the reach discs). Returns the largest per-tick joint
    change of a swing straight up and down (no step at all): above limit, no step is possible.

    The swing is the walker's own (trajectory.swing_stroke and swing_shape) on 8 directions
    (at most 31 tick pairs each), the step found by bisection to 1.6 mm. Up to about 20,000
    IK solves: run off the tick (set_gait, set_params, set_pose, set_height), like disc_radii.
    """
    legs = walker.geometry.legs
    buf = [0, 0, 0, 0, 0, 0, 0, 0, 0]
    worst0 = 0
    for i in range(6):
        j0 = _swing_peak(walker, body, legs[i], i, 0, 0, swing, stance, lift, buf)
        if j0 > worst0:
            worst0 = j0
        if j0 > limit:
            out[i] = 0
            continue
        lo = 0
        hi = caps[i]
        if _peak_all(walker, body, legs[i], i, hi, swing, stance, lift, limit, buf) <= limit:
            out[i] = hi
            continue
        while hi - lo > 16:
            mid = (lo + hi) >> 1
            if _peak_all(walker, body, legs[i], i, mid, swing, stance, lift, limit, buf) <= limit:
                lo = mid
            else:
                hi = mid
        out[i] = lo
    return worst0


def _peak_all(walker, body, leg, i, e, swing, stance, lift, limit, buf):
    """The largest per-tick joint change over 8 step directions (stops at the first past limit)."""
    worst = 0
    for k in range(8):
        j = _swing_peak(walker, body, leg, i, e, k * 4500, swing, stance, lift, buf)
        if j > worst:
            worst = j
            if j > limit:
                break
    return worst


def _swing_peak(walker, body, leg, i, e, angle, swing, stance, lift, buf):
    """Largest per-tick joint change (cdeg) of leg i's swing stepping e (0.1 mm) along angle (cdeg)."""
    ux = (e * cos(angle) + 16384) >> 15  # 0.1 mm
    uy = (e * sin(angle) + 16384) >> 15
    # From S = n - u to T = n + u, carried by C = -2u swing/stance (the stance's ground speed).
    cx = -(2 * ux * swing // stance)
    cy = -(2 * uy * swing // stance)
    n = swing if swing <= 30 else 30
    worst = 0
    sh = [0, 0]
    st = [0, 0]
    for k in range(n):
        u = k if swing <= 30 else k * swing // 30
        for v in (u, u + 1):
            swing_stroke(v, swing, st)
            swing_shape(v, swing, sh)
            x = -ux + mul_q15(cx, st[1]) + mul_q15(2 * ux - cx, st[0])
            y = -uy + mul_q15(cy, st[1]) + mul_q15(2 * uy - cy, st[0])
            z = mul_q15(lift, sh[1])
            body.to_leg(
                i,
                walker.nx[i] + (x << FINE_SHIFT),
                walker.ny[i] + (y << FINE_SHIFT),
                walker.ground + (z << FINE_SHIFT),
                buf,
                0,
            )
            if leg.ik(buf[0], buf[1], buf[2], buf, 6 if v == u else 3) != OK:
                return _UNREACHABLE
        for j in range(3):
            d = buf[3 + j] - buf[6 + j]
            if d < 0:
                d = -d
            if d > worst:
                worst = d
    return worst
