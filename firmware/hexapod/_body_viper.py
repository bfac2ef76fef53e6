"""hexapod.body's pose check and body -> leg transform compiled by MicroPython's viper emitter:
the same integer steps, as machine code (docs/viper.md lists every viper twin). tick.py takes
settled on MicroPython with viper; posed is the pose part of Body.to_leg inside the viper frame
(hexapod/_tick_viper.py). tests/test_tick_viper.py proves both equal to the plain code.
"""

import micropython

from hexapod._fixmath_viper import mul_q15


@micropython.viper
def settled(body) -> int:
    """hexapod.body.Body.settled: 1 when the pose has reached its target, else 0."""
    p = ptr32(body.pose)  # noqa: F821 (a viper built-in; the pose is array("i"))
    t = ptr32(body.target)  # noqa: F821
    for k in range(9):
        if p[k] != t[k]:
            return 0
    return 1


@micropython.viper
def posed(body, xyz) -> int:
    """Body.to_leg's pose part: the foot xyz[0:3] (fine) moved back through the body's pose, in place."""
    sb = 1
    sb <<= 31  # (v ^ sb) - sb sign-extends a ptr32 load (unsigned on a 64-bit VM); on a board it is v
    p = ptr32(body.pose)  # noqa: F821
    tr = ptr32(body.trig)  # noqa: F821
    cx = ((p[6] ^ sb) - sb) << 4
    cy = ((p[7] ^ sb) - sb) << 4
    cz = ((p[8] ^ sb) - sb) << 4
    x = int(xyz[0]) - (cx + (((p[0] ^ sb) - sb) << 4))
    y = int(xyz[1]) - (cy + (((p[1] ^ sb) - sb) << 4))
    z = int(xyz[2]) - (cz + (((p[2] ^ sb) - sb) << 4))
    c = (tr[4] ^ sb) - sb
    s = (tr[5] ^ sb) - sb
    a = int(mul_q15(x, c)) + int(mul_q15(y, s))
    y = int(mul_q15(y, c)) - int(mul_q15(x, s))
    x = a
    c = (tr[2] ^ sb) - sb
    s = (tr[3] ^ sb) - sb
    a = int(mul_q15(x, c)) - int(mul_q15(z, s))
    z = int(mul_q15(x, s)) + int(mul_q15(z, c))
    x = a
    c = (tr[0] ^ sb) - sb
    s = (tr[1] ^ sb) - sb
    a = int(mul_q15(y, c)) + int(mul_q15(z, s))
    z = int(mul_q15(z, c)) - int(mul_q15(y, s))
    y = a
    xyz[0] = x + cx
    xyz[1] = y + cy
    xyz[2] = z + cz
    return 0
