"""robots/default_guard.py (hexapod.reach's guard table): the servo guard's answers for the robot file's own
settings, made on the host, so that power-up and a change to a gait at its own cycle solve no IK.

Oracles: the live guard (reach.disc_radii, reach.servo_radii) and the exhaustive form of the
servo guard (bench/guard.py: every direction and tick pair solved in full), each run here on
the robot file; the table must hold their very integers.
"""

import math
import types

import robots.default as d
import robots.default_guard as table
from hexapod import geometry, reach, tick
from hexapod.body import Body
from hexapod.gait import swing_stance_ticks
from hexapod.walk import Walker
from hexapod_host.bench.guard import CountingIK, exhaustive_radii
from hexapod_host.guard_table import live_entries
from hexapod_host.serial import flash


def _robot(g):
    return tick.Robot(g, tick.default_servos(g), tick.FrameBuffer())


def _state(robot):
    w = robot.walker
    return [list(w.rho), list(w.srho), list(w.next_srho), w.servo_peak, w.clock.gait, w.clock.cycle_ms]


def _other_file(**change):
    data = {k: getattr(d, k) for k in dir(d) if k.isupper()}
    data.update(change)
    return types.SimpleNamespace(**data)


def test_the_table_holds_the_live_guards_answers_bit_for_bit():
    g = geometry.load(d)
    discs, servo = live_entries(g)
    assert tuple(table.ROBOT) == reach.robot_key(g)
    assert [tuple(r) for r in table.DISCS] == discs
    assert [tuple(r) for r in table.SERVO] == servo
    assert len(servo) == 4  # every gait at the robot file's cycle
    assert [r[1] for r in servo] == list(d.GAIT_CYCLE_MS)


def test_the_tables_servo_radii_are_the_exhaustive_guards():
    g = geometry.load(d)
    w = Walker(g)
    body = Body(g)
    for gait, cycle, lift, step, height, rho, peak, srho, _ in table.SERVO:
        assert height == d.BODY_HEIGHT and -w.ground >> 4 == height
        swing, stance = swing_stance_ticks(gait, cycle, [0, 0])
        out = [0] * 6
        caps = [min(r, step) for r in rho]
        assert exhaustive_radii(w, body, swing, stance, lift, g.servo_step, caps, out) == peak
        assert tuple(out) == tuple(srho)


def test_the_tables_stroke_gains_are_the_sine_swings_steepest_tick():
    # The swing's stroke (1 + sin) / 2 over its n = w - 2 middle ticks moves the most in the tick
    # around its middle: sin(pi / 2n) of the stroke for odd n, sin(pi / n) / 2 for even n (float),
    # times w in Q15. fixmath's sine table and the cdeg angles leave the integers within 1.2 w of it
    # (measured: -1.17 w at the tripod's 25 ticks).
    for gait, cycle, *_, gain in table.SERVO:
        w = swing_stance_ticks(gait, cycle, [0, 0])[0]
        n = w - 2
        share = math.sin(math.pi / (2 * n)) if n % 2 else math.sin(math.pi / n) / 2
        assert abs(gain - 32768 * w * share) <= 1.2 * w, (gait, gain, 32768 * w * share)


def test_power_up_and_each_gait_at_its_cycle_solve_no_ik_and_end_as_the_live_guard():
    solves, states = _power_up_and_every_gait(geometry.load(d))
    assert solves == 0
    live = geometry.load(d)
    live.name = "no table"  # (no robots/no table_guard.py: the guard runs)
    solves, want = _power_up_and_every_gait(live)
    assert solves > 4 * 1000  # what the table saves: discs, then each gait's servo radii
    assert states == want


def _power_up_and_every_gait(g):
    """(IK solves, the robot's state after power-up and after each gait at its own cycle) for g."""
    with CountingIK(g) as count:
        robot = _robot(g)
        states = [_state(robot)]
        for gait in range(4):
            assert robot.set_gait(gait) == tick.OK
            states.append(_state(robot))
    return count.solves, states


def test_a_pose_a_height_or_another_robot_file_runs_the_live_guard():
    g = geometry.load(d)
    robot = _robot(g)
    w = robot.walker
    probe = Body(g)
    probe.set_target([0, 0, 0, 500, 0, 0, 0, 0, 0])
    probe.jump()
    assert not reach.table_discs(table, probe, w.ground, w.lift, [0] * 6)  # a pose
    assert not reach.table_discs(table, Body(g), -700 << 4, w.lift, [0] * 6)  # another height
    assert not reach.table_discs(table, Body(g), w.ground, 250, [0] * 6)  # another lift
    assert reach.table_discs(table, Body(g), w.ground, w.lift, [0] * 6)
    assert not reach.table_servo(table, w, 2, 2400, w.lift, w.step, w.rho)  # another cycle
    assert reach.find_table(geometry.load(_other_file(FEMUR=860))) is None
    assert reach.find_table(geometry.load(_other_file(SERVO=dict(d.SERVO, planner_share_permille=300)))) is None
    assert reach.find_table(g) is table
    with CountingIK(g) as count:
        assert robot.set_gait(2, 2400) == tick.OK
    assert count.solves > 500


def test_the_table_is_flashed_with_its_robot_and_is_no_robot_of_its_own():
    assert "default_guard" not in flash.robots() and "default" in flash.robots()
    _, files, _ = flash.select_files("pico", "default")
    assert any(f.endswith("robots/default_guard.py") for f in files)
