"""Fixed-point inverse and forward kinematics of one three-joint leg.

Leg frame (design.md): origin on the coxa axis, x outward along the mount direction, y to
the left of it, z up; lengths in 0.1 mm. Joint angles in centidegrees as in seed 004's DH
table: theta1 coxa yaw (counter-clockwise seen from above), theta2 femur pitch from the
horizontal (up is positive), theta3 tibia relative to the femur (negative: knee bent
down). The femur joint sits `coxa` out along the coxa and `femur_offset` above the origin
(seed 004's a1 and d1).

The law of cosines is used in its half-angle and atan2 forms on exact integer products, so
the solve stays well-conditioned near full extension and near the minimum reach. Every
intermediate stays within MicroPython's small-int range (tests/test_leg_ranges.py checks).
"""

import sys
from array import array

from micropython import const

from hexapod.fixmath import ONE, atan2, cos, isqrt, mul_q15, sin, to_cdeg
from hexapod.units import format_fixed

# The viper twin (docs/viper.md): solve compiled by the viper emitter where MicroPython has one
# (hexapod/_leg_viper.py, proven equal to `solve` by tests/test_leg_viper.py); CPython and
# CircuitPython use `solve`.
_solve_fast = None
if sys.implementation.name == "micropython":
    try:
        from hexapod._leg_viper import solve as _solve_fast
    except Exception:  # no viper emitter on this build
        _solve_fast = None

OK = const(0)
TOO_FAR = const(1)
TOO_CLOSE = const(2)
COXA_LOW = const(3)
COXA_HIGH = const(4)
FEMUR_LOW = const(5)
FEMUR_HIGH = const(6)
TIBIA_LOW = const(7)
TIBIA_HIGH = const(8)
OUT_OF_RANGE = const(9)

COORD_MAX = const(30000)  # largest |x|, |y|, |z| accepted, 0.1 mm (3 m)
COXA_MAX = const(1500)  # longest coxa, 0.1 mm
LINK_MIN = const(100)  # shortest femur or tibia, 0.1 mm (10 mm: no servo link is shorter)
LINK_MAX = const(2500)  # longest femur or tibia, 0.1 mm
OFFSET_MAX = const(1500)  # largest |femur_offset|, 0.1 mm
ANGLE_MAX = const(18000)  # joint limits lie within +-180 degrees, centidegrees

# Servo travel of 180 degrees at each joint (seed 001: 600-2400 us), centidegrees.
DEFAULT_LIMITS = (-9000, 9000, -9000, 9000, -18000, 0)

_DEG180 = const(1800000)  # 180 degrees in fixmath.ANGLE_UNIT
_DEG360 = const(3600000)
_TWO28 = const(268435456)

_JOINTS = ("coxa", "femur", "tibia")

# Slots of a leg's solver array: geometry in (0.1 mm, 0.1 mm^2), result out (0.1 mm, cdeg).
# The geometry slots hold no negative number: viper's ptr32 loads are unsigned.
G_COXA = const(0)
G_OFFSET_UP = const(1)  # femur_offset when above the coxa origin, else 0
G_OFFSET_DOWN = const(2)  # -femur_offset when below it, else 0
G_REACH = const(3)
G_MIN_REACH = const(4)
G_SUM2 = const(5)  # (femur + tibia)^2
G_DIF2 = const(6)  # (femur - tibia)^2
G_FEMUR2 = const(7)
G_TIBIA2 = const(8)
G_EXCESS = const(9)
G_T1 = const(10)
G_T2 = const(11)
G_T3 = const(12)
G_SIZE = const(13)


def _sqrt12(vi, vf):
    """sqrt(vi + vf / 2**16) * 2**12, floored; 0 <= vi < 2**25, 0 <= vf < 2**16."""
    # Scale by the largest even power of two that fits: a small value (near full
    # extension or the minimum reach) keeps all 16 fraction bits of vf.
    s = 16
    lim = 8192  # 2**29 >> s: compare before shifting, so no product passes 2**30
    while vi >= lim:
        s -= 2
        lim <<= 2
    n = (vi << s) + (vf >> (16 - s))
    r = isqrt(n)
    # 4 to 10 more bits from one Newton step on the remainder (rem <= 2r < 2**16).
    k = 12 - (s >> 1)
    return (r << k) + (((n - r * r) << k) // ((r << 1) + 1))


def _bits_over_15(v):
    """How far v (>= 0, < 2**30) must be shifted right to fit in 15 bits."""
    e = 0
    while (v >> e) >= 32768:
        e += 1
    return e


class Leg:
    """One leg's geometry and joint limits; solves IK and FK into caller-owned buffers."""

    def __init__(self, *, coxa, femur, tibia, femur_offset=0, limits=DEFAULT_LIMITS):
        """Lengths in 0.1 mm; limits = (coxa_min, coxa_max, femur_min, ..., tibia_max), cdeg."""
        _check_int("coxa", coxa, 0, COXA_MAX)
        _check_int("femur", femur, LINK_MIN, LINK_MAX)
        _check_int("tibia", tibia, LINK_MIN, LINK_MAX)
        _check_int("femur_offset", femur_offset, -OFFSET_MAX, OFFSET_MAX)
        if len(limits) != 6:
            raise ValueError("limits: need 6 values (min, max for coxa, femur, tibia), got %d" % len(limits))
        for k in range(6):
            name = "%s %s limit" % (_JOINTS[k >> 1], "max" if k & 1 else "min")
            _check_int(name, limits[k], -ANGLE_MAX, ANGLE_MAX)
        for k in (0, 2, 4):
            if limits[k] > limits[k + 1]:
                raise ValueError(
                    "limits: %s min %d cdeg is above its max %d cdeg" % (_JOINTS[k >> 1], limits[k], limits[k + 1])
                )
        self.coxa = coxa
        self.femur = femur
        self.tibia = tibia
        self.femur_offset = femur_offset
        self.limits = tuple(limits)
        self.reach = femur + tibia  # longest femur-joint-to-foot distance, 0.1 mm
        self.min_reach = femur - tibia if femur > tibia else tibia - femur
        self.excess = 0  # by how much the last refused solve missed: 0.1 mm or cdeg
        # The solver's own geometry and result slots (G_*), made once: the solve allocates nothing.
        g = array("i", [0] * G_SIZE)
        g[G_COXA] = coxa
        g[G_OFFSET_UP] = femur_offset if femur_offset > 0 else 0
        g[G_OFFSET_DOWN] = -femur_offset if femur_offset < 0 else 0
        g[G_REACH] = self.reach
        g[G_MIN_REACH] = self.min_reach
        g[G_SUM2] = self.reach * self.reach
        g[G_DIF2] = self.min_reach * self.min_reach
        g[G_FEMUR2] = femur * femur
        g[G_TIBIA2] = tibia * tibia
        self._g = g
        self._solver = solve if _solve_fast is None else _solve_fast

    def ik(self, x, y, z, out, i=0):
        """Joint angles (cdeg) of the foot at (x, y, z), 0.1 mm, into out[i:i+3].

        Returns OK, or a reason code with `excess` set; out is untouched on refusal.
        """
        g = self._g
        code = self._solver(x, y, z, g)
        if code:
            self.excess = g[G_EXCESS]
            return code
        return self.accept(g[G_T1], g[G_T2], g[G_T3], out, i)

    def accept(self, t1, t2, t3, out, i=0):
        """Store angles (cdeg) into out[i:i+3] when every joint is inside its limits.

        Returns OK, or the first limit broken with `excess` set; out is untouched then.
        """
        lim = self.limits
        if t1 < lim[0]:
            self.excess = lim[0] - t1
            return COXA_LOW
        if t1 > lim[1]:
            self.excess = t1 - lim[1]
            return COXA_HIGH
        if t2 < lim[2]:
            self.excess = lim[2] - t2
            return FEMUR_LOW
        if t2 > lim[3]:
            self.excess = t2 - lim[3]
            return FEMUR_HIGH
        if t3 < lim[4]:
            self.excess = lim[4] - t3
            return TIBIA_LOW
        if t3 > lim[5]:
            self.excess = t3 - lim[5]
            return TIBIA_HIGH
        out[i] = t1
        out[i + 1] = t2
        out[i + 2] = t3
        return OK

    def fk(self, t1, t2, t3, out, i=0):
        """Foot position (x, y, z), 0.1 mm, of joint angles in cdeg, into out[i:i+3]."""
        t23 = t2 + t3
        rho = self.coxa * ONE + self.femur * cos(t2) + self.tibia * cos(t23)  # Q15
        zq = self.femur * sin(t2) + self.tibia * sin(t23)
        out[i] = (mul_q15(rho, cos(t1)) + 16384) >> 15
        out[i + 1] = (mul_q15(rho, sin(t1)) + 16384) >> 15
        out[i + 2] = self.femur_offset + ((zq + 16384) >> 15)
        return OK


def solve(x, y, z, g):
    """IK of one foot (0.1 mm, leg frame) with the geometry in g (G_* slots).

    Returns OK with theta1..3 (cdeg) in g[G_T1..G_T3], or TOO_FAR, TOO_CLOSE or
    OUT_OF_RANGE with g[G_EXCESS] (0.1 mm); joint limits are the caller's (Leg.accept).
    """
    if x > COORD_MAX or x < -COORD_MAX or y > COORD_MAX or y < -COORD_MAX or z > COORD_MAX or z < -COORD_MAX:
        m = x if x >= 0 else -x
        if y > m or -y > m:
            m = y if y >= 0 else -y
        if z > m or -z > m:
            m = z if z >= 0 else -z
        g[G_EXCESS] = m - COORD_MAX
        return OUT_OF_RANGE
    a1 = g[G_COXA]
    reach = g[G_REACH]
    v = z - g[G_OFFSET_UP] + g[G_OFFSET_DOWN]
    big = a1 + reach
    if x > big or x < -big or y > big or y < -big or v > reach or v < -reach:
        # Far outside: quartered coordinates keep the squares below 2**30 (excess +-0.5 mm).
        xs = x >> 2
        ys = y >> 2
        hs = ((isqrt(xs * xs + ys * ys) << 2) - a1) >> 2
        vs = v >> 2
        m = (isqrt(hs * hs + vs * vs) << 2) - reach
        g[G_EXCESS] = m if m > 0 else 1
        return TOO_FAR
    r2 = x * x + y * y
    # r = sqrt(r2) = (rj + fk / 2**16) / 2**j, with r2 scaled into [2**28, 2**30).
    j = 0
    rj = 0
    fk = 0
    if r2:
        n = r2
        while n < _TWO28:
            n <<= 2
            j += 1
        rj = isqrt(n)
        rem = n - rj * rj
        d = rj << 1
        # f = rem / (2 rj + f): divide by the denominator with f's first guess in it,
        # 16 quotient bits in two steps of 8 so that no numerator passes 2**29.
        d4 = (d << 4) + (rem << 4) // d
        num = rem << 12
        q = num // d4
        fk = (q << 8) + (((num - q * d4) << 8) // d4)
    # 2 * coxa * r = ti + tf / 2**16, exactly to 16 fraction bits.
    mm = (a1 * rj) << 1
    ti = mm >> j
    tf = ((mm - (ti << j)) << (16 - j)) + (((a1 * fk) << 1) >> j)
    ti += tf >> 16
    tf &= 65535
    # c^2 = ci - tf / 2**16: squared distance from the femur joint to the foot.
    ci = r2 + a1 * a1 + v * v - ti
    pi = g[G_SUM2] - ci  # P = (femur + tibia)^2 - c^2 = pi + tf / 2**16
    if pi < 0:
        g[G_EXCESS] = isqrt(ci - 1) + 1 - reach
        return TOO_FAR
    qi = ci - g[G_DIF2]  # Q = c^2 - (femur - tibia)^2 = qi + qf / 2**16
    qf = 0
    if tf:
        qi -= 1
        qf = 65536 - tf
    if qi < 0:
        g[G_EXCESS] = g[G_MIN_REACH] - isqrt(ci)
        return TOO_CLOSE
    sp = _sqrt12(pi, tf)
    sq = _sqrt12(qi, qf)
    # Knee: tan(gamma / 2) = sqrt(Q / P); theta3 = gamma - 180 degrees.
    t3 = (atan2(sq, sp) << 1) - _DEG180
    # Femur-joint angle between femur and foot line: atan2(sqrt(PQ), a^2 + c^2 - b^2),
    # both at scale 2**4 (sqrt(PQ) has scale 2**(24 - e) with e <= 20).
    e1 = _bits_over_15(sp)
    e2 = _bits_over_15(sq)
    e = 20 - e1 - e2
    yb = (sp >> e1) * (sq >> e2)
    if e > 0:
        yb = (yb + (1 << (e - 1))) >> e
    xb = ((g[G_FEMUR2] - g[G_TIBIA2] + ci) << 4) - (tf >> 12)
    # Foot line seen from the femur joint: h = r - coxa and v at scale 2**16 (both are
    # below 2**13 here). h is formed at scale 2**j first, so it stays exact when small.
    h = ((rj - (a1 << j)) << (16 - j)) + (fk >> j)
    t2 = atan2(v << 16, h) + atan2(yb, xb)
    if t2 > _DEG180:
        t2 -= _DEG360
    g[G_T1] = to_cdeg(atan2(y, x))
    g[G_T2] = to_cdeg(t2)
    g[G_T3] = to_cdeg(t3)
    return OK


def _check_int(name, value, lo, hi):
    if not isinstance(value, int) or isinstance(value, bool):
        raise ValueError("%s: need a whole number, got %r" % (name, value))
    if value < lo or value > hi:
        raise ValueError("%s: %d is outside the allowed %d..%d" % (name, value, lo, hi))


def describe(code, excess):
    """A sentence for a reason code and its excess (0.1 mm or cdeg), for the edges."""
    if code == OK:
        return "ok"
    if code == TOO_FAR:
        return "too far: %s mm beyond the reach" % format_fixed(excess, 1)
    if code == TOO_CLOSE:
        return "too close: %s mm inside the minimum reach" % format_fixed(excess, 1)
    if code == OUT_OF_RANGE:
        return "out of range: a coordinate is %s mm past the +-%s mm accepted" % (
            format_fixed(excess, 1),
            format_fixed(COORD_MAX, 1),
        )
    if COXA_LOW <= code <= TIBIA_HIGH:
        k = code - COXA_LOW
        return "%s %s its limit by %s deg" % (
            _JOINTS[k >> 1],
            "above" if k & 1 else "below",
            format_fixed(excess, 2),
        )
    return "unknown reason %d" % code
