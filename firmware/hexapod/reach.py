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

    The swing is the walker's own (trajectory.swing_stroke and swing_shape), every tick, on 8
    directions. Each answer passed that check in full and a step 1.6 mm longer (or the cap)
    failed it: a bisection's answer. The cost is kept down without loosening it: a try stops
    at the first tick past the limit, starting with the direction that failed last; each
    tick's IK serves both of its tick pairs; and each leg first tries the last leg's answer
    and 1.6 mm more (mirror-image legs agree: two tries instead of a bisection's seven).
    About 2,000 IK solves at a 1 s tripod (hexapod bench guard). Off the tick (set_gait,
    set_params, set_pose, set_height), like disc_radii.
    """
    legs = walker.geometry.legs
    buf = [0, 0, 0, 0, 0, 0, 0, 0, 0]
    first = [0]  # the direction to try first: the one that failed last
    worst0 = 0
    guess = RHO_CAP  # the last leg's answer: legs alike (mirror images) get it in two tries
    for i in range(6):
        leg = legs[i]
        j0 = swing_peak(walker, body, leg, i, 0, 0, swing, stance, lift, _UNREACHABLE, buf)
        if j0 > worst0:
            worst0 = j0
        if j0 > limit:
            out[i] = 0  # (a step of nothing is the same swing on every direction)
            continue
        lo = 0
        hi = caps[i]
        g = guess if guess < hi else hi
        if _fits(walker, body, leg, i, g, swing, stance, lift, limit, buf, first):
            lo = g
            if hi - lo > 16:
                if _fits(walker, body, leg, i, g + 16, swing, stance, lift, limit, buf, first):
                    lo = g + 16
                else:
                    hi = g + 16
            else:
                hi = lo
        else:
            hi = g
        while hi - lo > 16:
            mid = (lo + hi) >> 1
            if _fits(walker, body, leg, i, mid, swing, stance, lift, limit, buf, first):
                lo = mid
            else:
                hi = mid
        out[i] = lo  # passed in full; lo + 16 (or the cap) did not
        guess = lo
    return worst0


def _fits(walker, body, leg, i, e, swing, stance, lift, limit, buf, first):
    """True when no tick of leg i's swing stepping e (0.1 mm) on any of 8 directions turns a joint past limit."""
    k0 = first[0]
    for n in range(8):
        k = (k0 + n) & 7
        if swing_peak(walker, body, leg, i, e, k * 4500, swing, stance, lift, limit, buf) > limit:
            first[0] = k
            return False
    return True


def swing_peak(walker, body, leg, i, e, angle, swing, stance, lift, stop, buf):
    """Largest per-tick joint change (cdeg) of leg i's swing stepping e (0.1 mm) along angle
    (cdeg), every tick; returns as soon as a change passes stop (cdeg)."""
    u = step_vector(e, angle, swing, stance, [0, 0, 0, 0])
    worst = 0
    tmp = [0, 0]
    for v in range(swing + 1):
        swing_point(walker, body, i, u, v, swing, lift, tmp, buf)
        # Angles at tick v go to buf[3:6] and [6:9] in turn: the pair (v - 1, v) is both.
        at = 3 if v & 1 else 6
        if leg.ik(buf[0], buf[1], buf[2], buf, at) != OK:
            return _UNREACHABLE
        if v:
            for j in range(3):
                d = buf[3 + j] - buf[6 + j]
                if d < 0:
                    d = -d
                if d > worst:
                    worst = d
                    if d > stop:
                        return d
    return worst


def step_vector(e, angle, swing, stance, out):
    """Half a stance e (0.1 mm) along angle (cdeg), and the stance's carry over one swing, into out (0.1 mm)."""
    ux = (e * cos(angle) + 16384) >> 15
    uy = (e * sin(angle) + 16384) >> 15
    out[0] = ux
    out[1] = uy
    # From S = n - u to T = n + u, carried by C = -2u swing/stance (the stance's ground speed).
    out[2] = -(2 * ux * swing // stance)
    out[3] = -(2 * uy * swing // stance)
    return out


def swing_point(walker, body, i, u, v, swing, lift, tmp, buf):
    """Leg i's foot at tick v of the walker's swing for step_vector u, in the leg's frame, into buf[0:3]."""
    ux = u[0]
    uy = u[1]
    cx = u[2]
    cy = u[3]
    swing_stroke(v, swing, tmp)
    x = -ux + mul_q15(cx, tmp[1]) + mul_q15(2 * ux - cx, tmp[0])
    y = -uy + mul_q15(cy, tmp[1]) + mul_q15(2 * uy - cy, tmp[0])
    swing_shape(v, swing, tmp)
    z = mul_q15(lift, tmp[1])
    body.to_leg(
        i,
        walker.nx[i] + (x << FINE_SHIFT),
        walker.ny[i] + (y << FINE_SHIFT),
        walker.ground + (z << FINE_SHIFT),
        buf,
        0,
    )
