"""Virtual clock: MicroPython's wrapping tick arithmetic, sleeps that cost no real time. Both runtimes."""

PERIOD = 1 << 30


def test_ticks_add_and_diff_round_trip_across_the_wrap(rt):
    assert rt.call("scenarios.clock:round_trips") == []


def test_ticks_diff_matches_the_modular_definition(rt):
    # independent oracle: the representative of (a - b) mod P in [-P/2, P/2)
    pairs = [(0, PERIOD - 1), (PERIOD - 1, 0), (5, 10), (10, 5), (PERIOD // 2, 0), (0, PERIOD // 2), (123, 123)]
    expected = [((a - b + PERIOD // 2) % PERIOD) - PERIOD // 2 for a, b in pairs]
    assert rt.call("scenarios.clock:diffs", pairs) == expected
    assert expected[0] == 1 and expected[1] == -1  # the wrap itself


def test_sleeps_move_virtual_time_and_ticks_wrap(rt):
    a, b, diff, diff_ms, slept, now = rt.call("scenarios.clock:sleeps")
    assert a == PERIOD - 4 and b == 6 and diff == 10
    assert diff_ms == 3
    assert slept == 10
    assert now == PERIOD - 4 + 10 + 3000 + 10


def test_time_only_moves_forward(rt):
    out = rt.call("scenarios.clock:backwards")
    assert out[0] == 500 and out[3] == 500
    assert "forward" in out[1] and ">= 0" in out[2]


def test_monotonic_is_seconds_of_virtual_time(rt):
    assert rt.call("scenarios.clock:monotonic") == (1.5, 1500000000)
