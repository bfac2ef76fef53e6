"""The echo timed by pin IRQs: the stub Pin.irq runs handlers at the models' edges on the virtual
clock; the driver (irq=True) against hand-worked echoes at the range ends, timeouts to the us,
faults; Runner.wait holds the 20 ms grid to the us. Both runtimes."""

import pytest


def test_stub_irq_handlers_run_at_the_edges_in_time_order(rt):
    # two models 100 mm away: triggers fall at 1010 and 1020, echoes rise 460 us later
    seen, now = rt.call("scenarios.hcsr04_irq:edges_in_time_order")
    w = 582  # 2 * 100 mm / 343.42 mm/ms at 20 degC = 582.4 us, the model rounds
    assert seen == [("a", 1, 1470), ("a", 0, 1470 + w), ("b", 0, 1480 + w)]  # b only falling; a removed
    assert now == 101020


def test_stub_irq_sees_a_forced_or_unplugged_line_move(rt):
    assert rt.call("scenarios.hcsr04_irq:forced_or_unplugged") == [(0, 1005), (1, 1010), (0, 1015), (1, 1020)]


def test_stub_irq_two_pins_with_edges_at_one_instant_both_run(rt):
    w = 291  # 2 * 50 mm / 343.42 mm/ms = 291.2 us
    assert rt.call("scenarios.hcsr04_irq:edges_at_one_instant") == [(3, 1470), (5, 1470), (3, 1470 + w), (5, 1470 + w)]


@pytest.mark.parametrize(
    "args,fragment",
    [
        ((5,), "irq handler 5"),
        (("go",), "irq handler 'go'"),
        (("print", 0), "irq trigger 0"),
        (("print", 4), "irq trigger 4"),
        (("print", -1), "irq trigger -1"),
        (("print", True), "irq trigger True"),
        (("print", 1.0), "irq trigger 1.0"),
        (("print", None), "irq trigger None"),
    ],
)
def test_stub_irq_bad_handler_or_trigger_is_refused_by_name(rt, args, fragment):
    msg = rt.call("scenarios.hcsr04_irq:bad_irq", args)
    assert "Pin 7" in msg and fragment in msg and "allowed" in msg, msg


def c_mm_per_us(temp_centi_c):
    """Datasheet speed of sound (331.3 + 0.606 T m/s) in mm/us, float oracle."""
    return (331.3 + 0.606 * temp_centi_c / 100) / 1000


def expected(d, temp, max_range):
    """(status, 0.1 mm) a perfect driver reports for a target d (0.1 mm) the model echoes in whole us."""
    if not 200 <= d <= 40000:
        return 1, -1  # the module holds its echo 38 ms: out of range
    w = round(2 * d / 10 / c_mm_per_us(temp))
    got = w * c_mm_per_us(temp) / 2 * 10
    if got > max_range + 0.5:
        return 1, -1
    if got < 200 - 0.5:
        return 4, -1  # too close: 2 cm itself echoes 116 us = 19.92 mm at 20 degC
    return 0, got


@pytest.mark.parametrize("temp", [-1000, 2000, 4500])
def test_irq_distances_match_the_datasheet_and_the_blocking_path(rt, temp):
    # 2 cm and 4 m are the module's range ends; 10 m and 1 cm are outside it.
    targets = [100, 199, 200, 201, 205, 1000, 5000, 9999, 10000, 25000, 39990, 40000, 40001, 100000]
    got = rt.call("scenarios.hcsr04_irq:distances", temp, targets, True)
    got_blocking = rt.call("scenarios.hcsr04_irq:distances", temp, targets, False)
    assert got == got_blocking  # the IRQ's timestamps judge every echo as time_pulse_us does
    for d, (fired, st, dist, st_buf) in zip(targets, got, strict=True):
        want_st, want_d = expected(d, temp, 40000)
        assert fired == 6 and st == st_buf == want_st, (d, st)
        if st == 0:
            assert abs(dist - want_d) <= 0.5 + 0.2, (d, dist, want_d)  # rounding + the 2**14 scale
        else:
            assert dist == -1


def test_timeouts_to_the_microsecond_and_faults(rt):
    to, missing, held, stuck, unplugged, ok, wait, early = rt.call("scenarios.hcsr04_irq:timeouts_and_faults")
    # 1 m at 20 degC: 5824 us round trip (rounded up), + 1/16, + 1000 us for the burst
    assert to == 5824 + 5824 // 16 + 1000
    assert missing == (6, 2)  # PENDING, then NO_ECHO
    assert held == (6, 1)  # PENDING, then OUT_OF_RANGE
    assert stuck == (3, 3, 0)  # STUCK, reported, no ping
    assert unplugged == 2
    assert ok[0] == 0 and abs(ok[1] - 3000) <= 2 and ok[2] == 0
    assert wait == (5, 5, ok[1], 0)  # fired again within 60 ms: WAIT, buffers as the last ping left them
    assert early[0] == 0 and abs(early[1] - 3000) <= 2 and early[3] and early[4] == 5  # then WAIT


def test_runner_wait_holds_the_20_ms_grid_to_the_us(rt):
    # Steps that take 3.456, 19.999, 23 (an overrun), 5, 45 (far behind) and 1 ms; hand-worked starts.
    busy = [3456, 19999, 23000, 5000, 45000, 1000]
    assert rt.call("scenarios.hcsr04_irq:wait_grid", 777, busy) == [
        0,
        20000,
        40000,
        63000,
        80000,
        125000,
        145000,
    ]


def test_a_port_without_pin_irq_falls_back_to_time_pulse_us(rt):
    split, rr_split, i, st, d, blocked = rt.call("scenarios.hcsr04_irq:without_pin_irq")
    assert (split, rr_split, i, st, blocked) == (False, False, 0, 0, True)  # same tick, blocking
    assert abs(d - 2500) <= 2


def test_main_build_times_the_echo_by_irq(rt):
    split, blocked, dist = rt.call("scenarios.runner:irq_sonar", 12)
    assert split is True
    assert blocked <= 2 + 10 + 600  # the trigger and the driver's start-up sleeps, never an echo
    assert [abs(d - (3000 + 1000 * k)) <= 2 for k, d in enumerate(dist)] == [True] * 5
