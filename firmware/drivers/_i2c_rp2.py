"""I2C writes in the background on the RP2040 (MicroPython rp2 port with viper only).

machine.I2C's writeto waits while every byte crosses the bus (38 bytes of a PCA9685 frame: 0.86 ms
at 400 kHz). Here the bytes go into the I2C block's 16-entry TX FIFO (IC_DATA_CMD, STOP on the last
one; RP2040 datasheet 4.3) and a machine.Timer callback (hard where the port has it) tops the FIFO
up until every queued write is out, so the CPU pays only for the copies and the callbacks. The
RP2040 holds SCL low when its FIFO runs dry before a STOP (IC_EMPTYFIFO_HOLD_MASTER_EN = 1): a late
refill stretches the bus, never cuts a write short. machine.I2C still sets up the pins and the baud
rate; its other transactions must wait for idle() first (drivers.pca9685 does). One write per slot
(one slot per chip) is in flight; slots go out lowest first. A NACK (TX_ABRT) is counted and the
write sent again from its first byte, up to `tries` more times; the outcome (RETRIED or FAILED, the
driver's bits) is collected with the NEXT write of that slot: one frame later.

Emulated (rp2040js 1.4.1) only: never run on silicon, whose timer IRQ latency is not known here.
"""

import sys

import micropython
from micropython import const

if sys.platform != "rp2":
    raise ImportError("the RP2040's I2C block only (rp2 port)")

from array import array  # noqa: E402
from time import ticks_diff, ticks_us  # noqa: E402

import machine  # noqa: E402

SLOTS = const(4)
SLOT_BYTES = const(68)  # register pointer + 16 channels x 4 bytes, rounded up
_I2C0 = const(0x40044000)  # I2C1 is 0x4000 above
_NVIC_IPR0 = const(0xE000E400)
# The I2C block's registers (RP2040 datasheet 4.3.17), byte offsets
_IC_TAR = const(0x04)
_IC_DATA_CMD = const(0x10)
_IC_FS_SCL_HCNT = const(0x1C)
_IC_FS_SCL_LCNT = const(0x20)
_IC_RAW_INTR_STAT = const(0x34)
_IC_CLR_TX_ABRT = const(0x54)
_IC_CLR_STOP_DET = const(0x60)
_IC_ENABLE = const(0x6C)
_IC_STATUS = const(0x70)
_IC_TXFLR = const(0x74)
_IC_TX_ABRT_SOURCE = const(0x80)
# The state's words (array("i"), read by viper as machine words):
_BASE = const(0)  # the I2C block's address
_ACTIVE = const(1)  # the slot being sent, -1 none
_POS = const(2)  # its next byte
_RUN = const(3)  # the refill timer runs
_CALLS = const(4)  # refills (callbacks and queue()'s)
_DONE = const(5)  # writes done
_ABORTS = const(6)  # NACKs
_SCRATCH = const(7)  # what a clearing read returned
_SLOT0 = const(8)  # then _SLOT_WORDS words per slot, at these offsets:
_SLOT_WORDS = const(8)
_ADDR = const(0)  # 7-bit address
_LEN = const(1)  # bytes queued
_PENDING = const(2)  # queued and not yet done (from then on the timer's)
_TRIES = const(3)  # retries left
_STATUS = const(4)  # collected status (RETRIED, FAILED) for the caller
_ERRORS = const(5)  # collected NACKs for the caller
_ABRT_SRC = const(6)  # the last IC_TX_ABRT_SOURCE
_WRITE = const(7)  # this write's status so far
_RETRIED = const(1)
_FAILED = const(2)


# The one sender's state (the refill is the timer's callback itself: globals cost less than a
# bound method's attributes inside the IRQ).
_ST = None
_DATA = None
_TIMER = None


@micropython.viper
def _pump(t) -> int:
    """The timer's callback (t: the Timer; 0 from queue()): top up the TX FIFO, retire a finished
    or NACKed write, start the next; 0 when all is out (the timer then stops itself)."""
    s = ptr32(_ST)  # noqa: F821 (viper built-ins)
    d = ptr8(_DATA)  # noqa: F821
    s[_CALLS] += 1
    r = ptr32(s[_BASE])  # noqa: F821 (the I2C block's registers as words: r[offset >> 2])
    j = s[_ACTIVE]
    if j >= 0:
        o = _SLOT0 + _SLOT_WORDS * j
        if r[_IC_RAW_INTR_STAT >> 2] & 0x40:  # TX_ABRT: a NACK; the block sent STOP and flushed its FIFO
            s[o + _ABRT_SRC] = r[_IC_TX_ABRT_SOURCE >> 2]
            s[_SCRATCH] = r[_IC_CLR_TX_ABRT >> 2]  # the read clears it and lets the FIFO take bytes again
            s[_ABORTS] += 1
            s[o + _ERRORS] += 1
            if s[o + _TRIES] > 0:
                s[o + _TRIES] -= 1
                s[o + _WRITE] = _RETRIED
                s[_POS] = 0  # the whole write again (queued behind the abort's STOP)
            else:
                s[o + _WRITE] = _FAILED
                s[o + _STATUS] |= _FAILED
                s[o + _PENDING] = 0
                j = -1
                s[_ACTIVE] = -1
        elif s[_POS] >= s[o + _LEN] and (r[_IC_STATUS >> 2] & 0x25) == 0x04:  # all sent and the bus idle
            s[o + _STATUS] |= s[o + _WRITE]
            s[o + _PENDING] = 0
            s[_DONE] += 1
            j = -1
            s[_ACTIVE] = -1
    if j < 0:
        if r[_IC_STATUS >> 2] & 0x21:  # still finishing a STOP
            return 1
        s[_SCRATCH] = r[_IC_CLR_STOP_DET >> 2]  # cleared: machine.I2C then waits for a STOP of its own
        k = 0
        while k < SLOTS:
            if s[_SLOT0 + _SLOT_WORDS * k + _PENDING]:
                break
            k += 1
        if k == SLOTS:
            if s[_RUN]:
                s[_RUN] = 0
                _TIMER.deinit()
            return 0
        j = k
        s[_SCRATCH] = r[_IC_CLR_TX_ABRT >> 2]  # a TX_ABRT left by machine.I2C's own transactions is not this write's
        r[_IC_ENABLE >> 2] = 0  # IC_TAR changes only while IC_ENABLE is 0
        r[_IC_TAR >> 2] = s[_SLOT0 + _SLOT_WORDS * j + _ADDR]
        r[_IC_ENABLE >> 2] = 1
        s[_ACTIVE] = j
        s[_POS] = 0
    o = _SLOT0 + _SLOT_WORDS * j
    n = s[o + _LEN]
    pos = s[_POS]
    room = 16 - r[_IC_TXFLR >> 2]
    b = SLOT_BYTES * j
    while room > 0 and pos < n:
        v = d[b + pos]
        if pos == n - 1:
            v |= 0x200  # STOP after this byte
        r[_IC_DATA_CMD >> 2] = v
        pos += 1
        room -= 1
    s[_POS] = pos
    return 1


@micropython.viper
def queue(slot: int, buf, n: int, tries: int) -> int:
    """buf[:n] into slot, pending; the slot's collected status | 256 x its NACKs (then cleared),
    | 0x10000 when the timer must be started; -1 while the slot's last write is still queued."""
    s = ptr32(_ST)  # noqa: F821
    o = _SLOT0 + _SLOT_WORDS * slot
    if s[o + _PENDING]:
        return -1
    d = ptr8(_DATA)  # noqa: F821
    b = ptr8(buf)  # noqa: F821
    base = SLOT_BYTES * slot
    i = 0
    while i < n:
        d[base + i] = b[i]
        i += 1
    v = s[o + _STATUS] | s[o + _ERRORS] << 8  # the timer leaves a slot's words alone while it is not pending
    s[o + _STATUS] = 0
    s[o + _ERRORS] = 0
    s[o + _LEN] = n
    s[o + _TRIES] = tries
    s[o + _WRITE] = 0
    s[o + _PENDING] = 1  # pending: from here on the timer's
    if s[_RUN]:  # the timer runs: it takes this slot after the ones before
        return v
    if int(_pump(0)):  # no timer, so no IRQ touches the state: start here, then the timer
        s[_RUN] = 1
        return v | 0x10000
    return v


class Sender:
    """Background writes on I2C block bus_id (0 or 1), set up by machine.I2C beforehand."""

    def __init__(self, bus_id):
        if bus_id not in (0, 1):
            raise ValueError("bus_id: %r, allowed 0 or 1" % (bus_id,))
        self.bus_id = bus_id
        self._st = array("i", [0] * (_SLOT0 + _SLOT_WORDS * SLOTS))
        self._st[_BASE] = _I2C0 + 0x4000 * bus_id
        self._st[_ACTIVE] = -1
        self._data = bytearray(SLOTS * SLOT_BYTES)
        self._slots = 0
        m = machine.mem32
        base = self._st[_BASE]
        # A refill every 12 bytes' time (108 SCL periods of IC_FS_SCL_HCNT + LCNT clk_sys counts):
        # the 16-entry FIFO keeps 4 bytes (90 us at 400 kHz) for a late callback.
        period = 108 * (m[base + _IC_FS_SCL_HCNT] + m[base + _IC_FS_SCL_LCNT]) // (machine.freq() // 1000000)
        self.period_us = max(20, period)
        self._timer = machine.Timer()
        # machine.Timer runs on pico-sdk's default alarm pool: hardware alarm 3, TIMER_IRQ_3. Its
        # NVIC priority goes from the SDK's 0x80 to the lowest, 0xC0 (NVIC_IPR0 bits 31:30): a
        # sonar's echo IRQ (IO_IRQ_BANK0, 0x80) then preempts a refill instead of waiting up to
        # ~15 us for it, which would read ~2.5 mm long (measured on the emulated chip).
        m[_NVIC_IPR0] = (m[_NVIC_IPR0] & 0x00FFFFFF) | 0xC0000000
        # Hard callbacks (rp2 Timer's `hard=`, MicroPython 1.26+) refill from the IRQ itself. Older
        # ports only schedule the callback (soft): it then runs when the VM next looks, at a bytecode
        # jump or in sleep_ms, which in the loop is the frame's wait; a late refill stretches the bus.
        try:
            self._timer.init(period=1000000, tick_hz=1000000, callback=_idle_callback, hard=True)
            self.hard = True
        except TypeError:
            self.hard = False
        self._timer.deinit()
        global _ST, _DATA, _TIMER
        _ST, _DATA, _TIMER = self._st, self._data, self._timer

    def slot(self, address):
        """The slot for writes to a 7-bit address (one write in flight per slot; one slot per address)."""
        for j in range(self._slots):
            if self._st[_SLOT0 + _SLOT_WORDS * j + _ADDR] == address:
                return j
        if self._slots == SLOTS:
            raise ValueError("at most %d chips on one background sender" % SLOTS)
        j = self._slots
        self._slots += 1
        self._st[_SLOT0 + _SLOT_WORDS * j + _ADDR] = address
        return j

    def send(self, slot, buf, n, tries):
        """Queue buf[:n] (n <= 68 bytes) to slot's address, sent up to 1 + tries times. Returns the
        status bits (RETRIED, FAILED) of slot's earlier writes + 256 x the NACKs they met (then
        cleared), or -1 when slot's last write is still queued (wait with idle() first)."""
        v = queue(slot, buf, n, tries)
        if v >= 0x10000:
            self.start()
            v -= 0x10000
        return v

    def start(self):
        """The refill timer on (after queue() returned | 0x10000: the first bytes are in the FIFO)."""
        if self.hard:
            self._timer.init(period=self.period_us, tick_hz=1000000, callback=_pump, hard=True)
        else:
            self._timer.init(period=self.period_us, tick_hz=1000000, callback=_pump)

    def collect(self, slot):
        """send()'s outcome word without sending (call after idle())."""
        s = self._st
        o = _SLOT0 + _SLOT_WORDS * slot
        v = s[o + _STATUS] | s[o + _ERRORS] << 8
        s[o + _STATUS] = 0
        s[o + _ERRORS] = 0
        return v

    def idle(self, timeout_us=50000):
        """Wait (at most timeout_us) until every queued write is out and the bus is free; True
        then. On timeout the queue is dropped (those writes FAILED) and False returned."""
        s = self._st
        if not s[_RUN]:  # the timer stops itself only once nothing is queued or on the bus
            return True
        t0 = ticks_us()
        while s[_RUN]:
            if ticks_diff(ticks_us(), t0) > timeout_us:
                self._drop()
                return False
        return True

    def _drop(self):
        """The bus never finished (a chip holding SCL low?): timer off, the transfer aborted as the
        datasheet says (IC_ENABLE.ABORT: STOP, TX FIFO flushed; the block clears ABORT when done,
        waited for 1 ms at most), the block off and on, the queued writes FAILED. Not exercised on
        the emulator (rp2040js models neither a held SCL nor the abort's end)."""
        self._timer.deinit()
        s = self._st
        m = machine.mem32
        enable = s[_BASE] + _IC_ENABLE
        m[enable] = 3  # ENABLE | ABORT
        t0 = ticks_us()
        while m[enable] & 2 and ticks_diff(ticks_us(), t0) < 1000:
            pass
        m[enable] = 0  # IC_ENABLE 0 flushes the FIFO whatever the abort did
        m[enable] = 1
        s[_SCRATCH] = m[s[_BASE] + _IC_CLR_TX_ABRT]  # the read clears it
        for j in range(SLOTS):
            o = _SLOT0 + _SLOT_WORDS * j
            if s[o + _PENDING]:
                s[o + _PENDING] = 0
                s[o + _STATUS] |= _FAILED
        s[_ACTIVE] = -1
        s[_RUN] = 0

    @property
    def stats(self):
        """(refills: the timer's callbacks and queue()'s, writes done, NACKs) since start-up."""
        s = self._st
        return s[_CALLS], s[_DONE], s[_ABORTS]


def _idle_callback(t):
    """Sender's probe for hard callbacks: the timer is off again long before it could run."""


_SENDER = []  # the one Sender (its state is this module's)


def for_bus(i2c):
    """The Sender of a machine.I2C, or None when it is not the rp2's hardware I2C, or another
    block has the sender already (that bus then writes blocking)."""
    if type(i2c) is not machine.I2C:
        return None
    text = repr(i2c)  # "I2C(0, freq=400000, scl=5, sda=4, timeout=50000)"
    if not text.startswith("I2C("):
        return None
    bus_id = int(text[4 : text.index(",")])
    if not _SENDER:
        _SENDER.append(Sender(bus_id))
    return _SENDER[0] if _SENDER[0].bus_id == bus_id else None
