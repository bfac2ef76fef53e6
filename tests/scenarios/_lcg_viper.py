"""scenarios.lcg.Lcg's draw compiled by MicroPython's viper emitter: the same numbers, in machine
words (tests/test_lcg.py proves it on the VM; on the emulated Pico, tests/test_tick_viper.py's
digests would part if it drew others)."""

from array import array

import micropython


class Lcg:
    def __init__(self, seed=12345):
        self._seed = array("i", (seed,))

    @micropython.viper
    def draw(self, bits: int) -> int:
        """The next number of `bits` bits (at most 30: a small int on a 32-bit port)."""
        s = ptr32(self._seed)  # noqa: F821 (a viper built-in)
        # 1103515245 and 2**31 - 1 built at run time: as folded constants they are no small ints on
        # a 32-bit port. The product wraps at the word (32 or 64 bits): its low 31 bits are exact.
        a = 16838
        a <<= 16
        a |= 20077
        m = 1
        m <<= 31
        m -= 1
        x = (s[0] * a + 12345) & m
        s[0] = x
        return x >> (31 - bits)
