"""The PCA9685 model against the NXP data sheet (both runtimes) and against Adafruit's driver (CPython).

The both-runtime side is tests/scenarios/pca9685_model.py: register writes and reads over the stub I2C."""

from fractions import Fraction

import pytest

from hexapod_host.stubs import busio as fakes_busio


def test_power_on_defaults_read_over_i2c(rt):
    head, led0, led15, all_led, prescale, reserved, mode1 = rt.call("scenarios.pca9685_model:power_on")
    assert head == [0x31, 0x04, 0xE2, 0xE4, 0xE8, 0xE0]
    assert led0 == led15 == [0, 0, 0, 0x10]  # full OFF at power-on
    assert all_led == [0, 0, 0, 0]  # ALL_LED registers read back zero
    assert prescale == [0x1E]
    assert reserved == [0]
    assert mode1 == [0x11]  # SLEEP | ALLCALL


def test_auto_increment_wraps_as_the_data_sheet_says(rt):
    a, b, c, d = rt.call("scenarios.pca9685_model:auto_increment")
    assert a == [0x11, 0x12, 0x31]  # bits 7:5 of OFF_H are not writable: 0x12 kept whole (bit 4 + count)
    assert b == [0x79, 0x30]
    assert c == [0, 0x79, 0x30]
    assert d == [3, 0]


def test_prescale_written_only_while_asleep(rt):
    a, b, c, codes = rt.call("scenarios.pca9685_model:prescale_writes")
    assert (a, b, c) == (0x79, 0x79, 3)  # ignored while awake; the hardware forces >= 3
    assert codes == ["PRESCALE_WHILE_AWAKE", "PRESCALE_BELOW_MIN"]


def test_restart_needs_500us_after_wake(rt):
    assert rt.call("scenarios.pca9685_model:restart_timing") == [["RESTART_TOO_SOON"], [], ["RESTART_WHILE_ASLEEP"]]


def test_sleep_holds_pwm_for_restart(rt):
    a, b, c, d, mode1, codes = rt.call("scenarios.pca9685_model:sleep_and_restart")
    assert a == d == (300 * 31 * 10**9 // 25000000 + 500) // 1000  # prescale 0x1E at 25 MHz
    assert b == [0, 0xB0]
    assert c == 0
    assert mode1 == 0x20
    assert codes == []


def test_full_on_full_off_and_precedence(rt):
    a, period, b, counts, wrapped = rt.call("scenarios.pca9685_model:full_on_off")
    assert a == period == 4096 * 31 * 10**9 // 25000000
    assert b == 0
    assert counts == [4080, 16, False, False]
    assert wrapped == (32 * 31 * 10**9 + 12500000) // 25000000


def test_frequency_follows_data_sheet_formula(rt):
    *rows, fast = rt.call("scenarios.pca9685_model:frequencies", [3, 0x1E, 121, 255], 25750000)
    assert [p for p, _ in rows] == [3, 0x1E, 121, 255]
    for p, mhz in rows:
        assert mhz == round(Fraction(25_000_000_000, 4096 * (p + 1)))
    assert [rows[0][1] // 1000, rows[1][1] // 1000] == [1525, 196]  # UM10574: 1526 Hz max, "200 Hz" default
    assert fast == round(Fraction(25_750_000_000, 4096 * 256))


def test_reset_models_brownout(rt):
    assert rt.call("scenarios.pca9685_model:brownout") == [[0x11], [0x04], [0x1E], [0, 0x10], False, 0, 1]


def test_software_reset_general_call(rt):
    assert rt.call("scenarios.pca9685_model:software_reset") == [[0x11], 1]


def test_extclk_is_sticky_and_must_follow_sleep(rt):
    a, b, other = rt.call("scenarios.pca9685_model:extclk")
    assert a == [0x50, 50000000, []]
    assert b == 0x50
    assert other == ["EXTCLK_WHILE_AWAKE"]


def test_forbidden_sequences_are_flagged(rt):
    assert rt.call("scenarios.pca9685_model:forbidden_sequences") == [
        ["LED_WRITE_ASLEEP"],
        ["LED_WRITE_OSC_UNSTABLE"],
        ["RESERVED_WRITE", "RESERVED_WRITE"],
        ["ON_EQUALS_OFF"],
    ]


@pytest.mark.parametrize("och, expect_changed", [(0, True), (1, False)])
def test_output_change_on_ack_keeps_half_written_channels(rt, och, expect_changed):
    """OCH=0: a write cut by a NACK reaches the outputs at STOP; OCH=1: only whole channels do."""
    before, after = rt.call("scenarios.pca9685_model:nacked_channel", och)
    assert before == [0, 511, False, False]
    # Half a channel: new OFF_L (0x00) with the old OFF_H (0x01) is 256 counts, not 511 or 512.
    assert (after == [0, 256, False, False]) is expect_changed
    assert (after == before) is not expect_changed


def test_allcall_write_reaches_every_chip(rt):
    assert rt.call("scenarios.pca9685_model:allcall") == [0x79, 0x79]


# -- against Adafruit's driver (CPython) ------------------------------------------------------


def adafruit_on_model(osc_model=25_000_000, reference=25_000_000):
    import adafruit_pca9685
    from i2c_bus import I2CBus
    from pca9685_model import PCA9685Model

    bus = I2CBus()
    chip = bus.attach(PCA9685Model(0x40, osc_hz=osc_model))
    with fakes_busio.model_time(bus):
        pca = adafruit_pca9685.PCA9685(fakes_busio.I2C(bus), reference_clock_speed=reference)
    return bus, chip, pca


@pytest.mark.parametrize("freq", [24, 50, 60, 100, 200, 333, 1000, 1526])
def test_adafruit_frequency_setter_gives_data_sheet_prescale(freq):
    bus, chip, pca = adafruit_on_model()
    with fakes_busio.model_time(bus):
        pca.frequency = freq
    exact = Fraction(25_000_000, 4096 * freq)
    assert chip.prescale() == round(exact) - 1
    # Adafruit's frequency getter and the model's output rate are the same formula.
    assert chip.frequency_mhz() == round(pca.frequency * 1000)
    assert chip.violation_codes() == []
    assert chip.running()


def test_adafruit_duty_cycle_special_cases_on_model():
    bus, chip, pca = adafruit_on_model()
    with fakes_busio.model_time(bus):
        pca.frequency = 50
    pca.channels[0].duty_cycle = 0xFFFF
    pca.channels[1].duty_cycle = 0
    pca.channels[2].duty_cycle = 0x8000
    assert chip.pulse_ns(0) == chip.period_ns()
    assert chip.pulse_ns(1) == 0
    assert chip.counts(2) == (0, 0x800, False, False)
    assert abs(chip.pulse_ns(2) * 2 - chip.period_ns()) <= 1
    assert pca.channels[0].duty_cycle == 0xFFFF  # Adafruit reads the full-on bit back from the model
    assert pca.channels[2].duty_cycle == 0x8000


@pytest.mark.parametrize("trimmed", [False, True])
def test_fast_oscillator_shortens_pulses_unless_trimmed(trimmed):
    fast = 25_750_000  # 3 % fast
    bus, chip, pca = adafruit_on_model(osc_model=fast, reference=fast if trimmed else 25_000_000)
    with fakes_busio.model_time(bus):
        pca.frequency = 50
    duty = int(1500 * pca.frequency / 1_000_000 * 0xFFFF)  # adafruit_motor's pulse -> duty formula
    pca.channels[0].duty_cycle = duty
    us = chip.pulse_ns(0) / 1000
    if trimmed:
        assert abs(us - 1500) < 6  # within about one count (4.7 us)
    else:
        assert 1500 * 0.96 < us < 1500 * 0.985  # the untrimmed chip runs fast: pulses ~3 % short
