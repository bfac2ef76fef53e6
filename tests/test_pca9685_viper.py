"""The viper stage (drivers/_pca9685_viper.py, MicroPython only) writes the very register bytes of
the plain path (CPython), and both the counts of the data sheet's formula, on every pulse width."""

from fractions import Fraction

SRC = """
import machine
from i2c_bus import I2CBus
from pca9685_model import PCA9685Model
from drivers import pca9685
bus = I2CBus()
out = [pca9685._put is not None]
for osc, freq, stagger in ((25000000, 50, 0), (25750000, 50, 500), (24250000, 60, 333), (29000000, 330, 0)):
    bus.attach(PCA9685Model(0x40, osc_hz=osc))
    c = pca9685.PCA9685(machine.I2C(0, bus=bus), 0x40, osc_hz=osc, freq_hz=freq, channels=4, stagger_us=stagger,
                        sleep_us=bus.sleep_us)
    counts = []
    for us in range(pca9685.PULSE_MIN_US, pca9685.PULSE_MAX_US + 1):
        ch = us % 4
        c.stage(ch, us)
        f = c._frame
        i = 1 + 4 * ch
        counts.append((f[i] | f[i + 1] << 8, f[i + 2] | f[i + 3] << 8))
    out.append((osc, freq, c.prescale, counts))
    bus.detach(0x40)
print(out)
"""


def test_viper_stage_bytes_equal_the_plain_path_and_the_data_sheet(both_runtimes):
    cp, mp = both_runtimes(SRC, heapsize="4m")
    cp, mp = eval(cp.strip().splitlines()[-1]), eval(mp.strip().splitlines()[-1])  # noqa: S307 (our own repr)
    assert cp[0] is False and mp[0] is True  # CPython stages in Python, the VM in viper
    assert cp[1:] == mp[1:]  # byte for byte, 4 oscillator and frequency settings x 2001 pulse widths
    for osc, _freq, prescale, counts in cp[1:]:
        for k, (on, off) in enumerate(counts):
            us = 500 + k  # PULSE_MIN_US..PULSE_MAX_US
            exact = Fraction(us * osc, 1000000 * (prescale + 1))  # data sheet: counts = t * osc / (prescale + 1)
            assert off - on == int(exact + Fraction(1, 2)), (osc, us, on, off)  # rounded half up
