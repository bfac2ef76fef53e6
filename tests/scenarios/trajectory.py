"""hexapod.trajectory: seed 003's swing (eq. 12-14) in integers, the heading form, the swing shapes."""

from hexapod.fixmath import cos, mul_q15, sin
from hexapod.trajectory import (
    FINE_BITS,
    combined_point,
    combined_step,
    sin90_fine,
    swing_shape,
    swing_stroke,
    track_point,
)


def table_iii(ticks, s):
    """[t, fine x, y, z, tick x, y, z] per tick k: the point at x = z = 2 cm, both at 1e-6 cm with the
    fine sine and at 0.1 mm with the tick's Q15 sine."""
    rows = []
    buf = [0, 0, 0]
    step = [0, 0]
    for k in range(ticks):
        combined_step(k, s, step)
        t = step[0]
        # x = z = 2 cm at 1e-6 cm units: the table's sixth decimal is the last digit here.
        combined_point(k, s, 2000000, 0, 2000000, buf, sin90_fine, 1 << FINE_BITS)
        fine = list(buf)
        combined_point(k, s, 200, 0, 200, buf)  # the tick's Q15 sine, at 0.1 mm
        rows.append([t] + fine + list(buf))
    return rows


def heading(thetas, length, lift):
    """[theta, x, y, foot x, y, z] of a step of length at each heading, at t = s = 5."""
    out = [0, 0, 0]
    rows = []
    for theta in thetas:
        x = mul_q15(length, cos(theta))
        y = mul_q15(length, sin(theta))
        track_point(5, 5, x, y, lift, out)
        rows.append([theta, x, y] + list(out))
    return rows


def fine_sines(cases):
    """[sin90_fine(t, s)] of each (t, s)."""
    return [sin90_fine(t, s) for t, s in cases]


def shapes(widths):
    """[[swing_shape(u, w)] for u in 0..w] of each swing width w."""
    out = [0, 0]
    return [[list(swing_shape(u, w, out)) for u in range(w + 1)] for w in widths]


def strokes(widths):
    """[[swing_stroke(u, w)] for u in 0..w] of each swing width w."""
    out = [0, 0]
    return [[list(swing_stroke(u, w, out)) for u in range(w + 1)] for w in widths]
