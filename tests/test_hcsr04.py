"""HC-SR04 driver against the model: distance, timeouts, status codes, median, round robin. Both runtimes.

The firmware side is tests/scenarios/hcsr04.py: five models on stub pins, a driver on each."""

import itertools
import statistics

import pytest

PERIOD = 1 << 30


def true_distance(echo_us, temp_centi_c):
    """0.1 mm for an echo width, float oracle."""
    return echo_us * (331.3 + 0.606 * temp_centi_c / 100) / 2 * 1e4 / 1e6


@pytest.mark.parametrize("temp", [-1000, 2000, 3500])
def test_single_pings_read_the_model_distance(rt, temp):
    distances = [205, 555, 1000, 3333, 9999, 10000, 15000, 39990]
    out = rt.call("scenarios.hcsr04:single_pings", temp, distances)
    assert [st for st, _ in out] == [0] * len(distances)
    for d, (_, got) in zip(distances, out, strict=True):
        assert abs(got - d) <= 2, (d, got)  # 1 us echo quantisation is 0.17 mm


def test_distance_from_echo_is_exact_to_rounding(rt):
    widths = [140, 1000, 5824, 12345, 21000]
    rows = rt.call("scenarios.hcsr04:echo_distances", widths)
    assert len(rows) == 4 * len(widths)
    for temp, width, st, got in rows:
        assert st == 0
        assert abs(got - true_distance(width, temp)) <= 0.5 + 0.7, (temp, width, got)


def test_every_intermediate_fits_a_32_bit_small_int(rt):
    assert rt.call("scenarios.hcsr04:largest_intermediate") < 2**30


def test_timeout_follows_max_range(rt):
    rows = rt.call("scenarios.hcsr04:timeouts", [200, 10000, 15000, 40000])
    for r, timeout, block in rows:
        round_trip = 2 * r / 1e4 / 343.42 * 1e6
        assert round_trip + 1000 <= timeout <= round_trip * 1.07 + 1001  # burst allowance + 6 % margin
        assert block == 2 * timeout + 12
    assert rows[1][2] < 30000  # a 1 m max range never blocks 30 ms
    assert rows[3][2] > 20000  # 4 m cannot fit a 20 ms tick (refused by RoundRobin, below)


def test_status_codes_are_distinct_and_never_a_distance(rt):
    nd = -1
    assert rt.call("scenarios.hcsr04:measure_codes", [-2, -1, 50, 5824, 6000]) == [
        (2, nd, 2),  # -2: echo never rose: NO_ECHO
        (1, nd, 1),  # -1: echo longer than the timeout: OUT_OF_RANGE
        (4, nd, 4),  # 50 us is 8.6 mm: TOO_CLOSE
        (0, 10000, 0),  # 5824 us at 20 degC is 1000.0 mm
        (1, nd, 1),  # 6000 us is 103 cm, past the 1 m max range: OUT_OF_RANGE
    ]


def test_stuck_echo_fires_nothing_and_blocks_nothing(rt):
    assert rt.call("scenarios.hcsr04:stuck_echo") == (3, 0, 0)


@pytest.mark.parametrize("start", [0, PERIOD - 30000])
def test_a_sensor_refuses_to_ping_within_60_ms(rt, start):
    # started 30 ms before the tick counter wraps: the guard must hold across the wrap
    first, (code, d, st), again, after, pings = rt.call("scenarios.hcsr04:ping_guard", start)
    assert (first, code, st, again, after, pings) == (0, 5, 0, 5, 0, 2)
    assert abs(d - 1000) <= 2  # WAIT left the first ping's result in place


def test_median_of_the_last_n_ok_pings(rt):
    distances = [1000, 1010, 3000, 990, 1005, 1000, -1, 1002, 2000, 2000, 2000, 500, -1, -1, -1, 1000]
    rows = rt.call("scenarios.hcsr04:median_rows", distances, 5)
    window = []
    for (code, st, got, raw), x in zip(rows, distances, strict=True):
        assert code == st
        window = (window + [raw])[-5:]
        if x < 0:
            assert (st, got) == (2, -1)  # the fault shows at once, no held-over distance
        else:
            assert st == 0
            ok = [v for v in window if v >= 0]
            assert got == int(statistics.median(ok))  # even counts: the two middles' mean, floored
    assert max(got for _, _, got, _ in rows[:6]) < 1100  # the 3 m spike never comes through


def slots_ok(slots, n, tick_ms, neighbours, cycle_ms, crosstalk_ms):
    if sorted(i for i in slots if i >= 0) != list(range(n)) or len(slots) * tick_ms < cycle_ms:
        return False
    at = {i: k for k, i in enumerate(slots) if i >= 0}
    m = len(slots)
    for a, b in neighbours:
        d = (at[a] - at[b]) % m
        if min(d, m - d) * tick_ms < crosstalk_ms:
            return False
    return True


def shortest_cycle(n, tick_ms, neighbours, cycle_ms, crosstalk_ms):
    """Brute force oracle: fewest slots with any valid placement."""
    for m in range(n, 3 * n):
        for placing in itertools.permutations(range(m), n):
            slots = [-1] * m
            for i, s in enumerate(placing):
                slots[s] = i
            if slots_ok(slots, n, tick_ms, neighbours, cycle_ms, crosstalk_ms):
                return m
    return None


FIVE = ((0, 1), (0, 3), (1, 2), (3, 4))


@pytest.mark.parametrize(
    "n,tick_ms,neighbours,cycle_ms,crosstalk_ms",
    [
        (5, 20, FIVE, 60, 38),
        (5, 20, FIVE, 60, 60),
        (5, 10, FIVE, 60, 38),
        (5, 20, FIVE + ((2, 4),), 60, 38),
        (3, 20, ((0, 1), (1, 2), (0, 2)), 60, 20),
        (2, 20, (), 60, 38),
        (1, 50, (), 60, 0),
    ],
)
def test_round_robin_plan_is_valid_and_shortest(rt, n, tick_ms, neighbours, cycle_ms, crosstalk_ms):
    slots = rt.call("scenarios.hcsr04:plan", n, tick_ms, neighbours, cycle_ms, crosstalk_ms)
    assert slots_ok(slots, n, tick_ms, neighbours, cycle_ms, crosstalk_ms)
    assert len(slots) == shortest_cycle(n, tick_ms, neighbours, cycle_ms, crosstalk_ms)


@pytest.mark.parametrize("start,irq", [(0, False), (PERIOD - 250000, False), (PERIOD - 250000, True)])
def test_five_sensors_in_the_loop_read_right_without_breaking_any_rule(rt, start, irq):
    slots, dist, status, flags, pings, worst, max_block = rt.call("scenarios.hcsr04:five_in_the_loop", start, irq)
    assert status == [0] * 5
    assert all(abs(d - (1000 + 500 * k)) <= 2 for k, d in enumerate(dist))
    assert flags == {"short_trigger": 0, "ping_interval": 0, "busy": 0, "crosstalk": 0}
    assert pings == [20] * 5  # 100 ticks of 20 ms, each sensor every 100 ms
    assert len(slots) * 20 >= 60
    assert worst <= max_block < 20000


def test_the_model_catches_a_naive_order_that_pings_neighbours_back_to_back(rt):
    slots, crosstalk = rt.call("scenarios.hcsr04:naive_order")
    assert slots == (0, 1, 2, 3, 4)
    assert crosstalk > 0


@pytest.mark.parametrize("irq", [False, True])
def test_faults_keep_the_loop_running_and_no_tick_blocks_past_the_bound(rt, irq):
    (fdist, fstatus), w1, w2, max_block, dist, status, flags = rt.call("scenarios.hcsr04:faults_in_the_loop", irq)
    assert fstatus == [3, 2, 1, 1, 2]  # STUCK, NO_ECHO, OUT_OF_RANGE, OUT_OF_RANGE, NO_ECHO
    assert fdist == [-1] * 5
    assert w1 <= max_block and w2 <= max_block
    # with the model's echo rising 460 us after the trigger, a faulty ping costs at most one timeout
    assert w1 <= 12 + 460 + (max_block - 12) // 2
    assert status == [0] * 5
    assert [abs(d - t) <= 2 for d, t in zip(dist, [1000, 1500, 3000, 4000, 3000], strict=True)] == [True] * 5
    assert flags["ping_interval"] == 0 and flags["crosstalk"] == 0


def test_a_too_short_trigger_reports_no_echo_not_a_distance(rt):
    # a board whose sleep_us undershoots by 3 us: the module ignores 7 us triggers
    assert rt.call("scenarios.hcsr04:short_trigger") == (2, -1, 2, 1, 0, True)


@pytest.mark.parametrize("irq", [False, True])
def test_zero_heap_allocation_per_tick(mp, irq):
    used, status = mp.call("scenarios.hcsr04:tick_heap", irq)
    assert status == [0, 2, 3, 1, 0]  # every path ran inside the measurement
    assert used == 0


@pytest.mark.parametrize(
    "kwargs,fragment",
    [
        ({"max_range": 199}, "max_range: 199"),
        ({"max_range": 40001}, "max_range: 40001"),
        ({"max_range": True}, "max_range: True"),
        ({"samples": 0}, "samples: 0"),
        ({"samples": 10}, "samples: 10"),
        ({"temp_centi_c": 6001}, "temp_centi_c: 6001"),
        ({"temp_centi_c": 20.5}, "temp_centi_c: 20.5"),
    ],
)
def test_bad_settings_are_refused_by_name(rt, kwargs, fragment):
    msg = rt.call("scenarios.hcsr04:bad_sensor", kwargs)
    assert fragment in msg and "allowed" in msg


@pytest.mark.parametrize(
    "sensors,kwargs,fragment",
    [
        ("five", {"tick_ms": 0}, "tick_ms: 0"),
        ("five", {"neighbours": ((0, 5),)}, "neighbours: (0, 5)"),
        ("five", {"neighbours": ((2, 2),)}, "neighbours: (2, 2)"),
        ("five", {"neighbours": (3,)}, "neighbours: 3"),
        ("five", {"crosstalk_ms": 1000}, "no round robin of 5 sensors fits neighbours 1000 ms apart"),
        ("five", {"neighbours": ((0, 1.5),)}, "neighbours: (0, 1.5)"),
        ("none", {}, "at least one"),
        ("five", {"tick_ms": 10}, "lower max_range"),
        ("one_far", {"neighbours": ()}, "lower max_range"),  # one sensor with a 4 m max range
    ],
)
def test_bad_round_robins_are_refused(rt, sensors, kwargs, fragment):
    assert fragment in rt.call("scenarios.hcsr04:bad_round_robin", sensors, kwargs)
