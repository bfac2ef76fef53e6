"""The walk on the real tick, at 1 s cycles without the servo guard (scenarios.rig.unguarded_geometry).

Every scenario returns [robot.faults, the faulted ticks, rows]: rows as test_gait_walk.py reads them."""

from scenarios.rig import Rig, unguarded_geometry

from hexapod import tick


def _standing():
    rig = Rig(unguarded_geometry())
    rig.stand()
    return rig


def _done(rig, rows):
    return [rig.robot.faults, rig.faults, rows]


def _feet(w, keys):
    return [[getattr(w, k)[i] for k in keys] for i in range(6)]


def steady(vx, vy, yaw, settle, ticks, keys, gait=None):
    """Walk (vx, vy, yaw) for settle ticks; rows: the command, then each foot's keys ("su", "fx", ...) a tick."""
    rig = _standing()
    w = rig.w
    if gait is not None:
        rig.robot.set_gait(gait)
    rig.robot.walk(vx, vy, yaw)
    rig.run(settle)
    rows = [list(w.cmd)]
    for _ in range(ticks):
        rig.run(1)
        rows.append(_feet(w, keys))
    return _done(rig, rows)


def swing_ends(gait, vx, vy, yaw):
    """As steady, over a cycle and two ticks: first row [swing ticks, vx, vy, yaw], then [su, fx, fy] a foot."""
    rig = _standing()
    w = rig.w
    rig.robot.set_gait(gait)
    rig.robot.walk(vx, vy, yaw)
    rig.run(150)
    rows = [[w.clock.swing_ticks] + list(w.cmd)]
    for _ in range(w.clock.cycle_ticks + 2):
        rig.run(1)
        rows.append(_feet(w, ("su", "fx", "fy")))
    return _done(rig, rows)


def turn_in_place():
    """Turning on the spot: [body x, body y, [su, fx, fy] a foot] a tick."""
    rig = _standing()
    w = rig.w
    rig.robot.walk(0, 0, -2000)
    rig.run(150)
    rows = []
    for _ in range(60):
        rig.run(1)
        rows.append([w.bx, w.by, _feet(w, ("su", "fx", "fy"))])
    return _done(rig, rows)


def stop(gait):
    """Stop mid-step: [feet in the air at the stop, ticks to stop, cycle ticks], the walker's states,
    each foot [su, offsets from neutral x, y, z], [mode, faults]."""
    rig = _standing()
    robot = rig.robot
    w = rig.w
    robot.set_gait(gait)
    robot.walk(900, -300, 1200)
    states = []
    for _ in range(137):
        rig.run(1)
        states.append(w.state)
    robot.stop()
    air = sum(1 for i in range(6) if w.su[i] >= 0)
    n = 0
    while robot.mode == tick.WALKING and n < 1000:
        rig.run(1)
        states.append(w.state)
        n += 1
    feet = [[w.su[i], w.fx[i] - w.nx[i], w.fy[i] - w.ny[i], w.fz[i] - w.ground] for i in range(6)]
    return _done(rig, [[air, n, w.clock.cycle_ticks], states, feet, [robot.mode, robot.faults]])


def gait_switch():
    """Switch gaits while walking: [target, gait now, ticks waited, feet up before, phase, feet up after] each."""
    rig = _standing()
    w = rig.w
    rig.robot.walk(1000, 0, 0)
    rig.run(113)
    rows = []
    for target in (2, 3, 1, 0):
        rig.robot.set_gait(target)
        before = w.clock.gait
        n = 0
        air = 0
        while w.clock.gait == before:
            air = sum(1 for i in range(6) if w.su[i] >= 0)
            rig.run(1)
            n += 1
        rows.append([target, w.clock.gait, n, air, w.phase, sum(1 for i in range(6) if w.su[i] >= 0)])
        rig.run(57)
    return _done(rig, rows)


def heading():
    """walk_heading(L, theta): [L, theta, half stance ms, command, scale, leg 1's landing dx, dy] each."""
    rig = _standing()
    w = rig.w
    half = w.clock.stance_ticks * 20 // 2
    rows = []
    for length, theta in ((300, 0), (250, 4500), (200, 9000), (280, -13500)):
        rig.robot.walk_heading(length, theta)
        cmd = list(w.cmd)
        rig.run(300)
        # touch-down point of leg 1 relative to its neutral, in 0.1 mm
        while w.su[0] < 0:
            rig.run(1)
        while w.su[0] >= 0:
            rig.run(1)
        rows.append([length, theta, half, cmd, w.scale_permille, (w.fx[0] - w.nx[0]) >> 4, (w.fy[0] - w.ny[0]) >> 4])
    return _done(rig, rows)


def sweeps(left, right):
    """Seed 000's turn by coxa sweeps: [scale, vx, yaw], [left middle coxa's sweep, right middle's]."""
    rig = _standing()
    robot = rig.robot
    w = rig.w
    robot.set_params(step_length=600, cycle_ms=2000)
    robot.walk_sweeps(left, right)
    rows = [[w.scale_permille, w.cmd[0], w.cmd[2]]]
    rig.run(250)
    coxa = {1: [], 4: []}
    for _ in range(w.clock.cycle_ticks):
        rig.run(1)
        for i in (1, 4):
            if w.su[i] < 0:
                coxa[i].append(robot.angles[3 * i])
    rows.append([max(coxa[4]) - min(coxa[4]), max(coxa[1]) - min(coxa[1])])
    return _done(rig, rows)


def beyond_reach():
    """Commands past the reach: [command, scale, scaled command, step, smallest radius] each."""
    rig = _standing()
    w = rig.w
    rows = []
    for cmd in ((3000, 0, 0), (0, -3000, 0), (0, 0, 9000), (2000, 2000, -6000), (500, 0, 0)):
        rig.robot.walk(cmd[0], cmd[1], cmd[2])
        rows.append([list(cmd), w.scale_permille, list(w.cmd), w.step, min(w.rho)])
    return _done(rig, rows)


def no_room():
    """One leg with no room: [scale, command]."""
    w = _standing().w
    w.rho[4] = 0
    w.command(1000, 0, 500)
    return [w.scale_permille, list(w.cmd)]


def bad_calls(calls):
    """While walking, each robot.<method>(*args, **kwargs) of calls: its ValueError's text (or "ACCEPTED");
    last, whether the walk is unchanged."""
    rig = _standing()
    robot = rig.robot
    w = rig.w
    robot.walk(800, 0, 300)
    rig.run(77)

    def snap():
        return [
            robot.mode,
            w.state,
            list(w.cmd),
            w.step,
            w.lift,
            w.clock.gait,
            w.clock.cycle_ms,
            list(robot.body.target),
            w.ground,
        ]

    before = snap()
    rows = []
    for method, args, kwargs in calls:
        try:
            getattr(robot, method)(*args, **kwargs)
            rows.append("ACCEPTED")
        except ValueError as e:
            rows.append(str(e))
    rows.append(snap() == before)
    return _done(rig, rows)


def changes_in_flight():
    """Gait, step and lift changed while walking: which wait for all feet down."""
    rig = _standing()
    robot = rig.robot
    w = rig.w
    robot.walk(1500, 0, 0)
    rig.run(61)
    res = []
    phase = w.phase
    robot.set_gait(0)  # the gait it already walks
    res.append([w.pending, w.phase == phase])
    robot.set_params(step_length=200)  # step length: applies at once, the command rescales
    res.append([w.pending, w.step, w.cmd[0] < 1500])
    robot.set_params(lift_height=400)  # the feet would notice: waits for all feet down
    res.append([w.pending, w.lift, w.next_lift])
    rig.run(60)
    res.append([w.pending, w.lift])
    return res
