"""HC-SR04 model against the datasheet: trigger, echo width with temperature, range, faults. Both runtimes.

The firmware side is tests/scenarios/hcsr04.py (its model_* scenarios): one model on stub pins."""

import pytest


def expected_us(distance, temp_centi_c):
    c = 331.3 + 0.606 * temp_centi_c / 100  # m/s
    return 2 * distance / 10000 / c * 1e6


@pytest.mark.parametrize(
    "distance,temp", [(200, 2000), (201, 2000), (10000, 2000), (40000, 2000), (15000, -1000), (15000, 3500)]
)
def test_echo_width_is_the_round_trip_at_the_air_temperature(rt, distance, temp):
    width, waited = rt.call("scenarios.hcsr04:model_fire", distance, temp)
    assert abs(width - expected_us(distance, temp)) <= 0.5
    assert waited == width + 460  # echo rises after the 40 kHz burst


def test_about_58_us_per_cm_at_20_degrees(rt):
    assert rt.call("scenarios.hcsr04:model_round_trips", [100, 1000, 10000], 2000) == [58, 582, 5824]


def test_out_of_range_holds_echo_high_for_38_ms(rt):
    assert [w for w, _ in rt.call("scenarios.hcsr04:model_out_of_range")] == [38000, 38000]


def test_a_trigger_shorter_than_10_us_starts_nothing_and_is_flagged(rt):
    (w9, waited9), flagged, pings, w10, flagged_after, pings_after = rt.call("scenarios.hcsr04:model_short_trigger")
    assert w9 == -2 and waited9 == 100000
    assert (flagged, pings) == (1, 0)
    assert w10 == 5824 and (flagged_after, pings_after) == (1, 1)  # counted once, the good ping accepted


def test_pings_closer_than_60_ms_are_flagged(rt):
    assert rt.call("scenarios.hcsr04:model_ping_interval") == (1, 1, 3)


def test_a_trigger_during_the_echo_is_ignored(rt):
    assert rt.call("scenarios.hcsr04:model_trigger_during_echo") == (1, 1, 1)


def test_neighbours_pinged_close_together_flag_crosstalk(rt):
    assert rt.call("scenarios.hcsr04:model_crosstalk") == ((1, 1), (1, 1, 0))


def test_stuck_high_and_missing_echo_faults(rt):
    assert rt.call("scenarios.hcsr04:model_stuck_and_missing") == [(1, (-1, 100000)), (0, (-2, 100000)), 5824]
