"""Gait changes asked while walking (issue 22 point 2), on the default robot with its servo guard.

switch(a, b, vx, vy, yaw) returns [robot.faults, faulted ticks, info, rows]: info is [ticks from the ask
to the new gait, the walker's held ticks over the whole run after the ask, the smallest margin the tick
reported (0.1 mm), the new gait's cycle and slot ticks, the old gait's cycle ticks]; rows one a tick
from the ask on: [held this tick, gait walked, settling, the tick's margin, the walked vx, vy (0.1 mm/s)
and yaw rate (cdeg/s), then each foot's x, y (0.1 mm,
body frame), down (1/0), its distance from neutral and its reach disc (0.1 mm)]."""

from scenarios.rig import Rig

from hexapod.body import FINE_SHIFT
from hexapod.fixmath import isqrt
from hexapod.stability import NO_SUPPORT


def walking(gait, vx, vy, yaw, ticks):
    """A Rig stood up, walking `gait` at (vx, vy, yaw) for `ticks`."""
    rig = Rig()
    rig.stand()
    rig.robot.set_gait(gait)
    rig.robot.walk(vx, vy, yaw)
    rig.run(ticks)
    return rig


def switch(a, b, vx, vy, yaw, before=600, after=480):
    rig = walking(a, vx, vy, yaw, before)
    robot = rig.robot
    w = rig.w
    old_cycle = w.clock.cycle_ticks
    held0 = w.held
    robot.set_gait(b, wait=False)
    rows = []
    came = -1
    for k in range(after):
        h = w.held
        rig.run(1)
        if came < 0 and w.clock.gait == b:
            came = k + 1
        # (getattr: the same scenario runs on code from before gait changes on the move)
        row = [w.held - h, w.clock.gait, getattr(w, "settling", 0), getattr(robot, "margin", NO_SUPPORT)]
        row += [w.vel[0], w.vel[1], w.vel[2]]
        for i in range(6):
            dx = (w.fx[i] - w.nx[i]) >> FINE_SHIFT
            dy = (w.fy[i] - w.ny[i]) >> FINE_SHIFT
            row += [w.fx[i] >> FINE_SHIFT, w.fy[i] >> FINE_SHIFT, 1 if w.su[i] < 0 else 0]
            row += [isqrt(dx * dx + dy * dy), w.rho[i]]
        rows.append(row)
    info = [came, w.held - held0, getattr(robot, "margin_min", NO_SUPPORT)]
    info += [w.clock.cycle_ticks, w.clock.slot_ticks, old_cycle]
    return [robot.faults, rig.faults, info, rows]


def refusals():
    """Gait changes refused while walking change nothing: [per ask: what it said, state unchanged]."""
    rig = walking(0, 200, 0, 0, 100)
    robot = rig.robot
    w = rig.w

    def snap():
        return [robot.gait, robot.cycle_ms, w.clock.gait, w.pending, w.phase, list(w.cmd), list(w.vel), list(w.su)]

    out = []
    for args in ((7,), ("ripple",), (-1,), (True,), (2, 100), (2, 9000)):
        before = snap()
        try:
            out.append(str(robot.set_gait(*args)))
        except ValueError as e:
            out.append(str(e))
        out.append(snap() == before)
    # A second change while the first is still being checked: CONFIGURING, nothing changed.
    robot.set_gait(3, wait=False)
    before = snap()
    out.append(robot.set_gait(1, wait=False))
    out.append(snap() == before)
    return out


def heap_per_tick(pairs):
    """The most heap bytes one tick took from a change's ask on (the configure's own ticks left out:
    they run the guard's generator), for each (a, b) at 30 mm/s: [[a, b, gait walked, bytes, ticks]]."""
    import gc

    rig = Rig()
    rig.stand()
    robot = rig.robot
    out = []
    for a, b in pairs:
        robot.set_gait(a)
        robot.walk(300, 0, 0)
        rig.run(300)
        robot.set_gait(b, wait=False)
        worst = n = 0
        for _ in range(300):
            was = robot.configuring()
            gc.collect()
            gc.disable()
            m0 = gc.mem_alloc()
            robot.tick(rig.t)
            d = gc.mem_alloc() - m0
            gc.enable()
            rig.t += 20
            if was or robot.configuring():
                continue
            worst = d if d > worst else worst
            n += 1
        out.append([a, b, rig.w.clock.gait, worst, n])
    return out


def interrupted(what):
    """A change into wave asked walking the tripod at 15 mm/s, and `what` at the first tick of its three
    (walker.pending ROOMS: the settings taken, phase 0): "stop" (zero command), "walk" (a new command,
    at the rooms' tick and again at the slot's), "gait" (tetrapod asked, from the table); or
    "stopping": the change asked 40 ticks after a stop, so that the walker stops while it is taken
    (then walks again). Returns
    [the pending value seen each tick from the ask (until 0 for 20 ticks), then at the end: walker
    state, pending, phase, gait walked, held ticks since the ask, feet lifted in the 300 ticks after
    (walk: 0 if none lifted), robot.faults]."""
    rig = walking(0, 150, 0, 0, 400)
    robot = rig.robot
    w = rig.w
    held0 = w.held
    if what == "stopping":
        robot.stop()
        rig.run(40)  # slowed to a stand, the last steps landing
    robot.set_gait(3, wait=False)
    seen = []
    quiet = 0
    acted = 0
    for _ in range(600):
        rig.run(1)
        seen.append(int(w.pending))
        if w.pending >= 2 and not acted:
            acted = 1
            if what == "stop":
                robot.stop()
            elif what == "walk":
                robot.walk(100, 50, 0)
                rig.run(1)
                seen.append(int(w.pending))
                robot.walk(150, 0, 500)
            else:
                robot.set_gait(1, wait=False)
        if what == "stopping":
            acted = acted or not w.pending
        quiet = quiet + 1 if acted and not w.pending else 0
        if quiet >= 20:
            break
    lifted = 0
    if what == "stop" or what == "stopping":
        rig.run(300)
        robot.walk(150, 0, 0)
    su = [0] * 6
    for _ in range(300):
        rig.run(1)
        for i in range(6):
            su[i] |= 1 if w.su[i] >= 0 else 0
    lifted = sum(su)
    return [seen, [w.state, int(w.pending), w.phase, w.clock.gait, w.held - held0, lifted, robot.faults]]
