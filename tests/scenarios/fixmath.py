"""hexapod.fixmath on drawn inputs: the same rows on every runtime."""

from scenarios.lcg import Lcg

from hexapod import fixmath as f


def vectors(n):
    """(isqrt, atan2, sin, cos, mul_q15) of n drawn inputs."""
    draw = Lcg().draw
    out = []
    for k in range(n):
        y = (draw(30) - (1 << 29)) >> (k % 29)
        x = (draw(30) - (1 << 29)) >> (k % 23)
        s = k * 7 - 10000
        out.append((f.isqrt(draw(30)), f.atan2(y, x), f.sin(s), f.cos(s), f.mul_q15(y, draw(15))))
    return out
