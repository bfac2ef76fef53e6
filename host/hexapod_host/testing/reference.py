"""Float reference kinematics: the host-side test oracle (never shipped to a board).

Same conventions as firmware/hexapod/leg.py, written the textbook way with floats: the
law of cosines with acos (seed 003 eq. 1-9) for IK, and two independent forward
kinematics: seed 004's closed form (eq. 5-7) and the product of its DH matrices (eq. 1-4).
Lengths in the same unit in and out; angles in degrees.
"""

import math


def ik(x, y, z, coxa, femur, tibia, femur_offset=0.0):
    """(theta1, theta2, theta3) in degrees, knee down; None when out of reach."""
    t1 = math.degrees(math.atan2(y, x))
    h = math.hypot(x, y) - coxa
    v = z - femur_offset
    c = math.hypot(h, v)
    if c > femur + tibia or c < abs(femur - tibia) or c == 0.0:
        return None
    cos_b = (femur * femur + c * c - tibia * tibia) / (2 * femur * c)
    cos_g = (femur * femur + tibia * tibia - c * c) / (2 * femur * tibia)
    b = math.acos(max(-1.0, min(1.0, cos_b)))
    g = math.acos(max(-1.0, min(1.0, cos_g)))
    t2 = math.degrees(math.atan2(v, h) + b)
    if t2 > 180.0:
        t2 -= 360.0
    return t1, t2, math.degrees(g) - 180.0


def fk(t1, t2, t3, coxa, femur, tibia, femur_offset=0.0):
    """Seed 004 eq. 5-7: foot (x, y, z) of joint angles in degrees."""
    a1, a2, a23 = math.radians(t1), math.radians(t2), math.radians(t2 + t3)
    rho = coxa + femur * math.cos(a2) + tibia * math.cos(a23)
    return rho * math.cos(a1), rho * math.sin(a1), femur_offset + femur * math.sin(a2) + tibia * math.sin(a23)


def _dh(theta, d, a, alpha):
    ct, st = math.cos(theta), math.sin(theta)
    ca, sa = math.cos(alpha), math.sin(alpha)
    return [[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st], [0.0, sa, ca, d], [0, 0, 0, 1.0]]


def _mul(m, n):
    return [[sum(m[i][k] * n[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def fk_dh(t1, t2, t3, coxa, femur, tibia, femur_offset=0.0):
    """Seed 004 eq. 1-4: the same foot from the product of the three DH matrices (Table 2)."""
    m = _mul(
        _mul(_dh(math.radians(t1), femur_offset, coxa, math.pi / 2), _dh(math.radians(t2), 0.0, femur, 0.0)),
        _dh(math.radians(t3), 0.0, tibia, 0.0),
    )
    # DH frame 1 has z1 along the femur axis: with alpha1 = +90 the chain's z comes out up.
    return m[0][3], m[1][3], m[2][3]


def track_point(t, s, x, y, z):
    """Seed 003 eq. 12-14 in floats, as printed: foot offset at step t of s for lengths x, y, z."""
    a = math.radians(t * 90.0 / s)
    b = math.radians((s - t) * 90.0 / s)
    return x * math.sin(a), y * math.sin(a), z - z * (1.0 - math.sin(b))


class PidFloat:
    """Seed 000 eq. 14 in floats, as firmware/hexapod/pid.py states it: real gains (the paper's
    Kp = 25, Ki = 0.5, Kd = 1 in output units per 0.1 mm, per 0.1 mm s, per 0.1 mm/s), derivative
    on the measurement, each error weighed by its own interval Ts (s), integral clamped to
    +-i_max, output to +-out_max, error and measurement step to +-e_max; the first sample and one
    after more than ts_max_ms are P only; a zero interval changes nothing."""

    def __init__(self, kp, ki, kd, out_max, i_max, e_max=10000, ts_max_ms=1000):
        self.kp, self.ki, self.kd = kp, ki, kd
        self.out_max, self.i_max, self.e_max, self.ts_max_ms = out_max, i_max, e_max, ts_max_ms
        self.integral = 0.0
        self.first = True
        self.last_ms = self.last_m = 0
        self.output = 0.0

    def update(self, setpoint, measurement, now_ms):
        e = max(-self.e_max, min(self.e_max, setpoint - measurement))
        ts_ms = 0
        if not self.first:
            ts_ms = (now_ms - self.last_ms) % 2**30
            if ts_ms == 0:
                return self.output
            if ts_ms > self.ts_max_ms:
                ts_ms = 0
        d = 0.0
        if ts_ms:
            ts = ts_ms / 1000.0
            self.integral = max(-self.i_max, min(self.i_max, self.integral + self.ki * ts * e))
            dm = max(-self.e_max, min(self.e_max, measurement - self.last_m))
            d = -self.kd * dm / ts
        u = self.kp * e + self.integral + d
        self.output = max(-self.out_max, min(self.out_max, u))
        self.first = False
        self.last_ms, self.last_m = now_ms, measurement
        return self.output
