"""A command change in the middle of a swing (the wall follower's yaw, a new speed) does not kick a
joint: the swing foot moves as its new plan does plus at most walk.REPLAN_STEP a tick toward it.

Oracle: the servo guard's per-tick budget from the datasheet numbers in robots/default.py
(60 degrees in 170 ms at 50 Hz, 40 % of it: 282.35 cdeg), not from the code. Before the change
(the swing re-aimed in full every tick), the same sweeps measured up to 1,247 cdeg in one tick
(a yaw reversal at swing tick 21 of 25).
"""

import pytest

import robots.default as d
from hexapod import geometry, tick, walk
from tests.test_servo_guard import standing as standing_robot

# 60 degrees (6000 cdeg) per 170 ms, one 20 ms tick, the planner's share: 282.35 cdeg.
BUDGET = 6000 * 20 / d.SERVO["speed_ms_per_60deg"] * d.SERVO["planner_share_permille"] / 1000


def standing():
    return standing_robot(geometry.load(d))


def worst_step(robot, t, commands, ticks, settle=100):
    """Largest per-tick joint change (cdeg) after `settle` ticks; commands maps tick -> (vx, vy, yaw)."""
    prev = list(robot.angles)
    worst = 0
    for n in range(ticks):
        if n in commands:
            assert robot.walk(*commands[n]) == tick.OK
        assert robot.tick(t[0]) == tick.OK
        t[0] += 20
        if n >= settle:
            worst = max(worst, *(abs(a - b) for a, b in zip(robot.angles, prev, strict=True)))
        prev = list(robot.angles)
    return worst


# The wall follower's kind of change (a yaw step, either way, up to the accepted maximum) and
# speed steps, at the guard's largest accepted speed too (both are scaled by it).
CHANGES = [
    ((400, 0, 0), (400, 0, 9000)),
    ((400, 0, 9000), (400, 0, -9000)),
    ((200, 0, -3000), (400, 0, 3000)),
    ((400, 0, 0), (100, 0, 0)),
    ((100, 0, 0), (400, 0, 0)),
    ((3000, 0, 0), (3000, 0, 9000)),
    ((0, 0, 9000), (0, 0, -9000)),
]


@pytest.mark.parametrize("before,after", CHANGES)
def test_a_command_change_at_every_swing_tick_stays_inside_the_servo_budget(before, after):
    # The 1 s tripod swings 25 ticks, each group in turn: changing the command at ticks 150..174
    # hits every tick of a swing (one group or the other), 150 ticks into a steady walk.
    worst = 0
    for k in range(25):
        robot, t = standing()
        worst = max(worst, worst_step(robot, t, {0: before, 150 + k: after}, 150 + k + 60))
    assert worst <= BUDGET, (before, after, worst)


def test_random_follower_commands_stay_inside_the_servo_budget():
    # Forward speed and yaw as the wall follower asks (vx >= 0, no sideways), changed after
    # 1-30 ticks, anywhere in the accepted range; the start from standing is left out (its first
    # steps are longer: tests/test_servo_guard.py).
    import random

    rnd = random.Random(10)
    robot, t = standing()
    commands = {0: (400, 0, 0)}
    n = 0
    while n < 1500:
        n += rnd.randint(1, 30)
        commands[n] = (rnd.randint(50, walk.SPEED_MAX), 0, rnd.randint(-walk.YAW_RATE_MAX, walk.YAW_RATE_MAX))
    assert worst_step(robot, t, commands, 1500) <= BUDGET


def test_a_late_re_aim_is_the_same_on_both_runtimes(both_runtimes):
    # CPython runs the plain swing, the MicroPython VM the viper one (hexapod/_walk_viper.py).
    # a yaw or speed change early, mid and late in a swing
    cp, mp = both_runtimes.call("scenarios.replan:late_re_aims", 220, [120, 141, 170, 193], 110)
    assert cp == mp
    assert len(cp) == 110 and max(max(f[3]) for f in cp) > 20  # swings ran to their late ticks
