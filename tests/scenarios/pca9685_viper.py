"""drivers/pca9685.py's staging (viper on MicroPython, Python on CPython): the frame bytes it leaves."""

import machine
from i2c_bus import I2CBus
from pca9685_model import PCA9685Model

from drivers import pca9685
from hexapod.servo import ServoMap


def stage_counts(settings):
    """[viper staging in use] + per (osc_hz, freq_hz, stagger_us): (osc, freq, prescale, [(on, off)
    counts of each pulse width PULSE_MIN_US..PULSE_MAX_US, staged on channel us % 4])]."""
    bus = I2CBus()
    out = [pca9685._put is not None]
    for osc, freq, stagger in settings:
        bus.attach(PCA9685Model(0x40, osc_hz=osc))
        c = pca9685.PCA9685(
            machine.I2C(0, bus=bus),
            0x40,
            osc_hz=osc,
            freq_hz=freq,
            channels=4,
            stagger_us=stagger,
            sleep_us=bus.sleep_us,
        )
        counts = []
        for us in range(pca9685.PULSE_MIN_US, pca9685.PULSE_MAX_US + 1):
            ch = us % 4
            c.stage(ch, us)
            f = c._frame
            i = 1 + 4 * ch
            counts.append((f[i] | f[i + 1] << 8, f[i + 2] | f[i + 3] << 8))
        out.append((osc, freq, c.prescale, counts))
        bus.detach(0x40)
    return out


def bank_frames(limits, channels, cases, bad_values):
    """[one-call staging in use] + per pulse case: (both chips' frame bytes, ServoBank.clamped), servo 3's
    map swapped and servo 5's recalibrated before case 20; then per bad value for servo 7:
    (exception name, message, frames unchanged) or ("no error",)."""
    bus = I2CBus()
    bus.attach(PCA9685Model(0x40, osc_hz=25000000))
    bus.attach(PCA9685Model(0x41, osc_hz=25750000))
    i2c = machine.I2C(0, bus=bus)
    chips = [
        pca9685.PCA9685(i2c, 0x40, osc_hz=25000000, channels=9, stagger_us=100, sleep_us=bus.sleep_us),
        pca9685.PCA9685(i2c, 0x41, osc_hz=25750000, channels=9, sleep_us=bus.sleep_us),
    ]
    maps = [ServoMap(centre_us=(lo + hi) // 2, min_us=lo, max_us=hi) for lo, hi in limits]
    bank = pca9685.ServoBank(chips, channels, maps)
    out = [pca9685._stage_all is not None]

    def frames():
        return [bytes(c._frame) for c in chips]

    for k, p in enumerate(cases):
        if k == 20:
            bank._maps[3] = ServoMap(centre_us=1450, min_us=1400, max_us=1500)  # a swapped ServoMap
            bank._maps[5].min_us = 1000  # a recalibrated one
        bank.write(p)
        out.append((frames(), bank.clamped))
    for v in bad_values:
        p = [1500] * 18
        p[7] = v
        before = frames()
        try:
            bank.write(p)
            out.append(("no error",))
        except Exception as e:
            out.append((type(e).__name__, str(e), frames() == before))
    return out
