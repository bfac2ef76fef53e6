"""The control tick on a default robot: pulses, overruns, refusals, posture moves, clamps."""

import standing
from scenarios.rig import Rig

from hexapod import tick
from hexapod.servo import ServoMap


def pulses_while_walking():
    """Forty walking ticks: [angles, pulses, each servo map's width for its angle, frames, ticks] a tick."""
    rig = Rig()
    robot = rig.robot
    rig.stand()
    robot.walk(900, 200, 500)
    rows = []
    for _ in range(40):
        rig.run(1)
        raw = [robot.servos[k].raw(robot.angles[k]) for k in range(18)]
        rows.append([list(robot.angles), list(rig.frame.pulses), raw, rig.frame.frames, robot.ticks])
    return rows


def overruns():
    """[late ticks, worst interval, overruns after the clock wraps, walker phases] of a walk on a jumpy clock."""
    rig = Rig()
    robot = rig.robot
    rig.stand()
    robot.walk(1000, 0, 0)
    base = robot.overruns
    phases = []
    for now in (100000, 100020, 100040, 100075, 100095, 100195, 100215):
        robot.tick(now)
        phases.append(rig.w.phase)
    late = robot.overruns - base
    # time.ticks_ms() wraps at 2**30: 20 ms across the wrap is on time.
    robot.tick(2**30 - 10)
    robot.tick(10)
    return [late, robot.worst_interval_ms, robot.overruns - base, phases]


def _moving(rig):
    rig.robot.stand_up()
    rig.run(3)


def _walking(rig):
    rig.stand()
    rig.robot.walk(800, 0, 0)
    rig.run(20)


def _posing(rig):
    rig.stand()
    rig.robot.set_pose(roll=1000)
    rig.run(2)


def _low(rig):
    rig.stand()
    rig.robot.set_pose(0, 0, -400, 1500, 0, 0, 0, 0, 0)
    rig.run(40)


def _leaning(rig):
    rig.stand()
    rig.robot.set_params(lift_height=100)
    rig.robot.set_pose(0, 0, -300, 800, 0, 0, 0, 0, 0)
    rig.run(40)
    rig.robot.walk(500, 0, 0)
    rig.run(10)


STATES = {
    "sitting": None,
    "moving": _moving,
    "walking": _walking,
    "posing": _posing,
    "standing": Rig.stand,
    "low": _low,
    "leaning": _leaning,
}


def refusal(state, method, args, kwargs, code):
    """Bring a robot to state, call robot.method(*args, **kwargs): [its code, tick.<code>, nothing changed, pulses]."""
    rig = Rig()
    robot = rig.robot
    w = rig.w
    if STATES[state] is not None:
        STATES[state](rig)

    def snap():
        return [
            robot.mode,
            w.state,
            list(w.cmd),
            list(robot.body.target),
            w.ground,
            list(w.fx),
            list(w.fz),
            robot.posture.sets,
            w.lift,
            w.next_lift,
            list(w.rho),
            w.pending,
        ]

    before = snap()
    result = getattr(robot, method)(*args, **kwargs)
    return [result, getattr(tick, code), before == snap(), list(rig.frame.pulses)]


def stand_up_from_anywhere():
    """From a sprawled leg set to standing: per-tick [largest joint step, largest foot step], the feet's
    offsets from the neutral stance at the end, [faults, ticks]."""
    rig = Rig()
    robot = rig.robot
    w = rig.w
    # A sprawled leg set: every leg somewhere else, declared as joint angles.
    robot.assume_angles(
        [
            3000,
            2000,
            -4000,
            -2500,
            -3000,
            -6000,
            0,
            4000,
            -9000,
            2000,
            -1000,
            -12000,
            1500,
            3000,
            -3000,
            -3000,
            1000,
            -8000,
        ]
    )
    prev = [None, None]  # angles and feet of the frame before
    steps = []

    def frame(n):
        rig.run(1)
        feet = [[w.fx[i], w.fy[i], w.fz[i]] for i in range(6)]
        a, f = prev
        if a is not None:
            da = max(abs(robot.angles[k] - a[k]) for k in range(18))
            df = max(max(abs(feet[i][j] - f[i][j]) for j in range(3)) for i in range(6))
            steps.append([da, df])
        prev[0] = list(robot.angles)
        prev[1] = feet

    standing.stand(robot, frame)
    final = [[w.fx[i] - w.nx[i], w.fy[i] - w.ny[i], w.fz[i] - w.ground] for i in range(6)]
    return [steps, final, [robot.faults, robot.ticks]]


def sit_relax_and_height():
    """Height change, walk, stop, relax, stand again: the rows test_tick checks."""
    rig = Rig()
    robot = rig.robot
    w = rig.w
    rig.stand()
    rows = [[robot.set_height(1000), robot.mode]]
    worst = [0]
    prev = list(robot.angles)

    def frame(n):
        rig.run(1)
        worst[0] = max(worst[0], max(abs(robot.angles[k] - prev[k]) for k in range(18)))
        for k in range(18):
            prev[k] = robot.angles[k]

    n = standing.until_standing(robot, frame)
    rows.append([n, worst[0], [w.fz[i] >> 4 for i in range(6)]])
    rows.append([robot.walk(1000, 0, 0)])
    rig.run(100)
    robot.stop()
    rig.run(200)
    rows.append([robot.relax(), robot.mode])
    rig.run(200)
    rows.append([robot.mode, list(rig.frame.pulses), robot.faults])
    rows.append([robot.stand_up(), robot.mode])
    rig.run(200)
    rows.append([robot.mode, [w.fz[i] >> 4 for i in range(6)], robot.faults])
    return rows


def clamped_frame():
    """A femur servo recalibrated past the standing angle: [held, faults, fault leg, no frame sent,
    pulses kept, the code's text]."""
    rig = Rig()
    robot = rig.robot
    frame = rig.frame
    rig.stand()
    good = list(frame.pulses)
    frames = frame.frames
    # Recalibrate one femur servo so tightly that the standing angle is outside it.
    robot.servos[4] = ServoMap(centre_us=1500, min_us=1400, max_us=1500)
    code = robot.tick(rig.t)
    return [
        code == tick.FRAME_SERVO,
        robot.faults,
        robot.fault_leg,
        frame.frames == frames,
        list(frame.pulses) == good,
        tick.describe(code),
    ]


def _ordinary(robot, n):
    # Speed and turn change every tick, through the command path as a PID loop would.
    robot.walk(600 + (n * 7) % 900, (n * 13) % 400 - 200, ((n * 37) % 4000) - 2000)


def _extreme(robot, n):
    s = 1 if (n // 50) % 2 else -1
    robot.walk(3000 * s, -3000, -9000 * s)


def _walking_heap(rig, steer, ticks):
    """The heap bytes ticks walking ticks leave allocated, steer(robot, n) commanding each; then a stop."""
    import gc

    robot = rig.robot
    gc.collect()
    gc.disable()
    a = gc.mem_alloc()
    for n in range(ticks):
        steer(robot, n)
        robot.tick(rig.t)
        rig.t += 20
    walk_bytes = gc.mem_alloc() - a
    gc.enable()
    robot.stop()
    while robot.mode == tick.WALKING:
        rig.run(1)
    return walk_bytes


def steady_tick_heap():
    """MicroPython only (gc.mem_alloc): the heap bytes a stand-up and each gait's walking ticks leave
    allocated: ["stand", bytes], then [gait, bytes, faults] for every gait at ordinary commands
    changing every tick, then again at the extremes."""
    import gc

    rig = Rig()
    robot = rig.robot
    rows = []
    robot.stand_up()
    rig.run(5)
    frame = lambda n: rig.run(1)  # noqa: E731 (made before the weighing: a closure is heap)
    gc.collect()
    gc.disable()
    a = gc.mem_alloc()
    standing.until_standing(robot, frame)
    stand_bytes = gc.mem_alloc() - a
    gc.enable()
    rows.append(["stand", stand_bytes])
    for gait in range(4):
        robot.set_gait(gait)
        robot.walk(800, 100, 1200)
        rig.run(150)
        rows.append([gait, _walking_heap(rig, _ordinary, 400), robot.faults])
    # The extremes: longest cycle, largest step and lift, the commands at their limits.
    robot.set_params(step_length=600, lift_height=600, cycle_ms=5000)
    for gait in range(4):
        robot.set_gait(gait)
        robot.walk(3000, -3000, 9000)
        rig.run(100)
        rows.append([gait, _walking_heap(rig, _extreme, 300), robot.faults])
    return rows


def soft_start(move, before):
    """A move ("stand_up" or "sit_down") out of RELAXED; before: "power_up" (a new robot) or
    "relax" (stood, then relaxed). Per frame until the move ends (at most 400 frames): the
    servos given a pulse, as a bit mask (bit k: servo k), and whether any pulse changed from the
    frame before. Returns (masks, changed, frames to the mode the move ends in, that mode)."""
    rig = Rig()
    robot = rig.robot
    if before == "relax":
        rig.stand()
        robot.relax()
        while robot.mode != tick.RELAXED:
            rig.run(1)
    getattr(robot, move)()
    masks, changed, last = [], [], None
    n = 0
    while robot.mode == tick.MOVING and n < 400:
        rig.run(1)
        n += 1
        p = rig.frame.pulses
        mask = 0
        for k in range(18):
            if p[k]:
                mask |= 1 << k
        masks.append(mask)
        changed.append(last is not None and list(p) != last)
        last = list(p)
    return masks, changed, n, robot.mode
