"""hexapod.fixmath's isqrt, mul_q15 and sin compiled by MicroPython's viper emitter: the same
integer steps, as machine code (docs/viper.md lists every viper twin). The other twins call them,
and walk.py takes this sin on MicroPython with viper (a new command's aims are four sines).

Viper integers are machine words: every argument stays inside the range the plain function's
docstring allows. tests/test_rescale.py proves sin equal to fixmath.sin; isqrt and mul_q15 are
proven inside the twins that call them (tests/test_leg_viper.py, tests/test_tick_viper.py).
"""

from array import array

import micropython

from hexapod.fixmath import _SIN

# fixmath's sine table (Q15, 0..90 degrees: 0..32768) as unsigned half words, read with ptr16: half
# the heap of 32-bit words, and a load as fast.
SIN_Q15 = array("H", _SIN)


@micropython.viper
def isqrt(n: int) -> int:
    """hexapod.fixmath.isqrt: the floor of the square root of n, n < 2**30 (0 for n <= 0)."""
    if n <= 0:
        return 0
    x = 32768
    if n < 67108864:
        x = 8192
        if n < 4194304:
            x = 2048
            if n < 262144:
                x = 512
                if n < 16384:
                    x = 128
                    if n < 1024:
                        x = 32
    y = (x + n // x) >> 1
    while y < x:
        x = y
        y = (x + n // x) >> 1
    return x


@micropython.viper
def mul_q15(a: int, q: int) -> int:
    """hexapod.fixmath.mul_q15: a * q / 2**15 rounded, |a| < 2**29, |q| <= 2**15."""
    if a < 0:
        a = 0 - a
        return 0 - ((a >> 15) * q + (((a & 32767) * q + 16384) >> 15))
    return (a >> 15) * q + (((a & 32767) * q + 16384) >> 15)


@micropython.viper
def sin(cdeg: int) -> int:
    """hexapod.fixmath.sin: Q15 sine of cdeg (|cdeg| < 2**29)."""
    a = cdeg - (cdeg // 36000) * 36000
    neg = 0
    if a >= 18000:
        neg = 1
        a -= 18000
    if a > 9000:
        a = 18000 - a
    i = a // 25
    f = a - i * 25
    tab = ptr16(SIN_Q15)  # noqa: F821 (a viper built-in)
    s = tab[i]
    if f:
        s += ((tab[i + 1] - s) * f + 12) // 25
    if neg:
        return 0 - s
    return s
