"""The swing's servo budget: how far a swing may carry its foot in its ticks (hexapod.walk's planner).

The servo guard (hexapod.reach.servo_steps) passes the longest steady step, half a stance srho
(0.1 mm), whose swing keeps every joint within the servos' speed budget: from n - srho to n + srho
around the neutral point n, the ground carrying the foot C = 2 srho w / st back over its w swing
ticks (st stance ticks). A swing from lift-off S to touch-down T moves the foot
x(u) = S + C u / w + (T - S - C) stroke(u) (hexapod.trajectory.swing_stroke), so its fastest tick
moves it (C + D g) / w, with D = T - S - C the stroke and g = w x the stroke's largest share in one
tick. `swing_max` is |C + D g| of the guard's swing; a swing asking more lands short, on the line
from S + C toward T, and the next swings make the rest up (a steady step below srho has room).

This is the swing half of issue 22's planner; the stance half is the ease band (walker.band, off_band()):
a stance foot may walk on past its step to its reach disc, but not further from or nearer to its coxa
than the guard's swings lifted off (eased() shortens a swing from there, and a steady walk's feet then
drifted out and held every cycle). The budget alone keeps every joint within the datasheet budget on
the reversal schedule (tests/test_servo_guard.py) and the tetrapod under the stall in MuJoCo
(tests/test_physics_reversals.py). docs/physics.md, "Issue 22". Units: 0.1 mm, feet in body.FINE
units; nothing allocates (the walker's tick).
"""

from micropython import const

from hexapod.body import FINE_SHIFT
from hexapod.fixmath import isqrt
from hexapod.gait import RIPPLE
from hexapod.trajectory import swing_stroke

# A lift-off this far (0.1 mm) further from or nearer to the coxa axis than the guard's swings reached
# gets half the budget: a leg more stretched or folded turns its joints more for each mm (measured,
# the hold undone: the wave's tibia at 304 cdeg a tick against 282 without it, from 47 mm out).
SWING_EASE = const(300)
# A steady stance may end this much (0.1 mm) past its scaled step (hexapod.walk.STANCE_SLACK, 16: the
# guard's answer is good to 1.6 mm); its swing gets the budget of a half stance srho + STANCE_SLACK / 2
# (the old hold's longest swing, 2 srho + STANCE_SLACK) and no easing inside STANCE_SLACK, so that a
# steady walk's swings are never shortened (they were 0.3 mm a swing, and the feet drifted out).
_LIFT_SLACK = const(8)
EASE_DEAD = const(16)
# gain_steps' swing ticks a job step: ~0.65 ms on the emulated Pico (80 us a tick), under one of the
# servo guard's IK solves (~0.8 ms), the other steps a configure job takes.
_GAIN_TICKS = const(8)


def gain_steps(walker, w, s):
    """The stroke's largest share of one tick in a w-tick swing, times w (Q15), into walker.next_gain
    (s: two words of scratch): a generator yielding every _GAIN_TICKS ticks, a configure job's steps
    (a gait change on the move then finds it made: 3.4 ms of a Pico frame for the ripple's swing)."""
    last = 0
    best = 0
    for u in range(1, w + 1):
        swing_stroke(u, w, s)
        if s[0] - last > best:
            best = s[0] - last
        last = s[0]
        if u % _GAIN_TICKS == 0:
            yield
    walker.next_gain = best * w


def swing_budget(walker, g=0):
    """walker.stroke_gain (Q15, gain_steps' for its clock's swing; g when given) and swing_max (0.1 mm,
    per leg) for its clock and srho in force, and walker.band: the coxa axes' x, y (0.1 mm), then
    band_in, band_out (0.1 mm^2) a leg each (its words 24-41, the lift-off commands, are not made here)."""
    w = walker.clock.swing_ticks
    st = walker.clock.stance_ticks
    if not g:
        for _ in gain_steps(walker, w, walker._stroke):
            pass
        g = walker.next_gain
    walker.stroke_gain = g
    for i in range(6):
        r = walker.srho[i] + _LIFT_SLACK
        # The guard's swing: D = 2 r (st + w) / st forward, C = 2 r w / st back.
        walker.swing_max[i] = (2 * r * (st + w) // st * g >> 15) - 2 * r * w // st
        # The ease band: between these squared distances from the coxa axis a lift-off keeps its whole
        # budget (eased(): the neutral reach +- srho + EASE_DEAD). The walker holds a stance foot from
        # going further outside (off_band): a swing from there lands short, and the next stance would
        # end further out again (docs/physics.md, issue 22: the feet drifted out and held every cycle).
        # (No new names: a MicroPython function of more than 11 locals + stack slots takes its frame
        # from the heap, and a gait change on the move calls this from the tick.)
        r += EASE_DEAD - _LIFT_SLACK
        st = walker.geometry.neutral_reach
        walker.band[i] = walker.geometry.mount_x[i]
        walker.band[i + 6] = walker.geometry.mount_y[i]
        walker.band[i + 12] = (st - r) * (st - r) if st > r else 0
        walker.band[i + 18] = (st + r) * (st + r)
        st = walker.clock.stance_ticks


def off_band(walker, i):
    """1 when leg i's stance foot moved to (ax[i], ay[i]) (body frame, fine) lies outside its ease band
    and further out of it than the foot is now (fx, fy), else 0 (Walker._stance and its viper twin);
    0 also for a ripple foot the command turned away from (turned())."""
    b = walker.band
    x = (walker.ax[i] >> FINE_SHIFT) - b[i]
    y = (walker.ay[i] >> FINE_SHIFT) - b[i + 6]
    r = x * x + y * y
    if b[i + 12] <= r <= b[i + 18]:
        return 0
    x = (walker.fx[i] >> FINE_SHIFT) - b[i]
    y = (walker.fy[i] >> FINE_SHIFT) - b[i + 6]
    x = x * x + y * y
    if r > x if r > b[i + 18] else r < x:
        return 1 - turned(walker, i)
    return 0


def turned(walker, i):
    """1 when the ripple walks and the command now (walker.cmd) turns more than 60 degrees away from
    the one leg i's foot lifted for (walker.band[24:42], written by Walker._maybe_lift), else 0.

    Such a foot landed for another command (a reversal, a swap of forward and sideways): its stance
    runs across or back along its old one, and the band would hold the body for it until it lifts
    (on each side the ripple's other two legs swing first). It may walk on to its reach disc instead;
    its next swing, lifting outside the band, is eased (eased(): shorter, within the servo budget). A
    foot that lifted for the command it walks is held at the band as before, so steady walks keep their
    place (docs/physics.md, issue 22: the feet drifted out when the band held nothing). The turn
    counts as the arc a foot at the mean neutral radius sweeps (233.7 mm: 0.4 x cdeg/s in 0.1 mm/s)."""
    if walker.clock.gait != RIPPLE:
        return 0
    k = walker.band
    i += 24
    v = walker.cmd
    a = k[i] * v[0] + k[i + 6] * v[1] + (k[i + 12] * 2 // 5) * (v[2] * 2 // 5)
    n = isqrt(k[i] * k[i] + k[i + 6] * k[i + 6] + (k[i + 12] * 2 // 5) * (k[i + 12] * 2 // 5))
    m = isqrt(v[0] * v[0] + v[1] * v[1] + (v[2] * 2 // 5) * (v[2] * 2 // 5))
    # cos(angle) < 1/2 (joystick stream: 30, 45 or 60 degrees hold the same 40 ticks, 90 degrees 78); |vx|,
    # |vy| <= 3,000 and 0.4 |yaw| <= 3,600: n, m < 5,600 and every product a board's small int
    return 1 if n and m and 2 * a < n * m else 0


def in_budget(walker, i, t, cv):
    """Pull leg i's touch-down point t (fine) toward where the ground takes its lift-off point
    (carry cv[2:4], fine) until |C + D g| fits its budget (eased): 1 when t was moved (then also
    kept in the reach disc), else 0 (hexapod/_walk_viper.py's swings is the same in viper)."""
    sx = walker.sx[i]
    sy = walker.sy[i]
    dx = (t[0] - sx - cv[2]) >> FINE_SHIFT  # the stroke D, 0.1 mm
    dy = (t[1] - sy - cv[3]) >> FINE_SHIFT
    bx = dx * walker.stroke_gain >> 15
    by = dy * walker.stroke_gain >> 15
    b = isqrt(bx * bx + by * by)
    if b == 0:
        return 0
    # |C + k b| <= v: k |b| <= sqrt(v^2 - C_across^2) - C_along, C's parts across b and along it.
    a = ((cv[2] >> FINE_SHIFT) * bx + (cv[3] >> FINE_SHIFT) * by) // b
    bx = cv[2] >> FINE_SHIFT
    by = cv[3] >> FINE_SHIFT
    v = eased(walker, i)
    v = v * v - (bx * bx + by * by - a * a)
    v = isqrt(v) - a if v > 0 else 0  # the room for k |b|
    if v >= b:
        return 0
    if v < 0:
        v = 0
    t[0] = sx + cv[2] + (dx * v // b << FINE_SHIFT)
    t[1] = sy + cv[3] + (dy * v // b << FINE_SHIFT)
    walker._in_reach(i, t)
    return 1


def eased(walker, i):
    """Leg i's swing budget (0.1 mm) for its lift-off point: swing_max within srho of the neutral
    reach from the coxa axis (where the guard's swings were), less beyond (half at SWING_EASE more)."""
    g = walker.geometry
    x = (walker.sx[i] >> FINE_SHIFT) - g.mount_x[i]
    y = (walker.sy[i] >> FINE_SHIFT) - g.mount_y[i]
    e = isqrt(x * x + y * y) - g.neutral_reach
    if e < 0:
        e = -e
    e -= walker.srho[i] + EASE_DEAD
    if e > 0:
        return walker.swing_max[i] * SWING_EASE // (SWING_EASE + e)
    return walker.swing_max[i]
