"""Seed 003's sine swing trajectory (eq. 12-14) in integers, and the swing the gait uses.

Eq. 12-14: fx = x sin(t 90/s), fy = y sin(t 90/s), fz = z - z (1 - sin((s - t) 90/s)),
for t = -s..s. Its "four combined tracks" start from the middle (t = 0, foot up): track 1
comes down to the front (t = 0..s), tracks 2 and 3 run the stance back on the ground
(t = s-1..1, then 0..-s) and track 4 lifts back to the middle (t = -s+1..0). Table III is
that walk for s = 5, x = 2, z = 2 (cm).

The sine is a parameter: `sin90(t, s)` is sin(t 90/s) in Q15 through fixmath (the tick's
precision: far finer than 0.1 mm at leg scale), and `sin90_fine` is the same quarter-wave
sine at scale 2**FINE_BITS by an integer series, for checking Table III to its sixth
decimal (it makes big integers, so it is never used in the tick).
"""

from micropython import const

from hexapod.fixmath import ONE, mul_q15, sin

FINE_BITS = const(40)
_PI_BITS = const(64)
# pi * 2**64, floored (20 hex digits are more than the 64 bits used).
_PI_SCALED = 0x3243F6A8885A308D3


def sin90(t, s):
    """sin(t * 90 / s degrees) in Q15, for 0 < s <= 2**15 and |t| <= 4 s."""
    # Angle rounded to the nearest centidegree, half up: fixmath's table works in cdeg.
    return sin((t * 18000 + s) // (s << 1))


def sin90_fine(t, s):
    """sin(t * 90 / s degrees) * 2**FINE_BITS rounded, for 0 < s and |t| <= s (big integers)."""
    neg = t < 0
    if neg:
        t = -t
    one = 1 << _PI_BITS
    a = (_PI_SCALED * t) // (s << 1)  # the angle in radians at scale 2**64
    a2 = (a * a) >> _PI_BITS
    term = a
    total = a
    k = 1
    while term:
        term = -((term * a2) >> _PI_BITS) // ((k + 1) * (k + 2))
        total += term
        k += 2
    shift = _PI_BITS - FINE_BITS
    r = (total + (1 << (shift - 1))) >> shift
    if r > (one >> shift):
        r = one >> shift
    return -r if neg else r


def scale_round(v, q, one):
    """v * q / one rounded half up (one a power of two): the plain form of fixmath.mul_q15."""
    return (v * q + (one >> 1)) // one


def track_point(t, s, x, y, z, out, i=0, sine=sin90, one=ONE):
    """Eq. 12-14 at step t of s: (fx, fy, fz) in the units of x, y, z, into out[i:i+3].

    `sine(t, s)` returns sin(t 90/s) at scale `one`; fz uses sin((s - t) 90 / s), which for
    negative t is the far side of the arch, as Table III's track 4 shows.
    """
    q = sine(t, s)
    out[i] = scale_round(x, q, one)
    out[i + 1] = scale_round(y, q, one)
    out[i + 2] = z - scale_round(z, one - sine(s - t if t >= 0 else s + t, s), one)
    return out


def combined_step(k, s, out):
    """Seed 003's combined tracks, step k of 0..4s: (t, lifted) into out[0:2].

    lifted is 1 on tracks 1 and 4 (eq. 14 applies) and 0 on tracks 2 and 3 (z = 0).
    """
    if k <= s:
        out[0] = k
        out[1] = 1
    elif k < 2 * s or k <= 3 * s:
        out[0] = 2 * s - k
        out[1] = 0
    else:
        out[0] = k - 4 * s
        out[1] = 1
    return out


def combined_point(k, s, x, y, z, out, sine=sin90, one=ONE):
    """Foot offset (fx, fy, fz) at step k of seed 003's combined tracks (Table III's rows)."""
    combined_step(k, s, out)
    t = out[0]
    track_point(t, s, x, y, z if out[1] else 0, out, 0, sine, one)
    return out


def swing_shape(u, w, out):
    """The gait's swing at tick u of w (0..w): (forward fraction, height fraction), Q15, into out[0:2].

    Forward fraction runs 0 -> ONE along eq. 12/13 for t = -s..s (zero speed at both ends);
    height is eq. 14's arch squared, so the foot also meets the ground with zero vertical
    speed (a smooth touch-down) while it still peaks at the lift height mid-swing.
    """
    t = (u << 1) - w
    out[0] = (ONE + sin90(t, w) + 1) >> 1
    h = sin90(w - t if t >= 0 else w + t, w)
    out[1] = mul_q15(h, h)
    return out


def swing_stroke(u, w, out):
    """The swing's forward stroke at tick u of w: (stroke fraction, u / w), Q15, into out[0:2].

    The foot is carried at the stance's speed through the whole swing (the u / w part) and
    the stroke, eq. 12/13's (1 + sin) / 2 over the middle w - 2 ticks only, brings it
    forward to the touch-down point: the first and the last tick of every swing move the
    foot exactly as the stance feet move, so a foot that meets the ground a tick early or
    leaves it a tick late does not fight the stance.
    """
    n = w - 2 if w > 3 else w
    k = u - 1 if w > 3 else u
    if k <= 0:
        out[0] = 0
    elif k >= n:
        out[0] = ONE
    else:
        out[0] = (ONE + sin90((k << 1) - n, n) + 1) >> 1
    out[1] = (u << 15) // w
    return out
