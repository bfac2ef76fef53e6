"""A linear congruential generator, so both runtimes draw the same numbers."""


class Lcg:
    def __init__(self, seed=12345):
        self.seed = seed

    def draw(self, bits):
        """The next number of `bits` bits."""
        self.seed = (self.seed * 1103515245 + 12345) & 0x7FFFFFFF
        return self.seed >> (31 - bits)
