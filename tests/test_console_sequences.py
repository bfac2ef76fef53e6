"""Console commands never leave the robot frozen (issue 20, point 3): the reproduction, the
one-time notice of a held frame, and random command sequences through the real console on the
stub board, both runtimes (tests/scenarios/console_seq.py holds the rig, the generator and the
frame bounds with their reasoning)."""

import os

import pytest

from tests.console_rig import clean_stubs  # noqa: F401 (autouse fixture)

# Sequences per runtime in the ordinary run (one VM start), and in the long one (HEXAPOD_LONG=1).
SEQUENCES = 2000
LONG_SEQUENCES = 20000


def test_sit_after_a_stretched_tibia_sits(rt):
    # stand, `joint 2 tibia 0` (docs/jog.md's calibration step), `sit`: it used to answer ok and
    # hold every frame after (faults 50 a second, mode sitting, leg 2 frozen at 1500 1454 2348).
    replies, to_stand, took, mode, held, faults, leg2, notices = rt.call("scenarios.console_seq:sit_after_tibia_zero")
    assert replies[0] == "ok mode moving" and replies[2] == "ok mode moving", replies
    assert " angles 0.00 8.11 0.00 pulses 1500 1581 2400 " in replies[1]
    assert 0 < to_stand < 100
    assert mode == "sitting" and 0 < took <= 120  # the stretched leg slides home: 108 mm at 2 mm a frame
    assert held == 0 and faults == 0 and notices == []
    assert leg2 != [1500, 1454, 2348]


def test_a_held_frame_is_announced_once(rt):
    first, held, again = rt.call("scenarios.console_seq:held_notice")
    assert held == 100  # the frame cannot be sent: every frame is held ...
    assert first == [
        "held: leg 2: femur pulse 50 us below its calibrated 1631..2400 us; the servos keep the last frame"
        " until it clears (mode standing)"
    ]  # ... and the console says so once, with the leg and why
    assert len(again) == 2  # once more after frames were sent in between


def _check(result, n):
    count, commands, frames, oks, errs, worst, held, held_run, bad, bounds = result
    posture_frames, walk_frames, held_frames = bounds
    assert bounds == [821, 484, 821]
    assert bad == []
    assert count == n and commands >= 3 * n
    assert held == 0 and held_run == 0  # no frame held at all (the bound is held_frames)
    for word in ("stand", "sit", "relax"):
        assert worst[word] <= posture_frames, worst
    for word in ("stop", "walk", "wall"):
        assert worst.get(word, 0) <= walk_frames, worst
    # the sequences reached deep states: moves, jogs, walks, recalibrations and refusals
    for word in ("stand", "sit", "relax", "joint", "foot", "nudge", "pulse", "trim", "range", "dir", "walk", "wall"):
        assert oks.get(word, 0) >= 10, oks
    assert errs >= n // 5
    return frames


def test_random_command_sequences_never_freeze(rt):
    frames = _check(rt.call("scenarios.console_seq:sequences", 20, SEQUENCES), SEQUENCES)
    assert frames > 15 * SEQUENCES  # 37,374 frames (12.5 virtual minutes) at seed 20


@pytest.mark.skipif(not os.environ.get("HEXAPOD_LONG"), reason="the long run: HEXAPOD_LONG=1")
def test_random_command_sequences_long(rt):
    _check(rt.call("scenarios.console_seq:sequences", 21, LONG_SEQUENCES), LONG_SEQUENCES)
