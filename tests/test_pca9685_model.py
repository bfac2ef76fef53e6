"""The PCA9685 model against the NXP data sheet (both runtimes) and against Adafruit's driver (CPython)."""

from fractions import Fraction

import pytest

from hexapod_host.stubs import busio as fakes_busio

PRE = """
import machine
from i2c_bus import I2CBus
from pca9685_model import PCA9685Model
bus = I2CBus()
chip = bus.attach(PCA9685Model(0x40))
i2c = machine.I2C(0, bus=bus)
def w(reg, *vals):
    i2c.writeto_mem(0x40, reg, bytes(vals))
def r(reg, n=1):
    return list(i2c.readfrom_mem(0x40, reg, n))
def wake():
    w(0, 0x20)
    bus.sleep_us(500)
    w(0, 0xA0)
"""


def test_power_on_defaults_read_over_i2c(rt):
    src = (
        PRE
        + """
w(0, 0x31)  # AI on (still asleep) to read everything in one go
regs = r(0, 70)
print([regs[0:6], regs[6:10], regs[66:70], r(0xFA, 4), r(0xFE), r(0x46)])
"""
    )
    head, led0, led15, all_led, prescale, reserved = rt.value(src)
    assert head == [0x31, 0x04, 0xE2, 0xE4, 0xE8, 0xE0]
    assert led0 == led15 == [0, 0, 0, 0x10]  # full OFF at power-on
    assert all_led == [0, 0, 0, 0]  # ALL_LED registers read back zero
    assert prescale == [0x1E]
    assert reserved == [0]
    assert rt.value(PRE + "print(r(0))") == [0x11]  # SLEEP | ALLCALL


def test_auto_increment_wraps_as_the_data_sheet_says(rt):
    src = (
        PRE
        + """
w(0, 0x30)
w(0x44, 0x11, 0x12, 0x31)  # LED15_OFF_L, LED15_OFF_H, then wraps to MODE1
a = [chip.regs[0x44], chip.regs[0x45], chip.regs[0]]
w(0xFE, 0x79, 0x30)  # PRE_SCALE then MODE1
b = [chip.regs[0xFE], chip.regs[0]]
c = r(0xFD, 3)  # ALL_LED_OFF_H (reads 0), PRE_SCALE, MODE1
w(0, 0x10)  # AI off: every byte goes to the same register
w(0x06, 1, 2, 3)
d = [chip.regs[6], chip.regs[7]]
print([a, b, c, d])
"""
    )
    a, b, c, d = rt.value(src)
    assert a == [0x11, 0x12, 0x31]  # bits 7:5 of OFF_H are not writable: 0x12 kept whole (bit 4 + count)
    assert b == [0x79, 0x30]
    assert c == [0, 0x79, 0x30]
    assert d == [3, 0]


def test_prescale_written_only_while_asleep(rt):
    src = (
        PRE
        + """
w(0xFE, 0x79)
a = chip.prescale()
wake()
w(0xFE, 0x05)
b = chip.prescale()
w(0, 0x30)
w(0xFE, 0x01)
print([a, b, chip.prescale(), chip.violation_codes()])
"""
    )
    a, b, c, codes = rt.value(src)
    assert (a, b, c) == (0x79, 0x79, 3)  # ignored while awake; the hardware forces >= 3
    assert codes == ["PRESCALE_WHILE_AWAKE", "PRESCALE_BELOW_MIN"]


def test_restart_needs_500us_after_wake(rt):
    src = (
        PRE
        + """
w(0, 0x20); bus.sleep_us(400); w(0, 0xA0)
a = chip.violation_codes()
chip.clear_violations()
w(0, 0x30); w(0, 0x20); bus.sleep_us(500); w(0, 0xA0)
b = chip.violation_codes()
w(0, 0xB0)  # RESTART with SLEEP in the same byte
print([a, b, chip.violation_codes()])
"""
    )
    assert rt.value(src) == [["RESTART_TOO_SOON"], [], ["RESTART_WHILE_ASLEEP"]]


def test_sleep_holds_pwm_for_restart(rt):
    src = (
        PRE
        + """
wake()
w(0x06, 0, 0, 0x2C, 0x01)  # 300 counts
a = chip.pulse_us(0)
w(0, 0x30)  # sleep while running: RESTART set, outputs stop
b = [chip.pulse_us(0), r(0)[0]]
w(0, 0x20)  # awake, restart still pending: channels stay stopped
c = chip.pulse_us(0)
bus.sleep_us(600)
w(0, 0xA0)
print([a, b, c, chip.pulse_us(0), r(0)[0], chip.violation_codes()])
"""
    )
    a, b, c, d, mode1, codes = rt.value(src)
    assert a == d == (300 * 31 * 10**9 // 25000000 + 500) // 1000  # prescale 0x1E at 25 MHz
    assert b == [0, 0xB0]
    assert c == 0
    assert mode1 == 0x20
    assert codes == []


def test_full_on_full_off_and_precedence(rt):
    src = (
        PRE
        + """
wake()
w(0x06, 0, 0x10, 0, 0)  # full ON
a = chip.pulse_ns(0)
w(0x06, 0, 0x10, 0, 0x10)  # both: full OFF wins
b = chip.pulse_ns(0)
w(0x06, 0xF0, 0x0F, 0x10, 0x00)  # ON 4080, OFF 16: the pulse wraps the period end
c = list(chip.counts(0))
print([a, chip.period_ns(), b, c, chip.pulse_ns(0)])
"""
    )
    a, period, b, counts, wrapped = rt.value(src)
    assert a == period == 4096 * 31 * 10**9 // 25000000
    assert b == 0
    assert counts == [4080, 16, False, False]
    assert wrapped == (32 * 31 * 10**9 + 12500000) // 25000000


def test_frequency_follows_data_sheet_formula(rt):
    src = (
        PRE
        + """
out = []
for p in (3, 0x1E, 121, 255):
    w(0xFE, p)
    out.append([chip.prescale(), chip.frequency_mhz()])
chip.osc_hz = 25750000
out.append(chip.frequency_mhz())
print(out)
"""
    )
    *rows, fast = rt.value(src)
    for p, mhz in rows:
        assert mhz == round(Fraction(25_000_000_000, 4096 * (p + 1)))
    assert [rows[0][1] // 1000, rows[1][1] // 1000] == [1525, 196]  # UM10574: 1526 Hz max, "200 Hz" default
    assert fast == round(Fraction(25_750_000_000, 4096 * 256))


def test_reset_models_brownout(rt):
    src = (
        PRE
        + """
wake()
w(0xFE, 0x79); w(1, 0x0C); w(0x06, 0, 0, 0x2C, 0x01)
n = chip.resets
chip.reset()
print([r(0), r(1), r(0xFE), r(6) + r(9), chip.running(), chip.pulse_us(0), chip.resets - n])
"""
    )
    assert rt.value(src) == [[0x11], [0x04], [0x1E], [0, 0x10], False, 0, 1]


def test_software_reset_general_call(rt):
    src = (
        PRE
        + """
wake()
i2c.writeto(0, b'\\x06')
print([r(0), chip.resets])
"""
    )
    assert rt.value(src) == [[0x11], 1]


def test_extclk_is_sticky_and_must_follow_sleep(rt):
    src = (
        PRE
        + """
chip.ext_clock_hz = 50000000
w(0, 0x10); w(0, 0x50)
a = [r(0)[0], chip.clock_hz(), chip.violation_codes()]
w(0, 0x10)  # writing 0 does not clear EXTCLK
b = r(0)[0]
other = bus.attach(PCA9685Model(0x41))
i2c.writeto_mem(0x41, 0, b'\\x20'); i2c.writeto_mem(0x41, 0, b'\\x60')
print([a, b, other.violation_codes()])
"""
    )
    a, b, other = rt.value(src)
    assert a == [0x50, 50000000, []]
    assert b == 0x50
    assert other == ["EXTCLK_WHILE_AWAKE"]


def test_forbidden_sequences_are_flagged(rt):
    src = (
        PRE
        + """
w(0x06, 0, 0, 0x2C, 0x01)  # PWM written while asleep
a = chip.violation_codes(); chip.clear_violations()
w(0, 0x20); w(0x06, 0, 0, 0x2C, 0x01)  # right after wake
b = chip.violation_codes(); chip.clear_violations()
bus.sleep_us(500)
w(0x50, 1); w(0xFF, 1)
c = chip.violation_codes(); chip.clear_violations()
w(0x0A, 0x10, 0, 0x10, 0)  # LED1 ON == OFF == 16
print([a, b, c, chip.violation_codes()])
"""
    )
    assert rt.value(src) == [
        ["LED_WRITE_ASLEEP"],
        ["LED_WRITE_OSC_UNSTABLE"],
        ["RESERVED_WRITE", "RESERVED_WRITE"],
        ["ON_EQUALS_OFF"],
    ]


@pytest.mark.parametrize("och, expect_changed", [(0, True), (1, False)])
def test_output_change_on_ack_keeps_half_written_channels(rt, och, expect_changed):
    """OCH=0: a write cut by a NACK reaches the outputs at STOP; OCH=1: only whole channels do."""
    src = (
        PRE
        + """
wake()
w(1, 0x04 | %d)
w(0x06, 0, 0, 0xFF, 0x01)  # 511 counts
before = list(chip.counts(0))
bus.fault(0x40, 'nack', byte=5)  # pointer, ON_L, ON_H, OFF_L arrive; OFF_H is NACKed
try:
    i2c.writeto(0x40, bytes([0x06, 0, 0, 0x00, 0x02]))
except OSError:
    pass
print([before, list(chip.counts(0))])
"""
        % (och * 8)
    )
    before, after = rt.value(src)
    assert before == [0, 511, False, False]
    # Half a channel: new OFF_L (0x00) with the old OFF_H (0x01) is 256 counts, not 511 or 512.
    assert (after == [0, 256, False, False]) is expect_changed
    assert (after == before) is not expect_changed


def test_allcall_write_reaches_every_chip(rt):
    src = (
        PRE
        + """
other = bus.attach(PCA9685Model(0x41))
i2c.writeto_mem(0x70, 0xFE, b'\\x79')
print([chip.prescale(), other.prescale()])
"""
    )
    assert rt.value(src) == [0x79, 0x79]


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
