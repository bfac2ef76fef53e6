"""The stand-up helper every stand loop calls (host/hexapod_host/stubs/micropython/standing.py)."""

import pytest

ASKED_BUSY = "; the ask answered: refused: a posture or pose move is still running"  # tick.describe(BUSY)


def test_posture_bound_default_robot(rt):
    # robots/default.py: R = 300 + 850 + 1250 + |320| = 2720 (0.1 mm); a set at most
    # ceil((2 * 2720 + 1) / 20) = 273 frames; 24 soft-start frames + 3 sets + the ending frame = 844.
    bound, n, numbered, mode, ticks, again = rt.call("scenarios.stand_helper:default_robot")
    assert bound == 844
    assert 24 < n <= 844  # the soft start alone holds 24 frames
    assert n == rt.call("scenarios.stand_helper:open_coded")  # what the open-coded loops took
    assert numbered and ticks == n  # frame(n) got 0, 1, ... and each ticked the robot once
    assert mode == 3  # tick.STANDING
    assert again == 0  # already standing: no frame run


@pytest.mark.parametrize(
    "after, most, want",
    [
        (5, 5, 5),  # standing at the bound's last frame: the bound is not one short
        (5, 4, ["not standing after 4 frames: mode moving, last reason: ok", 4]),
        (1, 1, 1),
        (None, 3, ["not standing after 3 frames: mode moving, last reason: ok", 3]),
    ],
)
def test_bound_kept(rt, after, most, want):
    assert rt.call("scenarios.stand_helper:bounded", after, most) == want


def test_refused_ask_is_named(rt):
    assert rt.call("scenarios.stand_helper:refused") == [
        "not standing after 3 frames: mode relaxed, last reason: ok" + ASKED_BUSY
    ]


def test_robot_that_never_stands_ends(rt):
    # Frames that never tick the robot: moving for ever, stopped at the default bound (844 above).
    text, ticks = rt.call("scenarios.stand_helper:frozen")
    assert text == "not standing after 844 frames: mode moving, last reason: ok" and ticks == 0
