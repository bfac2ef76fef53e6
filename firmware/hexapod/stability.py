"""Static stability: how far the body centre lies inside the support polygon of the stance feet.

Feet are body-frame (x, y) in 0.1 mm; legs in their 1..6 order run clockwise seen from
above, so the stance feet in leg order are the polygon's corners, clockwise. The margin
is the smallest distance from the point (px, py) to a polygon edge, positive inside and
negative outside, in 0.1 mm. Fewer than three feet down has no support: NO_SUPPORT.
"""

import sys

from micropython import const

from hexapod.fixmath import isqrt

# fixmath's root as machine code where MicroPython has viper (hexapod/_fixmath_viper.py, equal for
# every n fixmath allows: tests/test_rescale.py): the margin takes one an edge each tick a change settles.
if sys.implementation.name == "micropython":
    try:  # noqa: SIM105 (no contextlib on MicroPython)
        from hexapod._fixmath_viper import isqrt  # noqa: F811
    except Exception:  # no viper emitter on this build: the plain root stays
        pass

NO_SUPPORT = const(-1000000)


def support_margin(xs, ys, down, px=0, py=0):
    """Margin (0.1 mm) of (px, py) inside the polygon of the feet with down[i] true."""
    count = 0
    for i in range(6):
        if down[i]:
            count += 1
    if count < 3:
        return NO_SUPPORT
    best = None
    for i in range(6):
        if not down[i]:
            continue
        j = i + 1
        while True:
            if j == 6:
                j = 0
            if down[j]:
                break
            j += 1
        ex = xs[j] - xs[i]
        ey = ys[j] - ys[i]
        length = isqrt(ex * ex + ey * ey)
        if length == 0:
            continue
        # Clockwise corners: the inside is to the right of each edge, where the cross is < 0.
        cross = ex * (py - ys[i]) - ey * (px - xs[i])
        d = -cross // length
        if best is None or d < best:
            best = d
    return NO_SUPPORT if best is None else best
