"""Every configure within a frame (issue 22, point 3): a gait, pose, height or walk-parameter change
asked with wait=False (the console's way) runs its IK solves in the frames' slack, at most two a
tick, the robot walking on in its gait meanwhile (a pose or height holds it standing), and ends
exactly where the same change asked with wait=True ends.

The bound is worked by hand from the emulated Pico (docs/physics.md, docs/pico.md): a guard solve
costs ~0.76 ms there (1.8 s for 2,365 solves), the whole frame takes at most ~2.9 ms, a walk
command in it ~1.3 ms more, and the goal is 6 ms a frame: (6 - 2.9 - 1.3) / 0.76 = 2.4, so two
solves a tick. The command itself solves nothing (even the six feet where they stand are checked
in the slack).
"""

import pytest

from hexapod import tick

KINDS = ("gait", "pose", "height", "params")


@pytest.mark.parametrize("kind", KINDS)
def test_a_configure_in_the_slack_solves_two_a_tick_one_walking_and_ends_as_one_made_at_once(both_runtimes, kind):
    cp, mp = both_runtimes.call("scenarios.configure:spread", kind)
    assert cp == mp
    code, asked, worst, ticks, job_code, after, sync, sync_code, travel = cp
    assert code == tick.OK and job_code == tick.OK and sync_code == tick.OK
    assert asked == 0  # not even the feet where they stand: all of it in the slack
    # Never more than two solves a tick standing, one walking (the gait, asked on the move: a walking
    # frame has room for one beside a walk command; docs/pico.md), and the work does go on.
    assert worst == (1 if kind == "gait" else 2)
    assert ticks > 100  # thousands of solves: spread over many frames
    assert after == sync  # reach discs, servo radii, peak, gait, cycle, pose, ground: the same integers
    if kind == "gait":
        assert after[7] == 2 and after[8] == 2400  # ripple at 2.4 s taken
        assert travel > 300  # walked on in the tripod while it was checked (> 30 mm at 40 mm/s)
    else:
        assert travel == 0


def test_while_a_pose_is_checked_the_robot_stands_and_other_configures_wait(rt):
    out = rt.call("scenarios.configure:refusals")
    assert out[:2] == [tick.OK, True]
    # walk, another configure, a posture move, a height: each refused, naming why
    assert out[2:6] == [tick.CONFIGURING] * 4
    assert "still being checked" in out[6]


def test_the_ticks_of_a_configure_in_the_slack_allocate_nothing_after_its_first(rt):
    if rt.name != "micropython":
        pytest.skip("heap bytes are counted in the MicroPython VM")
    allocated, ticks = rt.call("scenarios.configure:job_heap")
    assert ticks > 100
    # Its generators and their buffers are made when asked. Measured: the disc search's first
    # resume leaves 96 B in the unix VM (before any of its code runs; not traced further).
    assert len(allocated) <= 1 and sum(allocated) <= 128


@pytest.mark.parametrize("pattern", [".", "c.........", "cc..", "c"])
def test_under_the_runner_a_walking_step_waits_for_the_frames_commands(rt, pattern):
    # Runner.run sets robot.defer: a walking tick leaves its configure step owed and the loop pays it
    # after the console's line, skipping it in a frame that ran a command (a walk command ~1.1 ms
    # and a step ~0.85 ms made a 6.7 ms frame on the emulated Pico), but never two frames running:
    # a command every frame slows the configure to a step every second frame, never stops it.
    in_tick, wrong, first, ticks, after, sync = rt.call("scenarios.configure:deferred", pattern)
    assert in_tick == 0  # nothing solved in a walking tick
    assert wrong == [], (wrong, first)  # a step paid after each frame, but none after a command
    # unless the frame before skipped its own
    starts = {".": [1, 1, 1, 1], "c.........": [0, 1, 1, 1], "cc..": [0, 1, 1, 1], "c": [0, 1, 0, 1]}
    assert first[:4] == starts[pattern]
    assert ticks > 100 and after == sync  # the same change, the same integers, only later
