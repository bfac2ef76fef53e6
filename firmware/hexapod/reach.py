"""Reach discs: how far each foot may go from its neutral point, found by leg IK.

A foot's disc is the largest circle around its neutral point (body frame, under a body
pose) on which the leg solves, joint limits included, at ground height, half the lift and
the full lift: 12 directions at 3 heights per try, a bisection on the radius, then a 6 %
margin. The walker keeps every foot inside its disc. This runs when a pose, height or walk
parameter is set (it costs up to about 1,700 IK solves), never in the tick.
"""

from micropython import const

from hexapod.body import FINE_SHIFT
from hexapod.fixmath import cos, sin
from hexapod.leg import OK

RHO_CAP = const(1000)  # no disc is searched beyond this radius, 0.1 mm


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
