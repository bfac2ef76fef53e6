"""Where a port lets hexapod.faultlog's words outlive a soft reset (and a watchdog reset).

- rp2: the watchdog's scratch registers 0-3 (RP2040 datasheet, 4.7 Watchdog: SCRATCH0..7 at
  0x4005800C.. keep their values through a watchdog or soft reset and are cleared only by a
  power-on or RUN-pin reset; pico-sdk's watchdog_reboot and the bootrom use 4-7);
- esp32: RTC memory (machine.RTC().memory(): kept through soft, watchdog and deep-sleep resets);
- anywhere else: None, and the log lasts as long as the interpreter.
A brown-out of the board's own supply is a power-on reset on both chips (MicroPython reports
no brown-out cause on rp2 or esp32), so it clears the kept words: what the log can show is the
PCA9685 found reset (faultlog.BROWNOUT), which its servo-side logic supply causes.
"""

from micropython import const

_SCRATCH0 = const(0x4005800C)  # WATCHDOG_BASE 0x40058000 + SCRATCH0's offset 0x0C


class Rp2Scratch:
    """machine.mem32 (or a stand-in indexable by address) -> load_into/store of 4 words."""

    def __init__(self, mem32):
        self.mem32 = mem32

    def load_into(self, words):
        for i in range(len(words)):
            words[i] = self.mem32[_SCRATCH0 + 4 * i]

    def store(self, words):
        for i in range(len(words)):
            self.mem32[_SCRATCH0 + 4 * i] = words[i]


class RtcMemory:
    """machine.RTC() -> load_into/store of words, 4 bytes each little-endian, in its memory()."""

    def __init__(self, rtc, size=4):
        self.rtc = rtc
        self._buf = bytearray(4 * size)  # made once: store() is called from the loop

    def load_into(self, words):
        m = self.rtc.memory()
        for i in range(len(words)):
            j = 4 * i
            words[i] = m[j] | m[j + 1] << 8 | m[j + 2] << 16 | m[j + 3] << 24 if len(m) >= j + 4 else 0

    def store(self, words):
        b = self._buf
        for i in range(len(words)):
            x = words[i]
            for k in range(4):
                b[4 * i + k] = x >> 8 * k & 255
        self.rtc.memory(b)


def for_port(machine, platform):
    """The keeper this port has (sys.platform 'rp2' or 'esp32'), or None."""
    if platform == "rp2" and hasattr(machine, "mem32"):
        return Rp2Scratch(machine.mem32)
    if platform == "esp32" and hasattr(machine, "RTC"):
        return RtcMemory(machine.RTC())
    return None
