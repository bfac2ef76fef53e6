"""Stub pins: shared wires, pulls, models driving inputs, time_pulse_us as MicroPython's. Both runtimes.

The firmware side is tests/scenarios/pins.py."""


def test_pins_with_one_id_share_a_wire_and_outputs_reach_the_model(rt):
    assert rt.call("scenarios.pins:shared_wire") == (
        1,
        0,
        1,
        [(3, 1, 1000), (3, 0, 1000), (3, 1, 1000), (3, 0, 1000), (3, 1, 1007)],
        "Pin(3)",
        3,
    )


def test_inputs_read_force_then_model_then_pull(rt):
    assert rt.call("scenarios.pins:input_levels") == [(1, 0), 1, 0, 0, 0]


def test_bad_mode_or_pull_is_refused_with_the_pin_named(rt):
    out = rt.call("scenarios.pins:bad_mode_and_pull")
    assert "'GP7'" in out[0] and "mode 7" in out[0]
    assert "pull 9" in out[1]


def test_time_pulse_us_measures_and_advances_the_clock(rt):
    assert rt.call("scenarios.pins:pulse_width") == (500, 1800)


def test_time_pulse_us_timeouts_are_minus_two_and_minus_one(rt):
    # -2: the pulse never starts within timeout; -1: it lasts >= timeout (MicroPython's >= test)
    assert rt.call("scenarios.pins:pulse_timeouts") == [
        (-2, 1000),  # rise at 5000 is 4000 us away
        (400, 3400),  # waited 3000 for the rise, then timed 400
        (-1, 800),  # 100 us wait, then 700 us high hits the 700 us limit
        (300, 300),  # already high: timing starts at once, the pulse's past does not count
        (-1, 1000),  # undriven line sits low for ever: no end to a low pulse
    ]


def test_wdt_freq_reset_cause_unique_id(rt):
    assert rt.call("scenarios.pins:machine_extras") == [
        False,
        True,
        True,
        True,
        True,
        200000000,
        200000000,
        True,
        True,
        (True, 8),
    ]


def test_a_second_model_on_one_pin_is_refused(rt):
    assert "pin 9 is already connected" in rt.call("scenarios.pins:second_model")
