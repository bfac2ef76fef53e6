"""The tripod's stability margin, without the servo guard, and the support margin's geometry."""

from scenarios.rig import TICK_MS, stand, unguarded_geometry

from hexapod import tick
from hexapod.stability import NO_SUPPORT, support_margin


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
