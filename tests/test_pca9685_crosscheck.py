"""Cross-check on CPython: our driver, its CircuitPython backend, adafruit_pca9685 and
adafruit_servokit leave the same LED registers in the chip model for the same 18 pulse widths
(Adafruit within one count: it truncates where we round), and what each costs on the wire."""

import math
from fractions import Fraction

import machine
import pytest
from i2c_bus import I2CBus

from drivers import cp_pca9685
from drivers.pca9685 import PCA9685, ServoBank
from hexapod.servo import ServoMap
from hexapod_host.bench.i2c import CMAP, OSC, new_bus, servokit_servos
from hexapod_host.stubs import busio as fakes_busio

PULSES = [600, 777, 901, 1000, 1111, 1234, 1333, 1499, 1500, 1501, 1618, 1750, 1801, 1999, 2048, 2222, 2345, 2400]
WIDE = [ServoMap(min_us=500, max_us=2500) for _ in range(18)]


def led_counts(models):
    """(on, off) of the 18 servo channels, from the registers the outputs run."""
    return [models[0x40].counts(k)[:2] for k in range(16)] + [models[0x41].counts(k)[:2] for k in range(2)]


def ours(backend="micropython"):
    bus, models = new_bus()
    if backend == "micropython":
        i2c = machine.I2C(0, bus=bus)
        chips = [
            PCA9685(i2c, 0x40, osc_hz=OSC[0x40], sleep_us=bus.sleep_us, check_every=0),
            PCA9685(i2c, 0x41, osc_hz=OSC[0x41], channels=2, sleep_us=bus.sleep_us, check_every=0),
        ]
    else:
        i2c = fakes_busio.I2C(bus)
        with fakes_busio.model_time(bus):
            chips = [
                cp_pca9685.PCA9685(i2c, 0x40, osc_hz=OSC[0x40], check_every=0),
                cp_pca9685.PCA9685(i2c, 0x41, osc_hz=OSC[0x41], channels=2, check_every=0),
            ]
    bank = ServoBank(chips, CMAP, WIDE)
    bus.reset_stats()
    assert bank.write(PULSES) == 0
    return led_counts(models), bus.stats(), models


def servokit():
    bus, models = new_bus()
    servos = servokit_servos(bus, fakes_busio.I2C(bus))
    bus.reset_stats()
    for s, p in zip(servos, PULSES, strict=True):
        s.angle = p - 500
    return led_counts(models), bus.stats(), models


def adafruit_duty():
    """adafruit_pca9685 alone, with adafruit_motor's pulse -> 16-bit duty formula."""
    import adafruit_pca9685

    bus, models = new_bus()
    i2c = fakes_busio.I2C(bus)
    pcas = []
    freqs = []
    with fakes_busio.model_time(bus):
        for a in OSC:
            pca = adafruit_pca9685.PCA9685(i2c, address=a, reference_clock_speed=OSC[a])
            pca.frequency = 50
            pcas.append(pca)
            freqs.append(pca.frequency)  # read once: the getter costs a register read
    bus.reset_stats()
    for (c, ch), p in zip(CMAP, PULSES, strict=True):
        pcas[c].channels[ch].duty_cycle = adafruit_duty_of(p, freqs[c])
    return led_counts(models), bus.stats(), models


def adafruit_duty_of(pulse_us, freq):
    """adafruit_motor.servo's pulse width -> 16-bit duty cycle (floats, truncated)."""
    return int(pulse_us * freq / 1_000_000 * 0xFFFF)


def exact_counts():
    out = []
    for (c, _), p in zip(CMAP, PULSES, strict=True):
        osc = OSC[0x40 + c]
        prescale = round(Fraction(osc, 4096 * 50)) - 1
        out.append(Fraction(p * osc, 1_000_000 * (prescale + 1)))
    return out


def test_our_counts_are_the_exact_rounding():
    counts, _, models = ours()
    for (on, off), x in zip(counts, exact_counts(), strict=True):
        assert on == 0
        assert off == math.floor(x + Fraction(1, 2))
    assert models[0x40].violation_codes() == models[0x41].violation_codes() == []


@pytest.mark.parametrize("theirs", [servokit, adafruit_duty])
def test_adafruit_within_one_count_and_why(theirs):
    mine, _, _ = ours()
    other, _, models = theirs()
    assert models[0x40].violation_codes() == models[0x41].violation_codes() == []
    diffs = []
    for (on_a, off_a), (on_b, off_b), x in zip(mine, other, exact_counts(), strict=True):
        assert on_a == on_b == 0
        d = off_a - off_b
        diffs.append(d)
        assert d in (0, 1)  # never more than one count, and never above ours
        # Why: Adafruit scales to a 16-bit duty by * 0xFFFF (not 0x10000), truncates with int(),
        # and drops 4 bits with >> 4; each step can only lose, so it floors a slightly smaller
        # value where we round the exact one. The loss is x / 65536 from the scale plus under two
        # 16-bit steps (1/8 count) from ServoKit's truncated min duty and range. So one count
        # apart exactly when the exact count's fraction is >= 1/2, or within that loss above an integer.
        frac = x - math.floor(x)
        if d == 1:
            assert frac >= Fraction(1, 2) or frac < Fraction(1, 8) + x / 65536
        else:
            assert frac < Fraction(1, 2)
    assert 0 in diffs and 1 in diffs  # this pulse set shows both cases


def test_adafruit_registers_are_exactly_its_float_pipeline():
    """The one-count difference is nothing but Adafruit's arithmetic: replaying it predicts every register."""
    other, _, _ = adafruit_duty()
    for (c, _), p, (_, off) in zip(CMAP, PULSES, other, strict=True):
        osc = OSC[0x40 + c]
        prescale = int(osc / 4096.0 / 50 + 0.5) - 1  # adafruit_pca9685's frequency setter
        freq = osc / 4096 / (prescale + 1)  # its frequency getter
        assert off == adafruit_duty_of(p, freq) >> 4  # PWMChannel.duty_cycle drops 4 bits


def test_circuitpython_backend_leaves_identical_registers():
    mine, mine_stats, _ = ours()
    cp, cp_stats, models = ours("circuitpython")
    assert cp == mine
    assert (cp_stats["transactions"], cp_stats["bytes"]) == (mine_stats["transactions"], mine_stats["bytes"])
    assert models[0x40].violation_codes() == models[0x41].violation_codes() == []


def test_wire_cost_per_frame():
    _, mine, _ = ours()
    _, kit, _ = servokit()
    _, duty, _ = adafruit_duty()
    assert (mine["transactions"], mine["bytes"]) == (2, (2 + 64) + (2 + 8))
    # Adafruit writes one channel per transaction: address, register, ON_L ON_H OFF_L OFF_H.
    assert (kit["transactions"], kit["bytes"]) == (18, 18 * 6)
    assert (duty["transactions"], duty["bytes"]) == (18, 18 * 6)
    assert mine["time_ns"] < kit["time_ns"] * 0.7  # 16 STARTs, STOPs, addresses and register bytes fewer


def test_circuitpython_backend_faults_never_raise():
    bus, models = new_bus()
    spare = bus.detach(0x41)
    i2c = fakes_busio.I2C(bus)
    with fakes_busio.model_time(bus):
        chips = [
            cp_pca9685.PCA9685(i2c, 0x40, osc_hz=OSC[0x40], check_every=5, retries=1),
            cp_pca9685.PCA9685(i2c, 0x41, osc_hz=OSC[0x41], channels=2, check_every=5, retries=1),
        ]
        assert chips[1].offline and not chips[0].offline  # unplugged at boot: no exception
        bank = ServoBank(chips, CMAP, WIDE)
        assert bank.write(PULSES) & 8
        bus.attach(spare)
        spare.reset()
        bus.fault(0x40, "nack", byte=9)
        sts = [bank.write(PULSES) for _ in range(5)]
        models[0x40].reset()  # brownout
        sts += [bank.write(PULSES) for _ in range(5)]
    assert sts[0] & 1  # the NACK was retried
    assert any(s & 4 for s in sts[:5])  # chip 0x41 came back
    assert any(s & 4 for s in sts[5:])  # the brownout was found
    assert sts[-1] == 0
    assert chips[0].resets_seen == 1
    assert led_counts(models) == ours()[0]


def test_cp_backend_refuses_ext_clock():
    with pytest.raises(ValueError, match="ext_clock"):
        cp_pca9685.PCA9685(fakes_busio.I2C(I2CBus()), 0x40, ext_clock=True)


def test_fake_busio_requires_lock_like_circuitpython():
    i2c = fakes_busio.I2C(I2CBus())
    with pytest.raises(RuntimeError, match="lock"):
        i2c.writeto(0x40, b"\x00")
    assert i2c.try_lock() and not i2c.try_lock()
    with pytest.raises(OSError) as e:
        i2c.writeto(0x40, b"\x00")
    assert e.value.args[0] == 19
    i2c.unlock()


def test_servo_bank_from_board_same_on_both_backends():
    from drivers.pca9685 import servo_bank

    pca = {"pwm_hz": 50, "chips": tuple({"address": a, "osc_hz": o} for a, o in OSC.items())}
    table = tuple((0x40 if k < 9 else 0x41, k % 9, ServoMap(min_us=600, max_us=2400)) for k in range(18))
    results = []
    for backend in ("micropython", "circuitpython"):
        bus, models = new_bus()
        if backend == "micropython":
            bank = servo_bank(machine.I2C(0, bus=bus), pca, table, sleep_us=bus.sleep_us)
        else:
            with fakes_busio.model_time(bus):
                bank = cp_pca9685.servo_bank(fakes_busio.I2C(bus), pca, table)
        assert bank.write(PULSES) == 0
        results.append([models[0x40].counts(k) for k in range(9)] + [models[0x41].counts(k) for k in range(9)])
    assert results[0] == results[1]
