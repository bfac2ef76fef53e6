"""The last few faults (kind, what, frame) in SIZE words a keeper can hold across a soft reset.

Pure, like the rest of the core: the loop (runner.Runner) notices a fault starting and calls
record(); the log never reads a pin or a clock. A keeper (drivers.faultkeep) copies the words
somewhere a soft reset leaves alone (the RP2040's watchdog scratch registers, the ESP32's RTC
memory); without one the log lives as long as the interpreter.

One fault is one word below 2**29, a small int on every port, so recording allocates nothing:
    bit 28      MARK (a word without it is empty or someone else's: ignored at load)
    bits 25-27  kind (I2C, BROWNOUT, SONAR, WATCHDOG, BATTERY)
    bits 22-24  what: the chip's index in the board file (I2C, BROWNOUT) or the sonar's
                (drivers.hcsr04 order); 0 otherwise
    bits 0-21   the loop's frame count when it started, modulo 2**22 (23.3 hours at 50 Hz)
The words are oldest first; a new fault pushes the oldest out.
"""

from micropython import const

SIZE = const(4)  # the RP2040 has 4 watchdog scratch words free for applications (4-7 are the bootrom's)
I2C = const(1)  # a frame some chip did not take (the bank's failed_frames rose after a good frame)
BROWNOUT = const(2)  # a PCA9685 found reset and set up again: its logic supply dipped
SONAR = const(3)  # a sonar's ping came back NO_ECHO, STUCK or OUT_OF_RANGE after a good one
WATCHDOG = const(4)  # the board came up from a watchdog reset: the loop had stalled
BATTERY = const(5)  # the battery fell below its cutoff: the robot sat down and relaxed
KIND_NAMES = ("", "i2c", "brownout", "sonar", "watchdog", "battery")
_MARK = const(0x10000000)
_FRAME_MASK = const(0x3FFFFF)


class FaultLog:
    """SIZE words, oldest first; kept: how many of them came from before this boot."""

    def __init__(self, keeper=None):
        """keeper: has load_into(words) and store(words) (drivers.faultkeep), or None."""
        self.words = [0] * SIZE
        self.keeper = keeper
        self.kept = 0
        if keeper is not None:
            keeper.load_into(self.words)
            self._tidy()
            self.kept = self.count()

    def _tidy(self):
        """Drop words without the mark (power-on garbage, another program's) and close the gaps."""
        w = self.words
        n = 0
        for i in range(SIZE):
            x = w[i]
            if x & ~0x1FFFFFFF == 0 and x & _MARK and 1 <= x >> 25 & 7 <= BATTERY:
                w[n] = x
                n += 1
        for i in range(n, SIZE):
            w[i] = 0

    def count(self):
        """Faults held (0..SIZE)."""
        n = 0
        for x in self.words:
            if x:
                n += 1
        return n

    def record(self, kind, what, frame):
        """Keep one fault (kind I2C..BATTERY, what 0..7, frame >= 0); the oldest goes when full."""
        w = self.words
        n = self.count()
        if n == SIZE:
            for i in range(SIZE - 1):
                w[i] = w[i + 1]
            n -= 1
            if self.kept:
                self.kept -= 1
        w[n] = _MARK | (kind & 7) << 25 | (what & 7) << 22 | (frame & _FRAME_MASK)
        if self.keeper is not None:
            self.keeper.store(w)

    def clear(self):
        for i in range(SIZE):
            self.words[i] = 0
        self.kept = 0
        if self.keeper is not None:
            self.keeper.store(self.words)

    def entry(self, i):
        """Fault i (0 = oldest) as (kind, what, frame, before_this_boot)."""
        x = self.words[i]
        return (x >> 25 & 7, x >> 22 & 7, x & _FRAME_MASK, i < self.kept)
