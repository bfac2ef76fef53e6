"""Seed 000's turns: a walk command from the coxa sweeps the paper gives.

Seed 000 turns right by swinging the left coxas 45 degrees and the right ones 10 degrees.
`sweep_command` finds the (vx, yaw rate) whose stance makes the middle legs' coxas sweep
exactly that (a bisection on the turning radius, and for each radius on the speed), so the
paper's turn is one command among all the others; the engine itself turns properly about
any centre, and yaw alone pivots about the body centre. Off the tick (it allocates a little).
"""

from hexapod.body import FINE_SHIFT
from hexapod.fixmath import atan2, mul_q15, to_cdeg
from hexapod.limits import SPEED_MAX, YAW_RATE_MAX, is_whole


def coxa_sweep(walker, i, vx, w):
    """Leg i's coxa travel (cdeg, >= 0) over one stance at (vx, 0, w), no body pose."""
    xy = [0, 0]
    walker.aim_for(vx, 0, w)
    walker.target(i, xy)
    a = _coxa_angle(walker, i, xy[0], xy[1])
    walker.aim_for(-vx, 0, -w)
    walker.target(i, xy)
    b = _coxa_angle(walker, i, xy[0], xy[1])
    d = a - b
    if d > 18000:
        d -= 36000
    elif d < -18000:
        d += 36000
    return d if d >= 0 else -d


def _coxa_angle(walker, i, x, y):
    g = walker.geometry
    dx = (x >> FINE_SHIFT) - g.mount_x[i]
    dy = (y >> FINE_SHIFT) - g.mount_y[i]
    c = g.mount_cos[i]
    s = g.mount_sin[i]
    return to_cdeg(atan2(mul_q15(dy, c) - mul_q15(dx, s), mul_q15(dx, c) + mul_q15(dy, s)))


def sweep_command(walker, left, right, out):
    """(vx, yaw rate) that swings the left middle coxa by `left` and the right one by `right`
    cdeg per stance, into out[0:2]: seed 000's turns (right turn: left 45, right 10 degrees).

    The body then circles a centre on the side of the smaller sweep, as the paper's robot
    does; the engine's own turns (yaw_rate alone) pivot about the body centre.
    """
    for name, v in (("left", left), ("right", right)):
        if not is_whole(v) or v < 0 or v > 9000:
            raise ValueError("%s sweep: %r is outside 0..9000 (cdeg)" % (name, v))
    big = left if left >= right else right
    small = right if left >= right else left
    if big == 0:
        out[0] = out[1] = 0
        return out
    # Legs: the middle leg on the big side (leg 5 LM for a right turn) and the other one.
    ib = 4 if left >= right else 1
    js = 1 if left >= right else 4
    sign = -1 if left >= right else 1  # a right turn is clockwise: negative yaw
    lo = abs(walker.geometry.mount_y[js]) + walker.geometry.neutral_reach + 10
    hi = 1000000
    vx = 0
    w = 0
    for _ in range(40):
        radius = (lo + hi) >> 1
        # For this turning radius, the forward speed that gives the big sweep.
        a = 0
        b = SPEED_MAX
        for _ in range(24):
            m = (a + b) >> 1
            if coxa_sweep(walker, ib, m, sign * (m * 5730 // radius)) < big:
                a = m
            else:
                b = m
        vx = b
        w = sign * (vx * 5730 // radius)
        if w < -YAW_RATE_MAX or w > YAW_RATE_MAX:
            lo = radius
            continue
        # Too small a sweep on the inner side means too tight a turn.
        if coxa_sweep(walker, js, vx, w) < small:
            lo = radius
        else:
            hi = radius
        if hi - lo <= 1:
            break
    out[0] = vx
    out[1] = w
    return out
