"""Seed 000's discrete PID (eq. 14) in integers, with the sample time taken from the clock.

    u(k) = Kp e(k) + Ki Ts sum e(k) + Kd (e(k) - e(k-1)) / Ts        (seed 000, eq. 14)

Units: set point and measurement in 0.1 mm; error e = set point - measurement, 0.1 mm,
clamped to +-E_MAX; the output in the caller's command unit (the wall follower: yaw rate,
cdeg/s). Gains are integers in milli-units, so the paper's Kp = 25, Ki = 0.5, Kd = 1 are
kp = 25000 (output per 0.1 mm, x1000), ki = 500 (output per 0.1 mm per s, x1000) and
kd = 1000 (output per 0.1 mm/s, x1000). Time: now_ms from the loop (wrapping at 2**30 like
time.ticks_ms()); Ts is the actual interval since the previous update, in ms.

What differs from eq. 14, and why:
- the derivative is taken on the measurement, -Kd (m(k) - m(k-1)) / Ts: the same as eq. 14
  while the set point holds, and no kick when it changes;
- the integral weighs each error by its own interval (Ki sum Ts(k) e(k): eq. 14 with a
  varying Ts) and is clamped to +-i_max (anti-windup), the output to +-out_max;
- the first update after reset() has no interval: P only (the integral keeps what it has);
  an update whose interval is 0 (the same reading again) changes nothing; one after more
  than TS_MAX_MS counts as a first one (no derivative, no integral step).
Every intermediate stays a small int (|v| < 2**30) for gains up to GAIN_MAX; nothing allocates.
"""

from micropython import const

E_MAX = const(10000)  # error and measurement-step clamp, 0.1 mm (1 m)
GAIN_MAX = const(100000)  # largest kp, ki, kd: 100 output units per 0.1 mm (per s, x s), x1000
OUT_LIMIT = const(9000)  # largest out_max (the walk's largest yaw rate, cdeg/s)
TS_MAX_MS = const(1000)  # an interval longer than this restarts the derivative and integral
_WRAP = const(0x3FFFFFFF)  # time.ticks_ms() wraps at 2**30

KP = const(25000)  # seed 000: Kp = 25
KI = const(500)  # Ki = 0.5
KD = const(1000)  # Kd = 1


def _check(name, v, lo, hi, unit):
    if not isinstance(v, int) or isinstance(v, bool) or v < lo or v > hi:
        raise ValueError("%s: %r is outside %d..%d (%s)" % (name, v, lo, hi, unit))


class PID:
    """One PID loop; update(setpoint, measurement, now_ms) -> output, terms kept as attributes."""

    def __init__(self, kp=KP, ki=KI, kd=KD, out_max=OUT_LIMIT, i_max=OUT_LIMIT):
        """Gains in milli-units (see the module text); out_max, i_max: output clamps (output units)."""
        self.kp = self.ki = self.kd = 0
        self.out_max = self.i_max = 0
        self._i_milli = 0  # the integral term, 0.001 output units
        self.set_gains(kp, ki, kd)
        self.set_limits(out_max, i_max)
        self.reset()

    def set_gains(self, kp, ki, kd):
        """kp, ki, kd in milli-units, each 0..GAIN_MAX; ValueError names the first bad one, changes nothing."""
        _check("kp", kp, 0, GAIN_MAX, "output per 0.1 mm, x1000")
        _check("ki", ki, 0, GAIN_MAX, "output per 0.1 mm per s, x1000")
        _check("kd", kd, 0, GAIN_MAX, "output per 0.1 mm/s, x1000")
        self.kp = kp
        self.ki = ki
        self.kd = kd

    def set_limits(self, out_max, i_max):
        """Output clamp 1..OUT_LIMIT and integral clamp 0..out_max, output units; ValueError if not."""
        _check("out_max", out_max, 1, OUT_LIMIT, "output units")
        _check("i_max", i_max, 0, out_max, "output units, at most out_max")
        self.out_max = out_max
        self.i_max = i_max
        m = i_max * 1000
        if self._i_milli > m:
            self._i_milli = m
        elif self._i_milli < -m:
            self._i_milli = -m
        self.i = (self._i_milli + 500) // 1000

    def reset(self, keep_integral=False):
        """Forget the last sample (the next update is a first one); clear the integral unless kept."""
        self.samples = 0  # updates since reset
        self.last_ms = 0
        self.last_m = 0  # last measurement, 0.1 mm
        self.ts_ms = 0  # interval of the last update, ms (0: none)
        self.error = 0  # last error, 0.1 mm (clamped)
        self.p = 0  # last terms and output, output units
        self.d = 0
        self.output = 0
        if not keep_integral:
            self._i_milli = 0
        self.i = (self._i_milli + 500) // 1000

    def update(self, setpoint, measurement, now_ms):
        """One sample: set point and measurement (0.1 mm) at now_ms; returns the output."""
        e = setpoint - measurement
        if e > E_MAX:
            e = E_MAX
        elif e < -E_MAX:
            e = -E_MAX
        ts = 0
        if self.samples:
            ts = (now_ms - self.last_ms) & _WRAP
            if ts == 0:
                return self.output  # nothing new: the same sample is never counted twice
            if ts > TS_MAX_MS:
                ts = 0  # too long a gap for a rate or a rectangle: start over (integral kept)
        self.error = e
        self.p = (self.kp * e + 500) // 1000
        d = 0
        if ts:
            # Integral in 0.001 output units: ki * Ts * e / 1000, split so no product passes 2**30.
            a = self.ki * ts
            m = self._i_milli + (a // 1000) * e + ((a % 1000) * e + 500) // 1000
            lim = self.i_max * 1000
            if m > lim:
                m = lim
            elif m < -lim:
                m = -lim
            self._i_milli = m
            dm = measurement - self.last_m
            if dm > E_MAX:
                dm = E_MAX
            elif dm < -E_MAX:
                dm = -E_MAX
            d = -((self.kd * dm + (ts >> 1)) // ts)
        self.i = (self._i_milli + 500) // 1000
        self.d = d
        u = self.p + self.i + d
        if u > self.out_max:
            u = self.out_max
        elif u < -self.out_max:
            u = -self.out_max
        self.output = u
        self.ts_ms = ts
        self.last_ms = now_ms
        self.last_m = measurement
        if self.samples < 1000000:
            self.samples += 1
        return u
