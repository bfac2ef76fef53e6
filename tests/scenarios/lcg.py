"""A linear congruential generator, so both runtimes draw the same numbers."""

import sys

_Fast = None
if sys.implementation.name == "micropython":
    try:
        from scenarios._lcg_viper import Lcg as _Fast
    except Exception:  # no viper emitter on this build
        _Fast = None


class Lcg:
    def __init__(self, seed=12345):
        self.seed = seed

    def draw(self, bits):
        """The next number of `bits` bits."""
        self.seed = (self.seed * 1103515245 + 12345) & 0x7FFFFFFF
        return self.seed >> (31 - bits)


def drawer(seed=12345):
    """Lcg(seed).draw, or the same numbers from its viper twin where the runtime has viper. On the
    Pico a plain draw's products are big ints, the twin's machine words: 10,000 draws (with a
    modulo each) cost 54 M emulated instructions plain, 22 M with the twin (2026-11-27)."""
    return (_Fast or Lcg)(seed).draw
