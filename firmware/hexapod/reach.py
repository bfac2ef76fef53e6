"""Reach discs: how far each foot may go from its neutral point, found by leg IK.

A foot's disc is the largest circle around its neutral point (body frame, under a body
pose) on which the leg solves, joint limits included, at ground height, half the lift and
the full lift: 12 directions at 3 heights per try, a bisection on the radius, then a 6 %
margin. The walker keeps every foot inside its disc. This runs when a pose, height or walk
parameter is set (it costs up to about 1,700 IK solves), or a few solves a tick (disc_steps).
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
    for _ in disc_steps(walker, body, lift, out):
        pass
    return out


def disc_steps(walker, body, lift, out):
    """disc_radii one IK solve at a time: a generator that yields after each solve (hexapod.tick
    spreads a configure over frames this way); out holds the radii once it is exhausted.

    Each try solves 12 points of the circle at 3 heights and stops at the first that fails; a
    try of radius 0 that fails leaves the leg no disc. Allocates its buffer when started and
    nothing after."""
    legs = walker.geometry.legs
    buf = [0, 0, 0, 0, 0, 0]
    g = walker.ground
    z1 = g + (lift << FINE_SHIFT)
    zm = (g + z1) >> 1
    for i in range(6):
        leg = legs[i]
        lo = 0
        hi = RHO_CAP
        r = 0
        while True:
            ok = 1
            for k in range(12):
                a = k * 3000
                x = walker.nx[i] + ((r * cos(a) + 1024) >> 11)  # r (0.1 mm) * Q15 -> fine units
                y = walker.ny[i] + ((r * sin(a) + 1024) >> 11)
                for h in range(3):
                    body.to_leg(i, x, y, g if h == 0 else zm if h == 1 else z1, buf, 0)
                    code = leg.ik(buf[0], buf[1], buf[2], buf, 3)
                    yield
                    if code != OK:
                        ok = 0
                        break
                if not ok:
                    break
            if r == 0:
                if not ok:
                    lo = -1  # not even the neutral point: no disc
                    break
            else:
                if ok:
                    lo = r
                else:
                    hi = r
            if hi - lo <= 8:
                break
            r = (lo + hi) >> 1
        out[i] = 0 if lo < 0 else lo - (lo >> 4)  # keep a 6 % margin inside the last radius that passed


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
    set_params, set_pose, set_height), like disc_radii, or spread over frames (servo_steps).
    """
    peak = [0]
    for _ in servo_steps(walker, body, swing, stance, lift, limit, caps, out, peak):
        pass
    return peak[0]


def servo_steps(walker, body, swing, stance, lift, limit, caps, out, peak):
    """servo_radii one IK solve at a time: a generator that yields after each solve; out holds
    the radii and peak[0] the no-step peak once it is exhausted. Allocates nothing once made:
    its buffers are the walker's (guard_buf, guard_tmp), and the swing is written out here, not
    called (a call of this many arguments takes its frame from the heap on MicroPython)."""
    legs = walker.geometry.legs
    buf = walker.guard_buf
    tmp = walker.guard_tmp
    first = 0  # the direction to try first: the one that failed last
    worst0 = 0
    guess = RHO_CAP  # the last leg's answer: legs alike (mirror images) get it in two tries
    g0 = walker.ground
    for i in range(6):
        leg = legs[i]
        nx = walker.nx[i]
        ny = walker.ny[i]
        lo = 0
        hi = caps[i]
        g = guess if guess < hi else hi
        # Tries, in order: the swing with no step (-1: one direction, never stopped early),
        # the last leg's answer (0), 1.6 mm more (1), then the bisection (2); 3: answered.
        stage = -1
        e = 0
        while stage < 3:
            fits = 1
            for n in range(1 if stage < 0 else 8):
                k = 0 if stage < 0 else (first + n) & 7
                stop = _UNREACHABLE if stage < 0 else limit
                # step_vector and swing_point, written out.
                ux = (e * cos(k * 4500) + 16384) >> 15
                uy = (e * sin(k * 4500) + 16384) >> 15
                cx = -(2 * ux * swing // stance)
                cy = -(2 * uy * swing // stance)
                worst = 0
                for v in range(swing + 1):
                    swing_stroke(v, swing, tmp)
                    x = -ux + mul_q15(cx, tmp[1]) + mul_q15(2 * ux - cx, tmp[0])
                    y = -uy + mul_q15(cy, tmp[1]) + mul_q15(2 * uy - cy, tmp[0])
                    swing_shape(v, swing, tmp)
                    z = mul_q15(lift, tmp[1])
                    body.to_leg(i, nx + (x << FINE_SHIFT), ny + (y << FINE_SHIFT), g0 + (z << FINE_SHIFT), buf, 0)
                    # Angles at tick v go to buf[3:6] and [6:9] in turn: the pair (v - 1, v) is both.
                    code = leg.ik(buf[0], buf[1], buf[2], buf, 3 if v & 1 else 6)
                    yield
                    if code != OK:
                        worst = _UNREACHABLE
                        break
                    if v:
                        for j in range(3):
                            d = buf[3 + j] - buf[6 + j]
                            if d < 0:
                                d = -d
                            if d > worst:
                                worst = d
                        if worst > stop:
                            break
                if stage < 0:
                    if worst > worst0:
                        worst0 = worst
                    if worst > limit:
                        fits = -1  # (a step of nothing is the same swing on every direction)
                elif worst > limit:
                    first = k
                    fits = 0
                    break
            if fits < 0:
                lo = 0
                stage = 4
            elif stage < 0:
                stage = 0
                e = g
            elif stage == 0:
                if fits:
                    lo = g
                    if hi - lo > 16:
                        stage = 1
                        e = g + 16
                        continue
                    hi = lo
                else:
                    hi = g
                stage = 2
            elif stage == 1:
                if fits:
                    lo = e
                else:
                    hi = e
                stage = 2
            elif fits:
                lo = e
            else:
                hi = e
            if stage == 2:
                if hi - lo > 16:
                    e = (lo + hi) >> 1
                else:
                    stage = 3
        out[i] = lo  # passed in full; lo + 16 (or the cap) did not
        if stage == 3:
            guess = lo
    peak[0] = worst0


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


# -- the guard table ------------------------------------------------------------------
#
# The servo guard's answers for a robot file's own settings, made on the host.
#
# A configure's reach discs (reach.disc_steps) and servo radii (reach.servo_steps) cost thousands
# of IK solves: 2.5 s on a Pico, for the same answers every time the robot is powered up or
# changes to a gait at its robot file's settings. robots/NAME_guard.py keeps those answers
# (`python -m hexapod_host.guard_table NAME` writes it; tests/test_guard_table.py checks each entry against
# the live guard, bit for bit). An entry is used only for a level body (no pose) at the exact
# height, lift, gait, cycle, step and reach discs it was made for, and only when the robot file
# is the one it was made from (ROBOT, compared whole): anything else runs the live guard.
#
# The table's fields (lengths 0.1 mm, ms, cdeg a tick):
#     ROBOT = robot_key(geometry) of the robot file it was made from
#     DISCS = ((height, lift, (rho x6)), ...)
#     SERVO = ((gait, cycle_ms, lift, step, height, (rho x6), peak, (srho x6), stroke gain), ...)


def robot_key(geometry):
    """Everything of a Geometry the guard's answers depend on, as one tuple of integers."""
    leg = geometry.legs[0]
    key = [leg.coxa, leg.femur, leg.tibia, leg.femur_offset, geometry.neutral_reach, geometry.servo_step]
    key.extend(geometry.limits)
    for i in range(6):
        key.append(geometry.mount_x[i])
        key.append(geometry.mount_y[i])
        key.append(geometry.mount_angle[i])
    return tuple(key)


def find_table(geometry):
    """robots/NAME_guard.py for this geometry when it was made from the same robot file, else None."""
    try:
        table = __import__("robots.%s_guard" % geometry.name, None, None, ("ROBOT",))
    except ImportError:
        return None
    if tuple(table.ROBOT) != robot_key(geometry):
        return None  # made from another robot file: the live guard answers
    return table


def table_discs(table, body, ground, lift, out):
    """The reach discs for a level body at ground (fine) and lift into out; False when the table has none."""
    if not body.level:
        return False
    height = -ground >> FINE_SHIFT
    for row in table.DISCS:
        if row[0] == height and row[1] == lift:
            rho = row[2]
            for i in range(6):
                out[i] = rho[i]
            return True
    return False


def table_servo(table, walker, gait, cycle_ms, lift, step, rho):
    """The servo radii, the no-step peak and the swing's stroke gain into walker._srho, _peak and
    next_gain (hexapod.budget.gain_steps') for the walker's level pose_body at its ground; False
    when the table has no entry for exactly these settings."""
    body = walker.pose_body
    if body is None or not body.level:
        return False
    height = -walker.ground >> FINE_SHIFT
    for row in table.SERVO:
        if row[0] == gait and row[1] == cycle_ms and row[2] == lift and row[3] == step and row[4] == height:
            r = row[5]
            same = True
            for i in range(6):
                if r[i] != rho[i]:
                    same = False
            if same:
                walker._peak[0] = row[6]
                walker.next_gain = row[8]
                for i in range(6):
                    walker._srho[i] = row[7][i]
                return True
    return False
