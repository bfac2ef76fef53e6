"""The planner never asks for an unreachable foot: a sweep over the whole command range, every
gait, extreme parameters and poses, checks all 18 angles every tick. And the tripod's
static stability margin at nominal speed."""

import ast

from hexapod_host.testing.runtimes import UNGUARDED_GEOMETRY

# (Source text, not a scenario: test_tick_ranges.py runs it under an instrumented core.)
# The planner's reach at the extremes (every gait at 1 s too), without the servo guard, which
# refuses most of these settings (test_servo_guard.py).
SWEEP = (
    UNGUARDED_GEOMETRY
    + """
from hexapod import tick
from scenarios.rig import stand
lim = g.limits
seed = [12345]
def rnd(n):
    # A small LCG so both runtimes draw the same numbers.
    seed[0] = (seed[0] * 1103515245 + 12345) & 0x3FFFFFFF
    return seed[0] % n
def pick(limit):
    k = rnd(4)
    return limit if k == 0 else (-limit if k == 1 else (0 if k == 2 else rnd(2 * limit + 1) - limit))
for case in CASES:
    gait, step, lift, cycle, pose = case
    robot = tick.Robot(g, tick.default_servos(g), tick.FrameBuffer())
    t = stand(robot)
    code = robot.set_pose(*pose)
    while not robot.body.settled():
        robot.tick(t)
        t += 20
    robot.set_gait(gait)
    robot.set_params(step_length=step, lift_height=lift, cycle_ms=cycle)
    outside = 0
    ticks = 0
    refused = 0
    for k in range(COMMANDS):
        if robot.walk(pick(3000), pick(3000), pick(9000)) != 0:
            refused += 1
        for _ in range(1 + rnd(45)):
            robot.tick(t)
            t += 20
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
        t += 20
        n += 1
    print([case, code, ticks, outside, robot.faults, refused, robot.mode, robot.walker.held])
"""
)

CASES = [
    (0, 300, 300, 1000, (0, 0, 0, 0, 0, 0, 0, 0, 0)),
    (0, 600, 600, 500, (0, 0, 0, 0, 0, 0, 0, 0, 0)),
    (0, 600, 100, 5000, (0, 0, 0, 0, 0, 0, 0, 0, 0)),
    (1, 600, 600, 500, (0, 0, 0, 0, 0, 0, 0, 0, 0)),
    (2, 600, 300, 800, (0, 0, 0, 0, 0, 0, 0, 0, 0)),
    (3, 600, 600, 500, (0, 0, 0, 0, 0, 0, 0, 0, 0)),
    (3, 50, 100, 5000, (0, 0, 0, 0, 0, 0, 0, 0, 0)),
    (0, 600, 600, 700, (400, -300, 200, 0, 0, 0, 0, 0, 0)),
    (1, 600, 400, 900, (0, 0, -400, 1500, -1500, 0, 0, 0, 0)),
    (2, 600, 300, 1000, (-200, 200, 0, -800, 1200, 1500, 1000, -500, -300)),
    (0, 400, 600, 600, (0, 0, 400, 0, 1500, -1500, -2000, 0, 0)),
]


def test_no_joint_ever_leaves_its_limits(both_runtimes):
    cp, mp = both_runtimes("CASES = %r\nCOMMANDS = 40\n%s" % (CASES, SWEEP))
    assert cp == mp
    rows = [ast.literal_eval(line) for line in cp.splitlines()]
    assert len(rows) == len(CASES)
    walked = 0
    for case, code, ticks, outside, faults, refused, mode, _held in rows:
        assert outside == 0 and faults == 0, case  # every frame solved, every angle in its limits
        assert mode == 3, case  # and it stopped, standing, afterwards
        if code == 0 and refused == 0:
            walked += 1
        assert ticks > 500
    assert walked >= len(CASES) - 2  # the poses that leave a leg no room refuse walking instead


def test_tripod_static_stability_margin(rt):
    scale, cmd, worst = rt.call("scenarios.gait_limits:margin", 0)
    assert scale == 1000 and cmd == [1200, 0, 0]  # 120 mm/s: 30 mm steps, 1 s cycle
    # Minimum distance of the body centre inside the stance feet's polygon over a cycle:
    # 64.2 mm for the default robot (docs/motion.md). A positive margin with room to spare.
    assert worst >= 500, worst


def test_support_margin_geometry(rt):
    got = rt.call("scenarios.gait_limits:margin_geometry")
    # All six: the front and back edges are 100 mm away. Tripod 1-3-5: the edges RF-LM and
    # LM-RR pass 1.5e6 / hypot(1000, 2500) = 55.7 mm from the centre. A point 120 mm to the
    # right is 20 mm outside the edge RF-RR.
    assert got == [1000, 557, -200, True]
