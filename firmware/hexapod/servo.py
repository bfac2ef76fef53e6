"""Joint angle to servo pulse width: pulse_us = centre_us + direction * (angle - ref) * us_per_degree.

Angles in centidegrees, pulses in microseconds, us_per_degree in 0.01 us per degree
(1000 = seed 001's 10 us per degree: 600 us = -90, 1500 us = 0, 2400 us = +90 degrees
about the centre). centre_us is the pulse at the servo's reference angle ref_cdeg, the joint
angle it is calibrated at (0 unless given; the tibia's is mid-travel, -90 degrees, so its trim
has room both ways): a change of reference, never of mapping, so the same calibration gives
the same pulse for the same angle whatever the reference. The calibrated min/max clamp is the
last line of defence: a command that would need it is refused first by `pulse`, which says by
how much it missed.
"""

from array import array

from micropython import const

OK = const(0)
BELOW_MIN = const(1)
ABOVE_MAX = const(2)

PULSE_MIN_US = const(500)  # widest range any servo may be calibrated to
PULSE_MAX_US = const(2500)
_REF_MAX = const(18000)  # a reference angle's range, -_REF_MAX.._REF_MAX cdeg

# ServoMap.cal's words.
_CENTRE = const(0)
_DIRECTION = const(1)
_PER_DEGREE = const(2)
_MIN = const(3)
_MAX = const(4)


def _put(words, k, v):
    words[k] = v


def _word(k):
    """A property reading and writing word k of a ServoMap's cal."""
    return property(lambda self: self.cal[k], lambda self, v: _put(self.cal, k, v))


class ServoMap:
    """One servo's calibration; maps centidegrees to microseconds."""

    def __init__(self, *, centre_us=1500, direction=1, us_per_degree=1000, min_us=600, max_us=2400, ref_cdeg=0):
        for name, v in (("centre_us", centre_us), ("min_us", min_us), ("max_us", max_us)):
            if not isinstance(v, int) or v < PULSE_MIN_US or v > PULSE_MAX_US:
                raise ValueError("%s: %r is outside %d..%d us" % (name, v, PULSE_MIN_US, PULSE_MAX_US))
        if min_us > centre_us or centre_us > max_us:
            raise ValueError("need min_us <= centre_us <= max_us, got %d, %d, %d" % (min_us, centre_us, max_us))
        if direction not in (1, -1):
            raise ValueError("direction: %r, allowed 1 or -1" % (direction,))
        if not isinstance(us_per_degree, int) or us_per_degree < 100 or us_per_degree > 5000:
            raise ValueError("us_per_degree: %r is outside 100..5000 (0.01 us per degree)" % (us_per_degree,))
        if not isinstance(ref_cdeg, int) or isinstance(ref_cdeg, bool) or ref_cdeg < -_REF_MAX or ref_cdeg > _REF_MAX:
            raise ValueError("ref_cdeg: %r is outside %d..%d (0.01 deg)" % (ref_cdeg, -_REF_MAX, _REF_MAX))
        if ref_cdeg * us_per_degree % 10000:  # its distance from angle 0 must be a whole us (exact)
            raise ValueError(
                "ref_cdeg: %d at %d (0.01 us per degree) is not a whole us from angle 0: allowed whole degrees"
                % (ref_cdeg, us_per_degree)
            )
        self.ref_cdeg = ref_cdeg  # the joint angle centre_us is the pulse at, cdeg
        self._ref_us = ref_cdeg * us_per_degree // 10000  # its distance from angle 0, us
        # The pulse at angle 0, direction, us_per_degree, min_us, max_us as machine words
        # (array("i")): the tick's viper frame (hexapod/_tick_viper.py) reads all five for one
        # attribute lookup.
        self.cal = array("i", [centre_us - direction * self._ref_us, direction, us_per_degree, min_us, max_us])
        self.excess = 0  # microseconds past the range on the last refusal

    # The pulse at the reference angle, us (cal keeps the pulse at angle 0). Setting it (or the
    # direction) keeps the other: a flipped direction mirrors the servo about its reference, the
    # pulse at angle 0 moving by (old - new direction) * the reference's offset. Properties over
    # lambdas, as _word's: a named setter would be one more name kept on the board.
    centre_us = property(
        lambda self: self.cal[_CENTRE] + self.cal[_DIRECTION] * self._ref_us,
        lambda self, v: _put(self.cal, _CENTRE, v - self.cal[_DIRECTION] * self._ref_us),
    )
    direction = property(  # 1, or -1 for a servo mounted the other way round
        lambda self: self.cal[_DIRECTION],
        lambda self, d: (
            _put(self.cal, _CENTRE, self.cal[_CENTRE] + (self.cal[_DIRECTION] - d) * self._ref_us)
            or _put(self.cal, _DIRECTION, d)
        ),
    )

    # The other three as properties over cal (each one attribute, as before, for every other user).
    us_per_degree = property(lambda self: self.cal[_PER_DEGREE])  # pulse change per degree, 0.01 us
    min_us = _word(_MIN)  # shortest pulse this servo may get, us
    max_us = _word(_MAX)  # longest pulse this servo may get, us

    def raw_at(self, cdeg, centre_us, direction):
        """The pulse cdeg would get with another centre_us and direction (a recalibration's check)."""
        return centre_us + direction * ((cdeg * self.cal[_PER_DEGREE] + 5000) // 10000 - self._ref_us)

    def raw(self, cdeg):
        """Unclamped pulse width in us for an angle in cdeg (rounded half up)."""
        c = self.cal
        # cdeg * 0.01 us/deg-units / 100 cdeg/deg / 100 -> us; |cdeg| < 2**16 keeps this small.
        return c[_CENTRE] + c[_DIRECTION] * ((cdeg * c[_PER_DEGREE] + 5000) // 10000)

    def pulse(self, cdeg, out, i):
        """Store the pulse for cdeg into out[i] when inside min..max; else a code and `excess`."""
        p = self.raw(cdeg)
        c = self.cal
        if p < c[_MIN]:
            self.excess = c[_MIN] - p
            return BELOW_MIN
        if p > c[_MAX]:
            self.excess = p - c[_MAX]
            return ABOVE_MAX
        out[i] = p
        return OK

    def clamp(self, pulse_us):
        """The last line of defence: pulse_us forced into min..max."""
        c = self.cal
        if pulse_us < c[_MIN]:
            return c[_MIN]
        if pulse_us > c[_MAX]:
            return c[_MAX]
        return pulse_us

    def angle(self, pulse_us):
        """Inverse map: centidegrees for a pulse width in us (for calibration tools)."""
        c = self.cal
        return (c[_DIRECTION] * (pulse_us - c[_CENTRE]) * 10000) // c[_PER_DEGREE]
