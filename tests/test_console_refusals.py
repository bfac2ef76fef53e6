"""Issue 24, part 2: a refused command changes nothing, and "nothing" is all the console's state:
pulses and angles, the PCA9685 models' outputs, calibration rows and trims, the calibration source,
PID gains, the wall follower's mode, side and set point, the walk command and its deadline, mode,
gait, echo and the telemetry (rate, countdown, counts). Every command with bad arguments (and the
ones the robot's state refuses) in five
states: relaxed, jogged, standing, walking and following a wall; on both runtimes.

The console here (tests/scenarios/console_refusals.py) has a calibration file on a stub filesystem: a
file whose last row the present pose refuses (`load` must roll the other 17 back), a read-only
filesystem and one that writes short while reporting success (`save` must keep the source)."""

import pytest

from tests.console_rig import clean_stubs  # noqa: F401 (autouse fixture)

# Bad arguments for every command; then the lines a state refuses (checked per state below).
BAD = [
    "status now",
    "help me",
    "stand 1",
    "sit 1",
    "relax 1",
    "foot 7 100 0 -80",
    "foot 2 600 0 -80",
    "foot 2 300 0 -80",
    "foot 2 1e2 0 -80",
    "nudge 2 0 0 2000",
    "nudge 2 0 0",
    "joint 2 knee 10",
    "joint 2 femur 95",
    "joint 2 coxa x",
    "pulse 2 femur 2401",
    "pulse 2 femur 1500.5",
    "pulse 0 femur 1500",
    "get 9",
    "walk 1 2",
    "walk 400 0 0",
    "walk 0 0 91",
    "stop 1",
    "gait trot",
    "gait wave ripple",
    "height 59.9",
    "height 100.1",
    "height -80",
    "height x",
    "height 1e2",
    "height 80 1",
    "sonar 1",
    "wall up 8",
    "wall left 3",
    "wall right 51",
    "wall left",
    "wall left 12 zigzag",
    "wall left 12 Yaw",
    "wall left 12 yaw now",
    "pid 1 2",
    "pid 30 -1 0",  # a good kp before a bad ki: kp must not change either
    "pid 30 0 -1",
    "pid 101 0 0",
    "cal 2",
    "cal 2 foot",
    "trim 2 femur 301",
    "trim 2 femur x",
    "dir 2 femur 0",
    "range 2 femur 1500 1500",
    "range 2 femur 400 2400",
    "range 2 femur 2000 1000",
    "save 1",
    "load now",
    "defaults x",
    "echo sideways",
    "echo on",  # this console has no raw output
    "selftest 1 2 3",
    "stream on 0",
    "stream on 26",
    "stream on x",
    "stream on 5 6",
    "stream off 3",
    "stream sideways",
    "jump",
]
# Refused by the state rather than by the words (each state answers some of them with ok).
STATEFUL = [
    "trim 2 femur 100",  # jogged: 2350 + 100 is above 2400; standing/walking: refused or ok
    "range 2 femur 600 2300",  # jogged: 2350 is outside; standing: ok
    "load",  # leg 6 tibia's row refuses the pose when driven: all 18 rows roll back
    "<short>",  # save on a filesystem that writes short and says it did not
    "<readonly>",  # save on a read-only filesystem
    "height 70",  # jogged: refused (the legs are jogged); standing: checked over frames (no reply yet)
]

STATES = ("relaxed", "jogged", "standing", "walking", "following")


@pytest.mark.parametrize("state", STATES)
def test_a_refused_command_changes_nothing_in_any_state(rt, state):
    mode, follow_mode, out = rt.call("scenarios.console_refusals:refused", state, BAD + STATEFUL)
    assert mode == {"relaxed": 0, "jogged": 5, "standing": 3, "walking": 4, "following": 4}[state]
    assert (follow_mode != 0) == (state == "following")
    by = {}
    for line, reply, diff in out:
        by[line] = (reply, diff)
        if line in BAD:
            assert reply.startswith("err "), (state, line, reply)
        if reply is not None and reply.startswith("err "):
            assert diff == [], (state, line, reply, diff)
            assert "internal" not in reply, (state, line, reply)
    # hand-checked replies and refusals that must hold in every state
    assert by["pid 30 -1 0"][0] == "err pid: ki -1 is outside 0.000..100.000 "
    assert by["stream on 26"][0] == "err stream: HZ '26': allowed a whole number 1..25 (lines a second)"
    assert by["stream on 5 6"][0] == "err stream: need on [HZ], off or nothing (ask), got 'on 5 6'"
    assert by["height 59.9"][0] == "err height: height 59.9 is outside 60.0..100.0 mm"
    assert by["height 1e2"][0] == "err height: height '1e2' is not a decimal number (mm)"
    assert by["stream off 3"][0] == "err stream: need on [HZ], off or nothing (ask), got 'off 3'"
    assert by["wall left 12 zigzag"][0] == "err wall: form 'zigzag', allowed yaw, sweeps, crab"
    assert by["wall left 12 yaw now"][0] == "err wall: need left|right CM [FORM], or off, got 4 arguments"
    # a short write that reports success: only the read-back notices; the file and source are kept
    # (the OSError's text differs: CPython "[Errno 28] ...", MicroPython "(28, '...')")
    short = by["<short>"][0]
    assert short.startswith("err save: the filesystem refused ("), short
    assert "written file reads back different" in short and short.endswith("; the previous file is kept"), short
    assert by["<readonly>"][0].startswith("err save: the filesystem is read-only ("), by["<readonly>"]
    if state == "jogged":
        # leg 2 femur at 2350 us: trim +100 maps it to 2450, above 2400; 2350 is above 2300
        assert by["trim 2 femur 100"][0].startswith("err trim: leg 2 femur: at "), by["trim 2 femur 100"]
        assert by["range 2 femur 600 2300"][0].startswith("err range: leg 2 femur: at "), by
    if state in ("walking", "following"):
        assert by["height 70"][0] == "err height: refused: the robot is walking; stop first"
    else:  # taken, checked over the next frames: its reply comes later (test_console_height)
        assert by["height 70"] == (None, [4]), by["height 70"]  # the standing height changed
    if state in ("relaxed",):
        # nothing driven: the file's rows all apply; the saves that follow then fail and keep it
        assert by["load"][0] == "ok loaded hexapod_cal.txt", by["load"]
    else:
        # leg 6 tibia is driven: its row 2480..2500 cannot hold its angle, all 18 roll back
        assert by["load"][0].startswith("err load: hexapod_cal.txt kept the calibration in force: "), by["load"]
        assert by["load"][1] == []
