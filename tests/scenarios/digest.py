"""A digest of a run's results, the same on every runtime: one side of a comparison runs where the
other cannot (the emulated Pico's viper twins, the host VM's plain code) and the test compares digests."""

from array import array
from binascii import crc32


def fold(h, parts):
    """The digest h (0 to start) with parts folded in, in order: each an int (or bool) or a flat
    list or tuple of them, each int below 2**31 in size. A crc32 over the ints as 32-bit words,
    in C: a fold in bytecode (h * 31 + v) cost the Pico ~2,700 instructions an int, a sixth of a
    frame case. A crc catches every change confined to one word (a burst of at most 32 bits)."""
    for p in parts:
        h = crc32(array("i", p if isinstance(p, (list, tuple)) else (p,)), h)
    return h
