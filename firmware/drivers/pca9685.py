"""PCA9685 servo driver over a machine.I2C passed in (MicroPython; CPython with the stubs).

Pulse widths in us in; register counts computed exactly in small integers from the board's
oscillator trim: counts = round(pulse_us * osc_hz / (1e6 * (prescale + 1))). A chip's frame goes out as
ONE auto-increment burst from a buffer made once (two transactions for 18 servos on two
chips), and a frame allocates nothing. I2C errors are retried `retries` times and returned
as status bits, never raised. MODE1 is read back every `check_every` frames to catch a chip
that reset (brownout), which is then initialised again and sent the frame.

MODE2.OCH is set (outputs change on ACK): a channel's output only changes once all four of
its registers arrived, so a burst cut short by a NACK never outputs half a pulse width.

On the rp2 port (viper) servo_bank() sends the frames in the background (drivers/_i2c_rp2.py:
the I2C block's FIFO refilled by a timer IRQ) and stages all servos in one viper call: the CPU no
longer waits for the bus. A burst's outcome (RETRIED, FAILED, `errors`) then comes with the
NEXT frame's status (ServoBank.sync() takes it in at once); every other transaction (MODE1
read-back, start-up, off, relax) first waits, bounded, for the bus; the MODE1 read-backs of the
chips fall on different frames. Elsewhere (ESP32, CPython, the VM) writes block, as before.
"""

import sys
from array import array

import micropython
from micropython import const

from hexapod.servo import PULSE_MAX_US, PULSE_MIN_US

# The viper twin (docs/viper.md): stage's count and bytes as machine code where MicroPython has the
# viper emitter (drivers/_pca9685_viper.py, proven equal by tests/test_pca9685_viper.py); and the
# background sender, the rp2 port's only (drivers/_i2c_rp2.py refuses to import elsewhere).
# CPython and CircuitPython run the plain path and send in the foreground.
_put = _stage_all = _sender_for = _queue = None
if sys.implementation.name == "micropython":
    try:
        from drivers._pca9685_viper import put as _put
        from drivers._pca9685_viper import stage_all as _stage_all
    except Exception:  # no viper emitter on this build
        _put = _stage_all = None
    try:
        from drivers._i2c_rp2 import for_bus as _sender_for
        from drivers._i2c_rp2 import queue as _queue
    except Exception:  # not the rp2 port, or no viper emitter
        _sender_for = _queue = None

_MODE1 = const(0x00)
_MODE2 = const(0x01)
_LED0_ON_L = const(0x06)
_ALL_LED_OFF_H = const(0xFD)
_PRE_SCALE = const(0xFE)
_RESTART = const(0x80)
_EXTCLK = const(0x40)
_AI = const(0x20)
_SLEEP = const(0x10)
_OCH = const(0x08)
_OUTDRV = const(0x04)
_FULL = const(0x10)  # LEDn_OFF_H bit 4: full OFF
_OSC_WAIT_US = const(500)
_EIO = const(5)
_ETIMEDOUT = const(110)
_SKIP = const(0x100)  # _prepare: no frame to send this time

# Status bits returned by flush/write/off/relax/check (0: all went through).
OK = const(0)
RETRIED = const(1)  # an I2C error happened and a retry went through
FAILED = const(2)  # retries ran out: the chip kept what it had
REINIT = const(4)  # the chip had reset (brownout) or came back, and was initialised again
OFFLINE = const(8)  # the chip does not answer start-up: frames skipped, start-up retried


def describe(status):
    """Status bits as words, e.g. 'retried, reinit' (allocates: for logs, not the tick)."""
    if not status:
        return "ok"
    names = ("retried", "failed", "reinit", "offline")
    return ", ".join(names[i] for i in range(4) if status & (1 << i))


def prescale_for(osc_hz, freq_hz):
    """PRE_SCALE for an update rate: round(osc_hz / (4096 * freq_hz)) - 1 (data sheet 7.3.5)."""
    return (osc_hz + 2048 * freq_hz) // (4096 * freq_hz) - 1


class PCA9685:
    """One PCA9685 driving up to 16 servos; channels 0..channels-1 go out in each frame burst."""

    def __init__(
        self,
        i2c,
        address=0x40,
        *,
        osc_hz=25000000,
        freq_hz=50,
        channels=16,
        stagger_us=0,
        retries=2,
        check_every=10,
        sleep_us=None,
        ext_clock=False,
        sender=None,
    ):
        if not isinstance(address, int) or not 0x08 <= address <= 0x77 or address == 0x70:
            # 0x70 is every PCA9685's power-on ALLCALL address: a chip strapped there collides at boot.
            raise ValueError("address: %r, allowed 0x08..0x77 except 0x70 (PCA9685 boards: 0x40..0x6F)" % (address,))
        top = 50000000 if ext_clock else 30000000
        if not isinstance(osc_hz, int) or not 20000000 <= osc_hz <= top:
            raise ValueError("osc_hz: %r, allowed an int in 20000000..%d Hz" % (osc_hz, top))
        if not isinstance(freq_hz, int) or not 24 <= freq_hz <= 1526:
            raise ValueError("freq_hz: %r, allowed 24..1526 Hz" % (freq_hz,))
        prescale = prescale_for(osc_hz, freq_hz)
        if not 3 <= prescale <= 255:
            raise ValueError("freq_hz %d needs PRE_SCALE %d at %d Hz, allowed 3..255" % (freq_hz, prescale, osc_hz))
        if not isinstance(channels, int) or not 1 <= channels <= 16:
            raise ValueError("channels: %r, allowed 1..16" % (channels,))
        if not isinstance(retries, int) or not 0 <= retries <= 10:
            raise ValueError("retries: %r, allowed 0..10" % (retries,))
        if not isinstance(check_every, int) or check_every < 0:
            raise ValueError("check_every: %r frames, allowed >= 0 (0: never read back)" % (check_every,))
        if not isinstance(stagger_us, int) or stagger_us < 0:
            raise ValueError("stagger_us: %r, allowed >= 0 us" % (stagger_us,))
        self.i2c = i2c
        self.address = address
        self.osc_hz = osc_hz
        self.freq_hz = freq_hz
        self.channels = channels
        self._set_prescale(prescale)
        step = self.count(stagger_us)
        room = 4095 - self.count(PULSE_MAX_US)  # counts left for the last channel's ON time
        if room < 0:
            period_us = 4096 * (prescale + 1) * 1000 // (osc_hz // 1000)
            raise ValueError(
                "freq_hz: %d, its %d us period cannot hold a %d us servo pulse (allowed 24 Hz up to a longer period)"
                % (freq_hz, period_us, PULSE_MAX_US)
            )
        if (channels - 1) * step > room:
            lo, hi = 0, stagger_us  # the largest stagger that fits: count(lo) fits, count(hi) does not
            while hi - lo > 1:
                mid = (lo + hi) // 2
                if (channels - 1) * self.count(mid) > room:
                    hi = mid
                else:
                    lo = mid
            top = lo
            raise ValueError(
                "stagger_us: %d, allowed 0..%d us for %d channels (a %d us pulse must end inside the period)"
                % (stagger_us, top, channels, PULSE_MAX_US)
            )
        self._on = [ch * step for ch in range(channels)]  # ON count of each channel
        # what the viper stage reads: the count's constants, then each channel's ON count
        self._params = array("i", [0] * 5 + self._on)
        self._pack()
        self._retries = retries
        self._check_every = check_every
        self._ext = _EXTCLK if ext_clock else 0
        if sleep_us is None:
            import time

            sleep_us = time.sleep_us
        self._sleep_us = sleep_us
        self._frame = bytearray(1 + 4 * channels)  # register pointer + 4 bytes a channel
        self._frame[0] = _LED0_ON_L
        self._off_buf = bytearray(5)
        self._reg2 = bytearray(2)
        self._reg1 = bytearray(1)
        self._ptr = bytearray(1)
        for ch in range(channels):
            self.stage_off(ch)
        self.errors = 0  # I2C errors seen, retried ones included
        self.last_errno = 0
        self.resets_seen = 0  # chip resets found by the MODE1 read-back
        self.offline = True
        self._since = 0
        # drivers._i2c_rp2.Sender: frames go out in the background, their outcome (RETRIED,
        # FAILED, errors) comes back with the next frame's flush; None: writeto, blocking.
        self._bg = sender
        self._slot = sender.slot(address) if sender is not None else 0
        self.init()

    def _set_prescale(self, prescale):
        # counts = pulse_us * osc_hz / (1e6 * (prescale + 1)), split so that every intermediate
        # stays below 2**30 (MicroPython small ints): osc_hz = 1000 * khz + rem.
        self.prescale = prescale
        self._khz = self.osc_hz // 1000
        self._rem = self.osc_hz % 1000
        self._den = 1000 * (prescale + 1)
        self._den1000 = 1000 * self._den
        self._den2000 = 2000 * self._den
        if hasattr(self, "_params"):  # a later prescale (cp_pca9685 reads the chip's back)
            self._pack()

    def _pack(self):
        p = self._params
        p[0] = self._khz
        p[1] = self._rem
        p[2] = self._den
        p[3] = self._den1000
        p[4] = self._den2000

    def count(self, pulse_us):
        """Register counts (ticks of (prescale+1)/osc_hz) for pulse_us (0..2500 us), rounded half up."""
        a = pulse_us * self._khz  # <= 2500 * 50000
        q = a // self._den
        r = a - q * self._den
        return q + (2 * (1000 * r + pulse_us * self._rem) + self._den1000) // self._den2000

    # -- start-up -------------------------------------------------------------------------
    def init(self):
        """Data sheet start-up: sleep, prescale, totem-pole + OCH, wake, 500 us, restart with AI.

        True when the chip answered and reads back MODE1 and PRE_SCALE as written; False marks
        it offline (frames skipped, start-up tried again every check_every frames).
        """
        ext = self._ext
        ok = (
            self._write_reg(_MODE1, _SLEEP) != FAILED
            and (not ext or self._write_reg(_MODE1, _SLEEP | ext) != FAILED)
            and self._write_reg(_PRE_SCALE, self.prescale) != FAILED
            and self._write_reg(_MODE2, _OUTDRV | _OCH) != FAILED
            and self._write_reg(_MODE1, _AI | ext) != FAILED
        )
        if ok:
            self._sleep_us(_OSC_WAIT_US)  # the oscillator needs 500 us after SLEEP clears
            ok = (
                self._write_reg(_MODE1, _RESTART | _AI | ext) != FAILED
                and self._read_reg(_MODE1) == _AI | ext
                and self._read_reg(_PRE_SCALE) == self.prescale
            )
        self.offline = not ok
        self._since = 0
        return ok

    # -- staging (no I2C) -----------------------------------------------------------------
    def stage(self, channel, pulse_us):
        """Put pulse_us (us, PULSE_MIN_US..PULSE_MAX_US) on channel for the next flush()."""
        if not 0 <= channel < self.channels:
            raise ValueError("channel %r, allowed 0..%d" % (channel, self.channels - 1))
        if type(pulse_us) is not int or not PULSE_MIN_US <= pulse_us <= PULSE_MAX_US:
            raise ValueError("pulse_us %r, allowed %d..%d us" % (pulse_us, PULSE_MIN_US, PULSE_MAX_US))
        if _put is not None:
            _put(self._frame, self._params, channel, pulse_us)
            return
        on = self._on[channel]
        off = on + self.count(pulse_us)
        f = self._frame
        i = 1 + 4 * channel
        f[i] = on & 0xFF
        f[i + 1] = on >> 8
        f[i + 2] = off & 0xFF
        f[i + 3] = off >> 8

    def stage_off(self, channel):
        """Put channel full OFF (no pulse, servo limp) for the next flush()."""
        if not 0 <= channel < self.channels:
            raise ValueError("channel %r, allowed 0..%d" % (channel, self.channels - 1))
        f = self._frame
        i = 1 + 4 * channel
        f[i] = 0
        f[i + 1] = 0
        f[i + 2] = 0
        f[i + 3] = _FULL

    # -- I2C ------------------------------------------------------------------------------
    @micropython.native
    def flush(self):
        """Send the staged frame as one auto-increment burst; status bits (with a background
        sender: RETRIED/FAILED and `errors` of the previous frame's burst, see sync())."""
        status = self._prepare()
        if status & _SKIP:
            return status & 0xFF
        return status | self._emit()

    def _prepare(self):
        """flush() before the burst: start-up retried or MODE1 read back when due; | _SKIP when no burst."""
        status = OK
        if self.offline:
            self._since += 1
            if self._since < self._check_every:
                return OFFLINE | _SKIP
            if not self.init():
                return OFFLINE | _SKIP
            status = REINIT
        elif self._check_every:
            self._since += 1
            if self._since >= self._check_every:
                status = self.check()
                if self.offline:
                    return status | OFFLINE | _SKIP
        return status

    def _emit(self):
        """The staged frame's burst: sent now (blocking) or queued on the background sender."""
        bg = self._bg
        if bg is None:
            return self._send(self._frame, len(self._frame))
        v = bg.send(self._slot, self._frame, len(self._frame), self._retries)
        if v < 0:
            v = self._requeue()
        return self._take(v)

    def _requeue(self):
        """The last burst is still out: wait (bounded), then queue this one; send()'s word."""
        if not self._quiet():
            return FAILED
        return self._bg.send(self._slot, self._frame, len(self._frame), self._retries)

    def _take(self, v):
        """Status bits of a background outcome (status | 256 x NACKs), its errors counted."""
        if v >> 8:
            self.errors += v >> 8
            self.last_errno = _EIO  # what machine.I2C raises for a NACK on the rp2 port
        return v & 0xFF

    def sync(self):
        """Wait (bounded) until a background burst is out and take in its outcome now: status
        bits (RETRIED, FAILED) that would otherwise come with the next flush(); OK when blocking."""
        if self._bg is None:
            return OK
        if not self._quiet():
            return FAILED
        return self._take(self._bg.collect(self._slot))

    def _quiet(self):
        """True once the background sender (if any) is idle; a bus that never finishes times out:
        the error is counted and False returned (the caller reports FAILED), never a hang."""
        if self._bg is None or self._bg.idle():
            return True
        self.errors += 1
        self.last_errno = _ETIMEDOUT
        return False

    def write(self, pulses_us):
        """Stage pulses_us[0..channels-1] (us) on channels 0.. and flush(); status bits."""
        for ch in range(self.channels):
            self.stage(ch, pulses_us[ch])
        return self.flush()

    def check(self):
        """Read MODE1 back; a chip found reset (SLEEP set, AI clear) or stopped is initialised again."""
        self._since = 0
        mode1 = self._read_reg(_MODE1)
        if mode1 < 0:
            return FAILED
        if mode1 == _AI | self._ext:  # RESTART set would mean outputs stopped: also a re-init
            return OK
        self.resets_seen += 1
        if self.init():
            return REINIT
        return REINIT | FAILED

    def read_back(self):
        """(MODE1, PRE_SCALE) read from the chip now, -1 for one that did not answer (a self-test's
        look: register reads only, nothing written; not for the tick)."""
        return self._read_reg(_MODE1), self._read_reg(_PRE_SCALE)

    def mode1_written(self):
        """MODE1 as start-up left it (AI, plus EXTCLK with an external clock): what read_back should see."""
        return _AI | self._ext

    def off(self, channel):
        """Channel full OFF now (and in later frames until staged again); status bits."""
        self.stage_off(channel)
        b = self._off_buf
        b[0] = _LED0_ON_L + 4 * channel
        for j in range(4):
            b[1 + j] = self._frame[1 + 4 * channel + j]
        return OFFLINE if self.offline else self._send(b, 5)

    def relax(self):
        """Every output full OFF now (ALL_LED_OFF_H), and the staged frame too; status bits."""
        for ch in range(self.channels):
            self.stage_off(ch)
        return OFFLINE if self.offline else self._write_reg(_ALL_LED_OFF_H, _FULL)

    # -- the only I2C calls (a backend for another runtime overrides these two) -----------
    @micropython.native
    def _send(self, buf, n):
        """Write buf (n bytes) in one transaction with bounded retries; OK, RETRIED or FAILED."""
        if self._bg is not None and not self._quiet():
            return FAILED
        status = OK
        for _ in range(self._retries + 1):
            try:
                if self.i2c.writeto(self.address, buf) == n:
                    return status
                err = _EIO  # SoftI2C reports a data NACK as a short ACK count
            except OSError as e:
                err = e.args[0]
            self.errors += 1
            self.last_errno = err
            status = RETRIED
        return FAILED

    def _read_reg(self, reg):
        """One register's value, or -1 when retries ran out."""
        if self._bg is not None and not self._quiet():
            return -1
        for _ in range(self._retries + 1):
            try:
                self._ptr[0] = reg
                # Pointer write, repeated START, read: what readfrom_mem_into does, but a NACK on
                # the pointer byte is seen here even on SoftI2C (whose read_mem hides it).
                if self.i2c.writeto(self.address, self._ptr, False) == 1:
                    self.i2c.readfrom_into(self.address, self._reg1)
                    return self._reg1[0]
                err = _EIO
            except OSError as e:
                err = e.args[0]
            self.errors += 1
            self.last_errno = err
        return -1

    def _write_reg(self, reg, value):
        b = self._reg2
        b[0] = reg
        b[1] = value
        return self._send(b, 2)


class ServoBank:
    """Servos across PCA9685 chips: a caller-owned list of pulse_us in, one burst per chip out."""

    def __init__(self, chips, channel_map, servo_maps):
        """chips: PCA9685 list; channel_map[k] = (chip index, channel) and servo_maps[k] = ServoMap of servo k."""
        if len(channel_map) != len(servo_maps):
            raise ValueError("%d channel_map entries but %d servo_maps" % (len(channel_map), len(servo_maps)))
        seen = []
        for k in range(len(channel_map)):
            c, ch = channel_map[k]
            if not 0 <= c < len(chips):
                raise ValueError("servo %d: chip %r, allowed 0..%d" % (k, c, len(chips) - 1))
            if not 0 <= ch < chips[c].channels:
                raise ValueError("servo %d: channel %r, chip %d has 0..%d" % (k, ch, c, chips[c].channels - 1))
            if (c, ch) in seen:
                raise ValueError("servo %d: chip %d channel %d is already used" % (k, c, ch))
            seen.append((c, ch))
        self.chips = list(chips)
        self._n = len(channel_map)
        self._chip_of = [chips[c] for c, _ in channel_map]
        self._ch_of = [ch for _, ch in channel_map]
        self._maps = list(servo_maps)
        # bursts go out in the background when every chip shares one sender (drivers/_i2c_rp2.py)
        bg = self.chips[0]._bg if self.chips else None
        self._sender = bg if bg is not None and all(c._bg is bg for c in self.chips) else None
        self._pre = array("i", [0] * len(self.chips))
        # what the viper staging reads (_pca9685_viper.stage_all): 3 words of scratch per servo,
        # then per chip its servo count and (servo, channel) pairs; each chip's frame and params
        tab = [0] * (3 * self._n)
        for c in range(len(chips)):
            mine = [k for k in range(self._n) if channel_map[k][0] == c]
            tab.append(len(mine))
            for k in mine:
                tab += (k, channel_map[k][1])
        self._tab = array("i", tab)
        self._bufs = [b for c in self.chips for b in (c._frame, c._params)]
        self.clamped = 0  # pulses the calibrated min/max had to catch (the caller should have refused them)
        self.status = OK  # status bits of the last write_frame
        self.failed_frames = 0  # write_frame calls on which some chip kept its previous frame
        self.reinits = 0  # write_frame calls that found a chip reset (brownout) and set it up again

    @micropython.native
    def write_frame(self, pulses_us):
        """The control tick's sink (hexapod.tick.Robot): write(), keeping the status and counts."""
        st = self.write(pulses_us)
        self.status = st
        if st & (FAILED | OFFLINE):
            self.failed_frames += 1
        if st & REINIT:
            self.reinits += 1
        return st

    @micropython.native
    def write(self, pulses_us):
        """pulses_us[k] (us) to servo k, each forced into its calibrated min..max; status bits.

        A pulse of 0 means no pulse at all: that servo goes limp (channel full OFF).
        """
        if len(pulses_us) != self._n:
            raise ValueError("%d pulses for %d servos" % (len(pulses_us), self._n))
        got = -1
        if _stage_all is not None:
            try:
                got = _stage_all(pulses_us, self._maps, self._tab, self._bufs)
            except (TypeError, OverflowError):  # not an int: the plain path says which and how
                got = -1
        if got < 0:
            self._stage_plain(pulses_us)
        else:  # all staged in one viper call
            self.clamped += got
        return self._flush_all()

    def _stage_plain(self, pulses_us):
        """write()'s staging without viper (CPython) or for a list stage_all leaves to it (it raises)."""
        n = self._n
        for k in range(n):  # refuse a bad list before staging any of it
            if type(pulses_us[k]) is not int:
                raise ValueError("servo %d: pulse_us %r, allowed an int (us)" % (k, pulses_us[k]))
        for k in range(n):
            p = pulses_us[k]
            if p == 0:
                self._chip_of[k].stage_off(self._ch_of[k])
                continue
            q = self._maps[k].clamp(p)
            if q != p:
                self.clamped += 1
            self._chip_of[k].stage(self._ch_of[k], q)  # (raises on a limit outside 500..2500 us)

    @micropython.native
    def _flush_all(self):
        """Every chip's flush(); status bits."""
        status = OK
        chips = self.chips
        bg = self._sender
        if bg is None:
            for c in chips:
                status |= c.flush()
            return status
        pre = self._pre
        for i in range(len(chips)):  # every MODE1 read-back first: none waits for a burst going out
            c = chips[i]
            if c.offline or (c._check_every and c._since + 1 >= c._check_every):
                pre[i] = c._prepare()
            else:  # _prepare() when nothing is due, written out (a call costs ~20 us on a Pico)
                if c._check_every:
                    c._since += 1
                pre[i] = OK
        start = False
        for i in range(len(chips)):
            st = pre[i]
            if st & _SKIP:
                status |= st & 0xFF
                continue
            c = chips[i]
            v = _queue(c._slot, c._frame, len(c._frame), c._retries)
            if v < 0:
                v = c._requeue()
            if v >= 0x10000:
                start = True
                v -= 0x10000
            status |= st | (c._take(v) if v else OK)
        if start:
            bg.start()
        return status

    def sync(self):
        """Wait until background bursts are out; their status bits now instead of with the next frame."""
        status = OK
        for c in self.chips:
            status |= c.sync()
        return status

    def off(self, servo):
        """Servo `servo` limp now; status bits."""
        return self._chip_of[servo].off(self._ch_of[servo])

    def relax(self):
        """Every servo limp now; status bits."""
        status = OK
        for c in self.chips:
            status |= c.relax()
        return status


def servo_bank(i2c, pca, table, chip_class=None, background=True, **kw):
    """A ServoBank from a board file: pca = BOARD["pca9685"] ({"pwm_hz", "chips": ({"address", "osc_hz"},)}),
    table = (address, channel, ServoMap) per servo (hexapod.board.servo_table); kw go to each chip.
    background: frames through drivers._i2c_rp2 where it works (the rp2 port's machine.I2C), else
    blocking writes."""
    cls = chip_class or PCA9685
    sender = _sender_for(i2c) if background and _sender_for is not None and chip_class is None else None
    if sender is not None:
        kw["sender"] = sender
    chips = []
    index = {}
    for c in pca["chips"]:
        used = [row[1] for row in table if row[0] == c["address"]]
        n = max(used) + 1 if used else 1
        index[c["address"]] = len(chips)
        chips.append(cls(i2c, c["address"], osc_hz=c["osc_hz"], freq_hz=pca["pwm_hz"], channels=n, **kw))
    for k in range(len(table)):
        if table[k][0] not in index:
            raise ValueError("servo %d: address 0x%02x is not one of the board's PCA9685 chips" % (k, table[k][0]))
    if sender is not None:  # MODE1 read-backs on different frames: the worst frame carries one, not all
        for k in range(len(chips)):
            chips[k]._since = k * chips[k]._check_every // len(chips)
    return ServoBank(chips, [(index[row[0]], row[1]) for row in table], [row[2] for row in table])
