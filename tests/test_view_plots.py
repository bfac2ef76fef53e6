"""The live plots' values (player.COLUMNS): walking speed asked and of the body, battery, frames
per second of the host's clock, the loop's counters; "-" where a source has no such value. The
player is given its time (advance) and its clock: no wall-clock time."""

import pytest
from test_view import Counter

from hexapod_host.view import page
from hexapod_host.view import player as player_mod
from hexapod_host.view.page import live_text


class Walker(Counter):
    """Counter in a room: the body 1 mm further along x each 20 ms frame (50 mm/s), the walk asked
    30 mm/s forward and 40 mm/s to the left (50 mm/s), a 7.4 V battery, some counters."""

    def describe(self):
        return {"source": "walker", "walls": [[0.0, 0.0, 2000.0, 0.0]]}

    def snapshot(self):
        s = super().snapshot()
        s["extra"] = {"walk": [30.0, 40.0, 5.0], "battery_mv": 7400}
        s["counters"] = {"frames": self.n, "held": 0, "overruns": 2, "bus_failed": 1, "sonar_faults": 7}
        return s


class Clock:
    def __init__(self):
        self.t = 100.0

    def __call__(self):
        return self.t


def played(source, seconds, speed=1.0, step=0.2):
    clock = Clock()
    p = player_mod.Player(source, speed=speed, clock=clock)
    for _ in range(round(seconds / step)):
        clock.t += step
        p.advance(step)
    return p


def row(p):
    return dict(zip(player_mod.COLUMNS, p.history[-1], strict=True))


def test_speed_battery_rate_and_counters_from_a_source_in_a_room():
    r = row(played(Walker(), 2.0))
    assert r["asked_mm_s"] == 50.0  # hypot(30, 40)
    assert r["body_mm_s"] == 50.0  # 1 mm a 20 ms frame
    assert r["battery_v"] == 7.4
    assert r["frames_per_s"] == 50.0  # 10 frames each 0.2 s of the host's clock
    assert (r["overruns"], r["held"], r["bus_failed"], r["sonar_faults"]) == (2, 0, 1, 7)


def test_at_twice_the_speed_the_frames_come_twice_as_often():
    r = row(played(Walker(), 2.0, speed=2.0))
    assert r["frames_per_s"] == 100.0 and r["body_mm_s"] == 50.0  # the body's speed is in the source's time


def test_paused_no_frames_and_the_last_speed_kept():
    p = played(Walker(), 1.0)
    kept = len(p._moves)
    p.pause()
    for _ in range(200):  # 40 s of the host's clock, no frame
        p.clock.t += 0.2
        p.advance(0.2)
    assert len(p._moves) == kept  # a pause adds no samples to measure the speed over
    r = row(p)
    assert r["frames_per_s"] == 0.0 and r["body_mm_s"] == 50.0


def test_a_source_without_room_battery_or_counters_gives_none_not_zero():
    r = row(played(Counter(), 1.0))  # no walls, no extra, no counters
    assert r["body_mm_s"] is None and r["asked_mm_s"] is None and r["battery_v"] is None
    assert r["overruns"] is None and r["sonar_faults"] is None
    assert r["frames_per_s"] == 50.0  # every source has frames
    text = live_text(played(Counter(), 1.0).history[-1])
    assert text == (
        "speed asked - mm/s, body - mm/s  battery - V  frames/s 50  frame - us (worst -)  overruns -  held -  "
        "bus_failed -  sonar_faults -"
    )


def test_the_first_row_has_nothing_to_measure_yet():
    r = row(player_mod.Player(Walker(), clock=Clock()))
    assert r["body_mm_s"] is None and r["frames_per_s"] is None


@pytest.mark.parametrize("v, shown", [(None, "-"), (0, "0"), (7.4, "7.4"), (50.0, "50")])
def test_live_text_shows_dash_only_for_none(v, shown):
    row = [v] * len(player_mod.COLUMNS)
    assert live_text(row).startswith("speed asked %s mm/s, body %s mm/s  battery %s V" % (shown, shown, shown))


def test_a_plot_gets_only_the_rows_added_since_its_last_look():
    p = played(Counter(), 0.2)  # the row published at start (frame 0) and one 0.2 s on (frame 10)
    fresh, rows, mark = p.new_rows(None)  # a new tab: everything
    assert fresh and [r[0] for r in rows] == [0.0, pytest.approx(0.2)]
    fresh, rows, mark = p.new_rows(mark)
    assert (fresh, rows) == (False, [])  # nothing published since
    for _ in range(3):
        p.clock.t += 0.2
        p.advance(0.2)
    fresh, rows, mark = p.new_rows(mark)
    assert not fresh and [r[0] for r in rows] == pytest.approx([0.4, 0.6, 0.8])  # the three, oldest first
    assert rows == list(p.history)[-3:]


def test_a_plot_starts_over_with_the_history():
    p = played(Counter(end=20), 1.0)  # done at frame 20
    _, _, mark = p.new_rows(None)
    p.start()  # a finished trial gives way to the next: the history starts over
    fresh, rows, mark = p.new_rows(mark)
    assert fresh and [r[0] for r in rows] == [0.0]
    keep = p.history.maxlen
    for _ in range(keep + 5):  # more rows than the history keeps since the last look
        p.advance(0.02)
    fresh, rows, _ = p.new_rows(mark)
    assert fresh and len(rows) == keep == 500 and rows == list(p.history)


class Timed(Counter):
    """Counter whose board reports its frame time (telemetry's frame_us, frame_us_max)."""

    def snapshot(self):
        s = super().snapshot()
        s["extra"] = {"frame_us": 3395, "frame_us_max": 4431}
        return s


def test_the_firmware_frame_time_is_plotted():
    r = row(played(Timed(), 0.4))
    assert (r["frame_us"], r["frame_us_max"]) == (3395, 4431)
    assert "frame 3395 us (worst 4431)" in live_text(played(Timed(), 0.4).history[-1])
    assert ("firmware frame time (us)", (("last", "frame_us"), ("worst", "frame_us_max"))) in page.PLOTS
