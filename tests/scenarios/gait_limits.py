"""The planner's reach at the extremes and the tripod's stability margin, without the servo guard."""

from scenarios.rig import TICK_MS, stand, unguarded_geometry

from hexapod import tick
from hexapod.stability import NO_SUPPORT, support_margin


def sweep(cases, commands):
    """Each case (gait, step, lift, cycle, pose): random commands at the limits; a row a case:
    [case, set_pose's code, ticks, angles outside their limits, faults, refused walks, mode, held]."""
    g = unguarded_geometry()
    lim = g.limits
    seed = [12345]

    def rnd(n):
        # A small LCG so both runtimes draw the same numbers.
        seed[0] = (seed[0] * 1103515245 + 12345) & 0x3FFFFFFF
        return seed[0] % n

    def pick(limit):
        k = rnd(4)
        return limit if k == 0 else (-limit if k == 1 else (0 if k == 2 else rnd(2 * limit + 1) - limit))

    rows = []
    for case in cases:
        gait, step, lift, cycle, pose = case
        robot = tick.Robot(g, tick.default_servos(g), tick.FrameBuffer())
        t = stand(robot)
        code = robot.set_pose(*pose)
        while not robot.body.settled():
            robot.tick(t)
            t += TICK_MS
        robot.set_gait(gait)
        robot.set_params(step_length=step, lift_height=lift, cycle_ms=cycle)
        outside = 0
        ticks = 0
        refused = 0
        for _ in range(commands):
            if robot.walk(pick(3000), pick(3000), pick(9000)) != 0:
                refused += 1
            for _ in range(1 + rnd(45)):
                robot.tick(t)
                t += TICK_MS
                ticks += 1
                a = robot.angles
                for j in range(18):
                    lo = lim[2 * (j % 3)]
                    if a[j] < lo or a[j] > lim[2 * (j % 3) + 1]:
                        outside += 1
        robot.stop()
        n = 0
        while robot.mode == tick.WALKING and n < 2000:
            robot.tick(t)
            t += TICK_MS
            n += 1
        rows.append([case, code, ticks, outside, robot.faults, refused, robot.mode, robot.walker.held])
    return rows


def margin(gait):
    """Walking at nominal speed: [scale, command, the smallest support margin over a cycle]."""
    g = unguarded_geometry()
    robot = tick.Robot(g, tick.default_servos(g), tick.FrameBuffer())
    w = robot.walker
    t = stand(robot)
    robot.set_gait(gait)
    half = w.clock.stance_ticks * 20 // 2
    robot.walk(w.step * 1000 // half, 0, 0)  # nominal: a full step length per half stance
    for _ in range(300):
        robot.tick(t)
        t += TICK_MS
    xs = [0] * 6
    ys = [0] * 6
    down = [0] * 6
    worst = None
    for _ in range(w.clock.cycle_ticks):
        robot.tick(t)
        t += TICK_MS
        for i in range(6):
            xs[i] = w.fx[i] >> 4
            ys[i] = w.fy[i] >> 4
            down[i] = 1 if w.su[i] < 0 else 0
        m = support_margin(xs, ys, down)
        worst = m if worst is None or m < worst else worst
    return [w.scale_permille, list(w.cmd), worst]


def margin_geometry():
    """support_margin on a hexagon: all six down, a tripod, a tripod and a point outside, two feet."""
    xs = [1000, 0, -1000, -1000, 0, 1000]
    ys = [-1000, -1500, -1000, 1000, 1500, 1000]
    return [
        support_margin(xs, ys, [1, 1, 1, 1, 1, 1]),
        support_margin(xs, ys, [1, 0, 1, 0, 1, 0]),
        support_margin(xs, ys, [1, 0, 1, 0, 1, 0], 0, -1200),
        support_margin(xs, ys, [1, 1, 0, 0, 0, 0]) == NO_SUPPORT,
    ]
