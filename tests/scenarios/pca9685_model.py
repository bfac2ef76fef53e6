"""The PCA9685 model (host/stubs pca9685_model) driven over the stub machine.I2C, register by register."""

import machine
from i2c_bus import I2CBus
from pca9685_model import PCA9685Model


class Chip:
    """A bus, a model at 0x40 (power-on state) and machine.I2C on the bus."""

    def __init__(self):
        self.bus = I2CBus()
        self.chip = self.bus.attach(PCA9685Model(0x40))
        self.i2c = machine.I2C(0, bus=self.bus)

    def w(self, reg, *vals):
        self.i2c.writeto_mem(0x40, reg, bytes(vals))

    def r(self, reg, n=1):
        return list(self.i2c.readfrom_mem(0x40, reg, n))

    def wake(self):
        """Out of SLEEP with AI, 500 us for the oscillator, then RESTART."""
        self.w(0, 0x20)
        self.bus.sleep_us(500)
        self.w(0, 0xA0)


def power_on():
    """[MODE1..ALLCALLADR, LED0's four, LED15's four, ALL_LED's four, PRE_SCALE, register 0x46] with AI
    set, and MODE1 as it was."""
    c = Chip()
    first = c.r(0)
    c.w(0, 0x31)  # AI on (still asleep) to read everything in one go
    regs = c.r(0, 70)
    return [regs[0:6], regs[6:10], regs[66:70], c.r(0xFA, 4), c.r(0xFE), c.r(0x46), first]


def auto_increment():
    """[LED15_OFF_L, LED15_OFF_H, MODE1 after a wrapping burst], [PRE_SCALE, MODE1 after another],
    a read across the end, [LED0_ON_L, LED0_ON_H] after a burst with AI off."""
    c = Chip()
    chip = c.chip
    c.w(0, 0x30)
    c.w(0x44, 0x11, 0x12, 0x31)  # LED15_OFF_L, LED15_OFF_H, then wraps to MODE1
    a = [chip.regs[0x44], chip.regs[0x45], chip.regs[0]]
    c.w(0xFE, 0x79, 0x30)  # PRE_SCALE then MODE1
    b = [chip.regs[0xFE], chip.regs[0]]
    d3 = c.r(0xFD, 3)  # ALL_LED_OFF_H (reads 0), PRE_SCALE, MODE1
    c.w(0, 0x10)  # AI off: every byte goes to the same register
    c.w(0x06, 1, 2, 3)
    d = [chip.regs[6], chip.regs[7]]
    return [a, b, d3, d]


def prescale_writes():
    """[prescale written asleep, after a write awake, after writing 1 asleep, violations]."""
    c = Chip()
    chip = c.chip
    c.w(0xFE, 0x79)
    a = chip.prescale()
    c.wake()
    c.w(0xFE, 0x05)
    b = chip.prescale()
    c.w(0, 0x30)
    c.w(0xFE, 0x01)
    return [a, b, chip.prescale(), chip.violation_codes()]


def restart_timing():
    """Violations of a RESTART 400 us after wake, of one 500 us after, of RESTART with SLEEP."""
    c = Chip()
    chip = c.chip
    c.w(0, 0x20)
    c.bus.sleep_us(400)
    c.w(0, 0xA0)
    a = chip.violation_codes()
    chip.clear_violations()
    c.w(0, 0x30)
    c.w(0, 0x20)
    c.bus.sleep_us(500)
    c.w(0, 0xA0)
    b = chip.violation_codes()
    c.w(0, 0xB0)  # RESTART with SLEEP in the same byte
    return [a, b, chip.violation_codes()]


def sleep_and_restart():
    """[channel 0's us running, [us, MODE1] asleep, us awake before RESTART, us after, MODE1, violations]."""
    c = Chip()
    chip = c.chip
    c.wake()
    c.w(0x06, 0, 0, 0x2C, 0x01)  # 300 counts
    a = chip.pulse_us(0)
    c.w(0, 0x30)  # sleep while running: RESTART set, outputs stop
    b = [chip.pulse_us(0), c.r(0)[0]]
    c.w(0, 0x20)  # awake, restart still pending: channels stay stopped
    d = chip.pulse_us(0)
    c.bus.sleep_us(600)
    c.w(0, 0xA0)
    return [a, b, d, chip.pulse_us(0), c.r(0)[0], chip.violation_codes()]


def full_on_off():
    """[full ON's ns, the period ns, full ON + full OFF's ns, counts of ON 4080 OFF 16, its ns]."""
    c = Chip()
    chip = c.chip
    c.wake()
    c.w(0x06, 0, 0x10, 0, 0)  # full ON
    a = chip.pulse_ns(0)
    c.w(0x06, 0, 0x10, 0, 0x10)  # both: full OFF wins
    b = chip.pulse_ns(0)
    c.w(0x06, 0xF0, 0x0F, 0x10, 0x00)  # ON 4080, OFF 16: the pulse wraps the period end
    counts = list(chip.counts(0))
    return [a, chip.period_ns(), b, counts, chip.pulse_ns(0)]


def frequencies(prescales, fast_osc_hz):
    """[[prescale, mHz]] of each prescale written, then the mHz at the last with the oscillator at fast_osc_hz."""
    c = Chip()
    chip = c.chip
    out = []
    for p in prescales:
        c.w(0xFE, p)
        out.append([chip.prescale(), chip.frequency_mhz()])
    chip.osc_hz = fast_osc_hz
    out.append(chip.frequency_mhz())
    return out


def brownout():
    """After a reset() of a running, configured chip: [MODE1, MODE2, PRE_SCALE, LED0_ON_L + LED0_OFF_H,
    running, channel 0's us, resets counted]."""
    c = Chip()
    chip = c.chip
    c.wake()
    c.w(0xFE, 0x79)
    c.w(1, 0x0C)
    c.w(0x06, 0, 0, 0x2C, 0x01)
    n = chip.resets
    chip.reset()
    return [c.r(0), c.r(1), c.r(0xFE), c.r(6) + c.r(9), chip.running(), chip.pulse_us(0), chip.resets - n]


def software_reset():
    """[MODE1, resets] after the general call's SWRST (0x06 to address 0)."""
    c = Chip()
    c.wake()
    c.i2c.writeto(0, b"\x06")
    return [c.r(0), c.chip.resets]


def extclk():
    """[[MODE1, clock Hz, violations] after EXTCLK set asleep, MODE1 after writing it 0, a second chip's
    violations after EXTCLK set awake]."""
    c = Chip()
    chip = c.chip
    chip.ext_clock_hz = 50000000
    c.w(0, 0x10)
    c.w(0, 0x50)
    a = [c.r(0)[0], chip.clock_hz(), chip.violation_codes()]
    c.w(0, 0x10)  # writing 0 does not clear EXTCLK
    b = c.r(0)[0]
    other = c.bus.attach(PCA9685Model(0x41))
    c.i2c.writeto_mem(0x41, 0, b"\x20")
    c.i2c.writeto_mem(0x41, 0, b"\x60")
    return [a, b, other.violation_codes()]


def forbidden_sequences():
    """Violations of: LED written asleep, right after wake, reserved registers, ON == OFF."""
    c = Chip()
    chip = c.chip
    c.w(0x06, 0, 0, 0x2C, 0x01)  # PWM written while asleep
    a = chip.violation_codes()
    chip.clear_violations()
    c.w(0, 0x20)
    c.w(0x06, 0, 0, 0x2C, 0x01)  # right after wake
    b = chip.violation_codes()
    chip.clear_violations()
    c.bus.sleep_us(500)
    c.w(0x50, 1)
    c.w(0xFF, 1)
    d = chip.violation_codes()
    chip.clear_violations()
    c.w(0x0A, 0x10, 0, 0x10, 0)  # LED1 ON == OFF == 16
    return [a, b, d, chip.violation_codes()]


def nacked_channel(och):
    """[channel 0's counts at 511, its counts after a write whose OFF_H is NACKed], MODE2.OCH = och."""
    c = Chip()
    chip = c.chip
    c.wake()
    c.w(1, 0x04 | och * 8)
    c.w(0x06, 0, 0, 0xFF, 0x01)  # 511 counts
    before = list(chip.counts(0))
    c.bus.fault(0x40, "nack", byte=5)  # pointer, ON_L, ON_H, OFF_L arrive; OFF_H is NACKed
    try:  # noqa: SIM105 (MicroPython has no contextlib)
        c.i2c.writeto(0x40, bytes([0x06, 0, 0, 0x00, 0x02]))
    except OSError:
        pass
    return [before, list(chip.counts(0))]


def allcall():
    """[prescale of 0x40, of 0x41] after a PRE_SCALE write to the ALLCALL address 0x70."""
    c = Chip()
    other = c.bus.attach(PCA9685Model(0x41))
    c.i2c.writeto_mem(0x70, 0xFE, b"\x79")
    return [c.chip.prescale(), other.prescale()]
