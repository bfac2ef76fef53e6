"""Register-level PCA9685 model (NXP PCA9685 product data sheet, Rev. 4), for the I2C bus model.

Runs on CPython and in the MicroPython VM; nothing on the write path allocates unless a
violation is recorded. What it follows from the data sheet:
  - power-on / brownout / SWRST defaults: MODE1 0x11 (SLEEP, ALLCALL), MODE2 0x04 (OUTDRV),
    SUBADR1-3 0xE2/0xE4/0xE8, ALLCALLADR 0xE0, LEDn full OFF (OFF_H bit 4), PRE_SCALE 0x1E
  - the first byte of a write sets the register pointer; with MODE1.AI the pointer moves on
    after each byte, wrapping from LED15_OFF_H (0x45) and from PRE_SCALE (0xFE) to MODE1
  - PRE_SCALE is written only while SLEEP is set (otherwise blocked: PRESCALE_WHILE_AWAKE);
    the hardware forces values below 3 up to 3 (PRESCALE_BELOW_MIN)
  - the oscillator needs 500 us after SLEEP clears: a RESTART written sooner (RESTART_TOO_SOON)
    or PWM registers accessed sooner (LED_WRITE_OSC_UNSTABLE) are flagged (not with EXTCLK)
  - sleeping with PWM running sets RESTART; outputs stay stopped until RESTART is written
    (or, with OCH=0, a PWM register write and STOP); a 1 written to RESTART clears it
  - EXTCLK is sticky and may only be set after SLEEP (EXTCLK_WHILE_AWAKE otherwise)
  - LEDn_ON_H / OFF_H bits 7:5 read 0; bit 4 is full ON / full OFF, full OFF wins
  - ALL_LED_* write all sixteen channels and read back zero
  - MODE2.OCH=0: outputs take the new PWM registers at STOP; OCH=1: a channel's output
    changes only once all four of its registers were written (so a write cut short by a NACK
    never outputs half a channel)
  - reserved registers (0x46-0xF9, TestMode 0xFF) are not written (RESERVED_WRITE)
  - ON and OFF counts equal (ON_EQUALS_OFF) and writing PWM registers while asleep
    (LED_WRITE_ASLEEP: the servos get no pulse until the chip wakes) are flagged
Model choices where the data sheet is silent: ALL_LED writes reach the outputs at STOP with
OCH=0 and at once with OCH=1; with AI the pointer walks through reserved registers one by one;
with OUTDRV=0 (open drain) a servo input sees no pulse (no pull-up on servo boards).

The real oscillator (osc_hz, settable, e.g. 3 % fast) sets what each channel outputs:
update rate = osc / (4096 * (PRE_SCALE + 1)), pulse = (OFF - ON) mod 4096 counts of
(PRE_SCALE + 1) / osc seconds each.
"""

from micropython import const

MODE1 = const(0x00)
MODE2 = const(0x01)
SUBADR1 = const(0x02)
ALLCALLADR = const(0x05)
LED0_ON_L = const(0x06)
LED15_OFF_H = const(0x45)
ALL_LED_ON_L = const(0xFA)
ALL_LED_OFF_H = const(0xFD)
PRE_SCALE = const(0xFE)

RESTART = const(0x80)
EXTCLK = const(0x40)
AI = const(0x20)
SLEEP = const(0x10)
SUB1 = const(0x08)
SUB2 = const(0x04)
SUB3 = const(0x02)
ALLCALL = const(0x01)
INVRT = const(0x10)
OCH = const(0x08)
OUTDRV = const(0x04)
FULL = const(0x10)  # bit 4 of LEDn_ON_H (full ON) and LEDn_OFF_H (full OFF)

OSC_HZ = const(25000000)
OSC_WAIT_US = const(500)
PRESCALE_MIN = const(3)
PRESCALE_DEFAULT = const(0x1E)

CODES = (
    "PRESCALE_WHILE_AWAKE",
    "PRESCALE_BELOW_MIN",
    "RESTART_TOO_SOON",
    "RESTART_WHILE_ASLEEP",
    "LED_WRITE_OSC_UNSTABLE",
    "LED_WRITE_ASLEEP",
    "EXTCLK_WHILE_AWAKE",
    "RESERVED_WRITE",
    "ON_EQUALS_OFF",
)
_PRESCALE_AWAKE = const(0)
_PRESCALE_MIN = const(1)
_RESTART_SOON = const(2)
_RESTART_ASLEEP = const(3)
_LED_UNSTABLE = const(4)
_LED_ASLEEP = const(5)
_EXTCLK_AWAKE = const(6)
_RESERVED = const(7)
_ON_EQ_OFF = const(8)


class PCA9685Model:
    """One PCA9685 at `address`; attach it to an I2CBus. osc_hz: real internal oscillator, Hz."""

    def __init__(self, address=0x40, *, osc_hz=OSC_HZ, ext_clock_hz=0):
        if not 20000000 <= osc_hz <= 30000000:
            raise ValueError("osc_hz: %r, the internal oscillator is 25 MHz nominal (allowed 20-30 MHz)" % (osc_hz,))
        self.address = address
        self.osc_hz = osc_hz
        self.ext_clock_hz = ext_clock_hz
        self.bus = None
        self.regs = bytearray(256)
        self.out = bytearray(64)  # LED registers the outputs run from (latched at STOP or ACK)
        self._written = bytearray(16)  # OCH=1: which of a channel's 4 bytes came since its last latch
        self.violations = []  # (code, detail), in order
        self._txn_flags = 0  # codes already recorded in this transaction
        self.reset()
        self.resets = 0

    # -- state ---------------------------------------------------------------------------
    def reset(self):
        """Power-on / brownout / SWRST: every register back to its default, SLEEP set."""
        r = self.regs
        for i in range(256):
            r[i] = 0
        r[MODE1] = SLEEP | ALLCALL
        r[MODE2] = OUTDRV
        r[SUBADR1] = 0xE2
        r[SUBADR1 + 1] = 0xE4
        r[SUBADR1 + 2] = 0xE8
        r[ALLCALLADR] = 0xE0
        for ch in range(16):
            r[LED0_ON_L + 4 * ch + 3] = FULL
        r[PRE_SCALE] = PRESCALE_DEFAULT
        for i in range(64):
            self.out[i] = r[LED0_ON_L + i]
            if i < 16:
                self._written[i] = 0
        self._ptr = 0
        self._first = False
        self._led_dirty = False
        self._woke_us = -1
        self.resets = getattr(self, "resets", 0) + 1

    def _now(self):
        return self.bus.now_us() if self.bus is not None else 0

    def _flag(self, code, detail):
        bit = 1 << code
        if self._txn_flags & bit:
            return
        self._txn_flags |= bit
        self.violations.append((CODES[code], detail))

    def violation_codes(self):
        """The codes recorded so far, in order (a code is recorded once per transaction)."""
        return [v[0] for v in self.violations]

    def clear_violations(self):
        self.violations = []

    # -- the I2C side (called by the bus) -------------------------------------------------
    def answers(self, addr):
        """True when addr is this chip's address, or an enabled ALLCALL/SUBADR address."""
        if addr == self.address:
            return True
        m = self.regs[MODE1]
        r = self.regs
        return (
            (m & ALLCALL and addr == r[ALLCALLADR] >> 1)
            or (m & SUB1 and addr == r[SUBADR1] >> 1)
            or (m & SUB2 and addr == r[SUBADR1 + 1] >> 1)
            or (m & SUB3 and addr == r[SUBADR1 + 2] >> 1)
        )

    def on_start(self, read):
        self._first = not read
        self._txn_flags = 0

    def on_write(self, b):
        if self._first:
            self._first = False
            self._ptr = b
            return True
        p = self._ptr
        self._write_reg(p, b)
        self._advance()
        return True

    def on_read(self):
        p = self._ptr
        if LED15_OFF_H < p < PRE_SCALE:
            v = 0  # reserved and ALL_LED registers read zero
        else:
            v = self.regs[p]
        self._advance()
        return v

    def on_stop(self):
        if self._led_dirty:
            self._led_dirty = False
            for i in range(64):
                self.out[i] = self.regs[LED0_ON_L + i]
            self.regs[MODE1] &= ~RESTART & 0xFF  # a PWM write + STOP (OCH=0) clears RESTART
            for ch in range(16):
                self._check_counts(ch)

    def general_call(self, b):
        """General call data byte: 0x06 is the software reset (SWRST)."""
        if b == 0x06:
            self.reset()
            return True
        return False

    # -- registers ------------------------------------------------------------------------
    def _advance(self):
        if self.regs[MODE1] & AI:
            p = self._ptr
            self._ptr = 0 if p == LED15_OFF_H or p >= PRE_SCALE else p + 1

    def _write_reg(self, p, v):
        r = self.regs
        if p == MODE1:
            self._write_mode1(v)
        elif p == MODE2:
            r[MODE2] = v & 0x1F
        elif p <= ALLCALLADR:
            r[p] = v
        elif p <= LED15_OFF_H:
            k = p - LED0_ON_L
            r[p] = v & 0x1F if k & 1 else v
            self._check_led_write()
            if r[MODE2] & OCH:
                ch = k >> 2
                self._written[ch] |= 1 << (k & 3)
                if k & 3 == 3:
                    if self._written[ch] == 0xF:
                        self._latch(ch)
                    self._written[ch] = 0
            else:
                self._led_dirty = True
        elif ALL_LED_ON_L <= p <= ALL_LED_OFF_H:
            j = p - ALL_LED_ON_L
            v = v & 0x1F if j & 1 else v
            for ch in range(16):
                r[LED0_ON_L + 4 * ch + j] = v
                if r[MODE2] & OCH:
                    self.out[4 * ch + j] = v
            self._check_led_write()
            if not r[MODE2] & OCH:
                self._led_dirty = True
        elif p == PRE_SCALE:
            if not r[MODE1] & SLEEP:
                self._flag(_PRESCALE_AWAKE, "PRE_SCALE=%d ignored: SLEEP is 0" % v)
            elif v < PRESCALE_MIN:
                self._flag(_PRESCALE_MIN, "PRE_SCALE=%d forced to 3" % v)
                r[p] = PRESCALE_MIN
            else:
                r[p] = v
        else:
            self._flag(_RESERVED, "write 0x%02x to reserved register 0x%02x" % (v, p))

    def _latch(self, ch):
        for j in range(4):
            self.out[4 * ch + j] = self.regs[LED0_ON_L + 4 * ch + j]
        self.regs[MODE1] &= ~RESTART & 0xFF
        self._check_counts(ch)

    def _check_counts(self, ch):
        o = self.out
        i = 4 * ch
        if o[i + 1] & FULL or o[i + 3] & FULL:
            return
        if o[i] == o[i + 2] and o[i + 1] == o[i + 3]:
            self._flag(_ON_EQ_OFF, "LED%d ON and OFF counts are equal" % ch)

    def _check_led_write(self):
        m = self.regs[MODE1]
        if m & SLEEP:
            self._flag(_LED_ASLEEP, "PWM register written while SLEEP is set: no output until wake")
        elif not m & EXTCLK and self._woke_us >= 0 and self._now() - self._woke_us < OSC_WAIT_US:
            self._flag(_LED_UNSTABLE, "PWM register written %d us after wake (< 500)" % (self._now() - self._woke_us))

    def _write_mode1(self, v):
        r = self.regs
        old = r[MODE1]
        now = self._now()
        new = (v & 0x7F) | (old & EXTCLK)  # EXTCLK is sticky: only a reset clears it
        if v & EXTCLK and not old & EXTCLK and not (old & SLEEP and v & SLEEP):
            self._flag(_EXTCLK_AWAKE, "EXTCLK set without SLEEP set first")
        restart = old & RESTART
        if v & SLEEP and not old & SLEEP:
            if self._any_output():
                restart = RESTART  # PWM was running: held for a restart
            self._woke_us = -1
        elif old & SLEEP and not v & SLEEP:
            self._woke_us = now
        if v & RESTART:
            if v & SLEEP:
                self._flag(_RESTART_ASLEEP, "RESTART written with SLEEP set: no effect")
            else:
                if not new & EXTCLK and (self._woke_us < 0 or now - self._woke_us < OSC_WAIT_US):
                    waited = now - self._woke_us if self._woke_us >= 0 else 0
                    self._flag(_RESTART_SOON, "RESTART written %d us after wake (< 500)" % waited)
                restart = 0
        r[MODE1] = new | restart

    def _any_output(self):
        for ch in range(16):  # noqa: SIM110  (a generator would allocate in the VM)
            if not self.out[4 * ch + 3] & FULL:
                return True
        return False

    # -- what the outputs do --------------------------------------------------------------
    def running(self):
        """True when the PWM outputs run (awake, no restart pending)."""
        return not self.regs[MODE1] & (SLEEP | RESTART)

    def clock_hz(self):
        """The clock the prescaler divides: EXTCLK input if selected, else the real oscillator."""
        return self.ext_clock_hz if self.regs[MODE1] & EXTCLK else self.osc_hz

    def prescale(self):
        return self.regs[PRE_SCALE]

    def frequency_mhz(self):
        """Update rate in mHz: osc / (4096 * (PRE_SCALE + 1)), rounded."""
        d = 4096 * (self.regs[PRE_SCALE] + 1)
        return (self.clock_hz() * 1000 + d // 2) // d

    def period_ns(self):
        d = self.clock_hz()
        return (4096 * (self.regs[PRE_SCALE] + 1) * 1000000000 + d // 2) // d

    def counts(self, ch):
        """(on, off, full_on, full_off) of channel ch as the output runs it."""
        o = self.out
        i = 4 * ch
        on = o[i] | (o[i + 1] & 0xF) << 8
        off = o[i + 2] | (o[i + 3] & 0xF) << 8
        return (on, off, bool(o[i + 1] & FULL), bool(o[i + 3] & FULL))

    def pulse_ns(self, ch):
        """High time of channel ch's output per period in ns (0: no pulse; the period: always high)."""
        if not 0 <= ch < 16:
            raise ValueError("channel %r, allowed 0..15" % (ch,))
        if not self.running() or not self.regs[MODE2] & OUTDRV or not self.clock_hz():
            return 0
        on, off, full_on, full_off = self.counts(ch)
        if full_off:
            high = 0
        elif full_on:
            high = 4096
        elif on == off:
            high = 0
        else:
            high = (off - on) % 4096
        if self.regs[MODE2] & INVRT:
            high = 4096 - high
        d = self.clock_hz()
        return (high * (self.regs[PRE_SCALE] + 1) * 1000000000 + d // 2) // d

    def pulse_us(self, ch):
        """pulse_ns rounded to whole us."""
        return (self.pulse_ns(ch) + 500) // 1000

    def pulses_us(self):
        """pulse_us of all 16 channels (a new list)."""
        return [self.pulse_us(ch) for ch in range(16)]
