"""Gait changes while walking (hexapod.walk.Walker's pending change), without a stop.

A change asked while walking goes in three steps (docs/motion.md, "Changing gait on the move"):

1. fitting: while a foot on the ground lies outside the new gait's stance disc (its reach, step
   and servo-speed radius), the old gait walks on with its steps aimed inside three quarters of
   the new disc (aim_inside) until fits(): a foot far behind would otherwise start the new gait's
   shorter swing from there and turn its joints faster than the servo budget.
2. Then no new swing starts; at the first tick with every foot down the new clock is taken
   (walker._apply, its stroke gain made by the configure job: budget.gain_steps), the swing budget
   and the feet's rooms the next tick and the slot the one after (walker.pending ROOMS, _SLOT): one
   part a tick, so that none takes a Pico frame past 6 ms (docs/pico.md). The feet stay down and
   the body walks on.
3. phase_in: the new clock starts at the slot whose lift order suits the feet, and the body walks
   slower (walker.slow, permille of the command) until every leg has begun its first new swing
   (walker.settling ticks, under one cycle), just enough that no stance foot reaches the edge of
   its disc before it lifts. The new swings aim for the full command.

Units as in hexapod.walk: feet fine (0.1 mm << 4), discs 0.1 mm, rooms in ticks. Off the steady
tick: each runs once a change, fits once a tick while fitting.
"""

import sys
from array import array

from micropython import const

from hexapod.body import FINE, FINE_SHIFT
from hexapod.budget import swing_budget
from hexapod.fixmath import isqrt
from hexapod.gait import TICK_MS

# fixmath's root as machine code where MicroPython has viper (hexapod/_fixmath_viper.py, equal for
# every n fixmath allows: tests/test_rescale.py): a change's rooms take six in one tick.
if sys.implementation.name == "micropython":
    try:  # noqa: SIM105 (no contextlib on MicroPython)
        from hexapod._fixmath_viper import isqrt  # noqa: F811
    except Exception:  # no viper emitter on this build: the plain root stays
        pass

ROOM_MAX = const(1000000)  # a foot that does not move has room without end (ticks)
# walker.pending: 1 while a change waits for every foot down, then its last two parts on the move.
ROOMS = const(2)  # the settings taken: the feet's rooms next tick
_SLOT = const(3)  # the rooms made: the slot next tick
# The stance's slack (0.1 mm) and the ramp's steps a tick (0.1 mm/s, cdeg/s), copied by hand.
_SLACK = const(16)  # hexapod.walk.STANCE_SLACK
_SPEED_STEP = const(40)  # hexapod.walk.SPEED_STEP
_YAW_STEP = const(100)  # hexapod.walk.YAW_STEP


def init(w):
    """The walker's state for changes on the move (its __init__ calls this)."""
    w.goal = array("i", [0, 0, 0])  # the ramp's target: cmd, slow/1000 of it while a change settles
    w.slow = 1000
    w.settling = 0  # ticks left until every leg has begun its first swing of the new gait
    w.fitting = 0  # 1 while the feet are brought inside the pending change's discs
    w._early = 0  # bits: legs whose swing began before the change (fits)
    w._room = array("i", [0] * 6)
    w._keep = array("i", [0] * 12)


def reset(w):
    """A change is taken: no fitting, and no slow-down until phase_in sets one."""
    w.fitting = 0
    w.slow = 1000
    w.settling = 0


def begin(w):
    """A change the feet would notice was taken while walking: pending, fitting where needed."""
    w.pending = 1
    w._early = 0
    for i in range(6):
        if w.su[i] >= 0:
            w._early |= 1 << i  # its swing was aimed before: it may land outside
    w.fitting = 0 if fits(w) else 1
    scale(w)


def scale(w):
    """walker._rescale; while fitting, the steps aimed inside the pending change's discs too (a new
    command while the slot waits makes the rooms again: they are the command's)."""
    if w.pending == _SLOT:
        w.pending = ROOMS
    if w.fitting:
        aim_inside(w)
    else:
        w._rescale()


def goal(w):
    """The ramp's goal: the command, or slow/1000 of it (toward 0) while a change settles."""
    c = w.cmd
    g = w.goal
    k = w.slow
    for j in range(3):
        g[j] = c[j] * k // 1000 if c[j] >= 0 else -(-c[j] * k // 1000)


def after_tick(w, airborne):
    """The end of a walker tick with a change pending or settling (airborne: feet in the air)."""
    if w.settling:
        w.settling -= 1
        if not w.settling and w.slow < 1000:
            w.slow = 1000  # every leg has lifted in the new gait: back to the full command
            goal(w)
    if w.fitting and fits(w):
        w.fitting = 0  # from now on no new swing: the change waits for every foot down
        w._rescale()
    if w.pending and not w.fitting and not airborne:
        # One part a tick (a Pico frame has room for one): the settings, then the feet's rooms, then
        # the slot; no foot lifts meanwhile (walker._maybe_lift), the body walks on.
        if w.pending == 1:
            w._apply()  # pending ROOMS on the move
        elif w.pending == ROOMS:
            swing_budget(w, w.stroke_gain)  # (no swing before the next tick's lifts)
            for i in range(6):
                w._room[i] = stance_room(w, i)  # phase_in's, for the feet where they stand
            w.pending = _SLOT
        else:
            phase_in(w, 1)
            w.pending = 0


def fits(w):
    """1 when every foot on the ground lies inside the pending change's stance disc and no swing
    aimed before the change is still in the air (it may land outside), else 0."""
    for i in range(6):
        if w.su[i] >= 0:
            if w._early >> i & 1:
                return 0
            continue
        lim = w.next_rho[i] if w.next_rho[i] < w.step else w.step
        if 0 < w.next_srho[i] < lim:
            lim = w.next_srho[i]
        lim += _SLACK
        dx = (w.fx[i] - w.nx[i]) >> FINE_SHIFT
        dy = (w.fy[i] - w.ny[i]) >> FINE_SHIFT
        if dx * dx + dy * dy > lim * lim:
            return 0
    return 1


def stance_discs(w, out):
    """Each leg's stance disc (0.1 mm) into out[0:6], as walker._rescale leaves stance_rho: the step
    its reach, step and servo radii allow, the stance's slack more, within its reach (the viper
    rescale writes the same; here, not in walk.py: the VM compiles walk.py in one piece)."""
    rho = w.rho
    srho = w.srho
    step = w.step
    for i in range(6):
        lim = rho[i] if rho[i] < step else step
        if 0 < srho[i] < lim:
            lim = srho[i]  # (no room to step at all: walking is refused, keep the reach)
        lim += _SLACK
        out[i] = lim if lim < rho[i] else rho[i]


def aim_inside(w):
    """The command scaled to both the gait walked and three quarters of the pending one's discs (one
    walker._rescale); the stance discs are the gait walked's (as its _rescale leaves them), so no
    foot now outside the new disc holds the body."""
    srho = w.srho
    keep = w._keep
    stance_discs(w, keep)  # the gait walked's, kept
    for i in range(6):
        keep[i + 6] = srho[i]
        lim = w.next_rho[i] if w.next_rho[i] < w.next_srho[i] else w.next_srho[i]
        # Three quarters: the feet then fit with room to spare for the new lift order.
        lim = lim * 3 >> 2
        if 0 < lim < srho[i]:
            srho[i] = lim
    w._rescale()
    for i in range(6):
        w.stance_rho[i] = keep[i]
        srho[i] = keep[i + 6]


def phase_in(w, old):
    """Start the new clock (every foot down) at the slot that lets the body walk fastest, with the
    rooms (walker._room) made `old` ticks ago by after_tick (the body walked on meanwhile).

    Each stance foot may still move room[i] ticks at the command before it leaves its stance disc;
    at phase p leg i lifts in r = start[i] - p ticks (mod the cycle). The slot chosen has the largest
    slow = min(1000, room * 1000 // r) over the legs; the body's goal is slow/1000 of the command
    for the ticks until the last leg has lifted (settling, at most one cycle)."""
    clock = w.clock
    best = _best_slot(w, old)
    if best < 1000:
        # The ramp takes `lag` ticks to slow from the speed walked to the goal, the feet moving on
        # faster meanwhile: try again with that much less room (the slot may change).
        c = w.cmd
        lag = 0
        for j in range(3):
            d = w.vel[j] - c[j] * best // 1000
            d = (d if d >= 0 else -d) // (_YAW_STEP if j == 2 else _SPEED_STEP) + 1
            if d > lag:
                lag = d
        best = _best_slot(w, lag + old)
    cycle = clock.cycle_ticks
    last = 0
    for i in range(6):
        r = clock.start[i] - w.phase
        if r < 0:
            r += cycle
        if r > last:
            last = r
    w.slow = best
    w.settling = last + 1
    goal(w)


def _best_slot(w, lag):
    """The slowdown (permille) of the best slot with every room `lag` ticks less; phase there."""
    clock = w.clock
    room = w._room
    cycle = clock.cycle_ticks
    best = -1
    p = -clock.slot_ticks
    while p + clock.slot_ticks < cycle:  # (not range: a variable step makes a range object)
        p += clock.slot_ticks
        k = 1000
        for i in range(6):
            r = clock.start[i] - p
            if r < 0:
                r += cycle
            m = room[i] - lag if room[i] > lag else 0
            if r > m and m * 1000 // r < k:
                k = m * 1000 // r
        if k > best:
            best = k
            w.phase = p
    return best


def stance_room(w, i):
    """Ticks leg i's foot (down) may move at the command before it leaves its stance disc; its path
    taken as straight at its velocity now (-v - yaw x p), ROOM_MAX when it does not move."""
    c = w.cmd
    rot = c[2] * 5719 // 1000  # Q15 rad/s (cdeg * pi / 18000 * 2**15)
    px = w.fx[i] >> FINE_SHIFT
    py = w.fy[i] >> FINE_SHIFT
    ux = (-c[0] + (py * rot >> 15)) * (FINE * TICK_MS) // 1000  # the foot's move a tick, fine
    uy = (-c[1] - (px * rot >> 15)) * (FINE * TICK_MS) // 1000
    s = isqrt(ux * ux + uy * uy)
    if s == 0:
        return ROOM_MAX
    dx = (w.fx[i] - w.nx[i]) >> FINE_SHIFT
    dy = (w.fy[i] - w.ny[i]) >> FINE_SHIFT
    along = (dx * ux + dy * uy) // s  # 0.1 mm the foot already is along its move from neutral
    across = (dx * uy - dy * ux) // s
    r = w.stance_rho[i]
    if across * across >= r * r:
        return 0
    left = isqrt(r * r - across * across) - along
    return left * FINE // s if left > 0 else 0
