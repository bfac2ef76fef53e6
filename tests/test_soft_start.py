"""Soft start (issue 20, point 2): a move out of RELAXED switches the servos on a leg group at a
time, so the supply never sees 18 hobby servos start at once. Both runtimes."""

import pytest

SITTING, STANDING = 1, 3  # hexapod.tick modes
STAGGER = 8  # frames between groups: 160 ms, the 100-200 ms
FRONT, MIDDLE, REAR = (1, 6), (2, 5), (3, 4)  # legs, 1 RF .. 6 LF


def servos(*legs):
    """The bit mask of the three servos of each leg (bit 3 * (leg - 1) + joint)."""
    return sum(0b111 << 3 * (leg - 1) for leg in legs)


@pytest.mark.parametrize("move, ends", [("stand_up", STANDING), ("sit_down", SITTING)])
@pytest.mark.parametrize("before", ["power_up", "relax"])
def test_leg_groups_come_on_one_at_a_time(rt, move, ends, before):
    masks, changed, frames, mode = rt.call("scenarios.tick:soft_start", move, before)
    assert mode == ends
    # Front pair from the first frame, the middle pair 8 frames later, the rear pair 8 after that.
    want = [servos(*FRONT)] * STAGGER + [servos(*FRONT, *MIDDLE)] * STAGGER + [servos(*FRONT, *MIDDLE, *REAR)]
    assert masks[: 2 * STAGGER + 1] == want
    assert all(m == servos(1, 2, 3, 4, 5, 6) for m in masks[2 * STAGGER :])
    # At most one group (6 servos) starts in any frame: 18 at once without the soft start.
    started = [bin(b & ~a).count("1") for a, b in zip([0] + masks, masks, strict=False)]
    assert max(started) == 6 and sum(started) == 18
    # The first pose is held until the rear pair has had 8 frames too: nothing but the groups
    # coming on changes before frame 24; the posture move starts then.
    assert changed[1:24] == [False] * 7 + [True] + [False] * 7 + [True] + [False] * 7
    if move == "stand_up":
        assert changed[24]
    else:  # a relaxed robot rests where sitting puts it: nothing moves once the groups are on
        assert not any(changed[17:]) and frames <= 2 * STAGGER + STAGGER + 2
    print("%s after %s: %d frames (%d ms), 24 of them the soft start" % (move, before, frames, 20 * frames))
