"""hexapod.leg.solve compiled by MicroPython's viper emitter: the same integer steps, run as
machine code. Imported by leg.py only on MicroPython, and only if the port has viper.

Viper integers are machine words (32 bits on a board); every value here stays below 2**30
(tests/test_leg_ranges.py) and tests/test_leg_viper.py proves this file returns exactly what
the plain `solve` returns, code, excess and angles, on well over 100,000 feet.
"""

from array import array

import micropython
from micropython import const

from hexapod._fixmath_viper import isqrt
from hexapod.fixmath import _ATAN

# Reason codes and solver slots copied from hexapod.leg (viper folds only a module's own consts);
# tests/test_viper_twins.py checks each against the name after its #.
_OK = const(0)  # hexapod.leg.OK
_TOO_FAR = const(1)  # hexapod.leg.TOO_FAR
_TOO_CLOSE = const(2)  # hexapod.leg.TOO_CLOSE
_OUT_OF_RANGE = const(9)  # hexapod.leg.OUT_OF_RANGE
_COORD_MAX = const(30000)  # hexapod.leg.COORD_MAX
_G_COXA = const(0)  # hexapod.leg.G_COXA
_G_OFFSET_UP = const(1)  # hexapod.leg.G_OFFSET_UP
_G_OFFSET_DOWN = const(2)  # hexapod.leg.G_OFFSET_DOWN
_G_REACH = const(3)  # hexapod.leg.G_REACH
_G_MIN_REACH = const(4)  # hexapod.leg.G_MIN_REACH
_G_SUM2 = const(5)  # hexapod.leg.G_SUM2
_G_DIF2 = const(6)  # hexapod.leg.G_DIF2
_G_FEMUR2 = const(7)  # hexapod.leg.G_FEMUR2
_G_TIBIA2 = const(8)  # hexapod.leg.G_TIBIA2
_G_EXCESS = const(9)  # hexapod.leg.G_EXCESS
_G_T1 = const(10)  # hexapod.leg.G_T1
_G_T2 = const(11)  # hexapod.leg.G_T2
_G_T3 = const(12)  # hexapod.leg.G_T3

_ATAN_WORDS = array("i", _ATAN)


@micropython.viper
def solve(x: int, y: int, z: int, gbuf) -> int:
    g = ptr32(gbuf)  # noqa: F821 (a viper built-in)
    if x > _COORD_MAX or x < 0 - _COORD_MAX or y > _COORD_MAX or y < 0 - _COORD_MAX:
        return int(_out_of_range(x, y, z, gbuf))
    if z > _COORD_MAX or z < 0 - _COORD_MAX:
        return int(_out_of_range(x, y, z, gbuf))
    a1 = g[_G_COXA]
    reach = g[_G_REACH]
    v = z - g[_G_OFFSET_UP] + g[_G_OFFSET_DOWN]
    big = a1 + reach
    if x > big or x < 0 - big or y > big or y < 0 - big or v > reach or v < 0 - reach:
        xs = x >> 2
        ys = y >> 2
        hs = ((int(isqrt(xs * xs + ys * ys)) << 2) - a1) >> 2
        vs = v >> 2
        m = (int(isqrt(hs * hs + vs * vs)) << 2) - reach
        g[_G_EXCESS] = m if m > 0 else 1
        return _TOO_FAR
    r2 = x * x + y * y
    j = 0
    n = 0
    if r2:
        n = r2
        while n < 268435456:
            n <<= 2
            j += 1
    # _isqrt, _sqrt12 and _atan2 written out (a viper call costs ~5 us on the Pico, more than most
    # of their bodies): one floor root serves three jobs, one arctangent four, in loops.
    rj = fk = ti = tf = ci = pi = qi = qf = sp = sq = sh = 0
    job = 0
    while True:
        # isqrt(n): the floor square root.
        r = 0
        if n > 0:
            r = 32768
            if n < 67108864:
                r = 8192
                if n < 4194304:
                    r = 2048
                    if n < 262144:
                        r = 512
                        if n < 16384:
                            r = 128
                            if n < 1024:
                                r = 32
            q = (r + n // r) >> 1
            while q < r:
                r = q
                q = (r + n // r) >> 1
        if job == 0:
            if r2:
                rj = r
                rem = n - rj * rj
                d = rj << 1
                d4 = (d << 4) + (rem << 4) // d
                num = rem << 12
                q = num // d4
                fk = (q << 8) + (((num - q * d4) << 8) // d4)
            mm = (a1 * rj) << 1
            ti = mm >> j
            tf = ((mm - (ti << j)) << (16 - j)) + (((a1 * fk) << 1) >> j)
            ti += tf >> 16
            tf &= 65535
            ci = r2 + a1 * a1 + v * v - ti
            pi = g[_G_SUM2] - ci
            if pi < 0:
                g[_G_EXCESS] = int(isqrt(ci - 1)) + 1 - reach
                return _TOO_FAR
            qi = ci - g[_G_DIF2]
            if tf:
                qi -= 1
                qf = 65536 - tf
            if qi < 0:
                g[_G_EXCESS] = g[_G_MIN_REACH] - int(isqrt(ci))
                return _TOO_CLOSE
            vi = pi
            vf = tf
        elif job == 1:
            sp = (r << sh) + (((n - r * r) << sh) // ((r << 1) + 1))
            vi = qi
            vf = qf
        else:
            sq = (r << sh) + (((n - r * r) << sh) // ((r << 1) + 1))
            break
        # _sqrt12(vi, vf): the root of vi + vf / 2**16 in 12 fraction bits, through the root above.
        job += 1
        sv = 16
        lim = 8192
        while vi >= lim:
            sv -= 2
            lim <<= 2
        n = (vi << sv) + (vf >> (16 - sv))
        sh = 12 - (sv >> 1)
    e1 = 0
    while (sp >> e1) >= 32768:
        e1 += 1
    e2 = 0
    while (sq >> e2) >= 32768:
        e2 += 1
    e = 20 - e1 - e2
    yb = (sp >> e1) * (sq >> e2)
    if e > 0:
        yb = (yb + (1 << (e - 1))) >> e
    xb = ((g[_G_FEMUR2] - g[_G_TIBIA2] + ci) << 4) - (tf >> 12)
    h = ((rj - (a1 << j)) << (16 - j)) + (fk >> j)
    table = ptr32(_ATAN_WORDS)  # noqa: F821 (a viper built-in)
    t2 = t3 = 0
    for k in range(4):
        # _atan2(ay, ax) of the tibia's (sq, sp), the femur's (v << 16, h) and (yb, xb), the coxa's (y, x).
        if k == 0:
            ay = sq
            ax = sp
        elif k == 1:
            ay = v << 16
            ax = h
        elif k == 2:
            ay = yb
            ax = xb
        else:
            ay = y
            ax = x
        yy = ay
        xx = ax
        a = 0
        if xx != 0 or yy != 0:
            if ax < 0:
                ax = 0 - ax
            if ay < 0:
                ay = 0 - ay
            steep = 0
            if ay > ax:
                steep = 1
                t = ax
                ax = ay
                ay = t
            if ay >= 32768:
                sk = 1
                while (ay >> sk) >= 32767:
                    sk += 1
                ay = (ay >> sk) + ((ay >> (sk - 1)) & 1)
                ax = (ax >> sk) + ((ax >> (sk - 1)) & 1)
            num = ay << 15
            t = num // ax
            if num - t * ax >= ax - (num - t * ax):
                t += 1
            ti = t >> 7
            if ti >= 256:
                a = table[256]
            else:
                lo = table[ti]
                a = lo + (((table[ti + 1] - lo) * (t & 127) + 64) >> 7)
            if steep:
                a = 900000 - a
            if xx < 0:
                a = 1800000 - a
            if yy < 0 and a != 1800000:
                a = 0 - a
        if k == 0:
            t3 = (a << 1) - 1800000
        elif k == 1:
            t2 = a
        elif k == 2:
            t2 += a
        else:
            g[_G_T1] = (a + 50) // 100
    if t2 > 1800000:
        t2 -= 3600000
    g[_G_T2] = (t2 + 50) // 100
    g[_G_T3] = (t3 + 50) // 100
    return _OK


@micropython.viper
def _out_of_range(x: int, y: int, z: int, gbuf) -> int:
    g = ptr32(gbuf)  # noqa: F821 (a viper built-in)
    m = x if x >= 0 else 0 - x
    if y > m or 0 - y > m:
        m = y if y >= 0 else 0 - y
    if z > m or 0 - z > m:
        m = z if z >= 0 else 0 - z
    g[_G_EXCESS] = m - _COORD_MAX
    return _OUT_OF_RANGE
