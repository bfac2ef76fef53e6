"""view/pace.py: the server draws a tab only while the page keeps up (hand-worked sequences)."""

import pytest

from hexapod_host.view.pace import Pace


def beats(p, n, marks=None):
    """n beats of the player; the marks the page sends back arrive before beat k ({k: marks})."""
    drawn = []
    for k in range(n):
        for mark in (marks or {}).get(k, ()):
            p.shown(mark)
        if p.ready():
            drawn.append((k, p.sending()))
    return drawn


def test_a_page_that_keeps_up_gets_every_beat():
    p = Pace(in_flight=2, patience=5)
    # each mark comes back before the next beat
    drawn = beats(p, 6, {k: (k,) for k in range(1, 7)})
    assert drawn == [(0, 1), (1, 2), (2, 3), (3, 4), (4, 5), (5, 6)]
    assert p.skipped == 0


def test_a_silent_page_gets_two_draws_then_one_per_patience():
    p = Pace(in_flight=2, patience=5)
    drawn = beats(p, 20)
    # beats 0, 1 drawn (2 in flight), 2-6 skipped (5 = patience), 7 drawn, 8-12 skipped, 13, ...
    assert drawn == [(0, 1), (1, 2), (7, 3), (13, 4), (19, 5)]
    assert p.skipped == 15


def test_a_mark_back_frees_exactly_one_draw():
    p = Pace(in_flight=2, patience=100)
    drawn = beats(p, 10, {4: (1,)})
    assert drawn == [(0, 1), (1, 2), (4, 3)]
    assert p.skipped == 7


@pytest.mark.parametrize("mark", [0, -1, 3, 99, "1", 1.0, None, True, [1], {"a": 1}])
def test_a_mark_never_sent_changes_nothing(mark):
    p = Pace(in_flight=2, patience=100)
    p.sending(), p.sending()
    p.shown(1)
    p.shown(mark)
    assert (p.sent, p.seen) == (2, 1)


def test_an_old_mark_never_moves_seen_back():
    p = Pace()
    for _ in range(3):
        p.sending()
    p.shown(3)
    p.shown(2)
    assert p.seen == 3


@pytest.mark.parametrize("in_flight, patience", [(0, 5), (2, 0), (-1, -1)])
def test_bad_settings_are_refused(in_flight, patience):
    with pytest.raises(ValueError, match="allowed 1 or more"):
        Pace(in_flight=in_flight, patience=patience)
