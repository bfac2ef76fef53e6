"""Jogging: the console's single-servo moves on a hexapod.tick.Robot (mode JOG).

Robot.jog_foot, jog_joint and jog_pulse call these (Robot.calibrate stays in the resident tick:
the boot puts a calibration file's rows in force with it, where this module's import would take
a frame); a module of its own so that a
board's heap holds this code only once a jog session begins (a CircuitPython board compiles it at
the first jog command; a loop that never jogs never loads it: docs/flashing.md). The results, the
refusals and the ValueErrors are the Robot methods' own (tests/test_tick_jog.py).
"""

from micropython import const

from hexapod.leg import OK

_JOG_IK = const(26)  # hexapod.tick.JOG_IK
_JOG = const(5)  # hexapod.tick.JOG


def _check_leg(leg):
    if not isinstance(leg, int) or isinstance(leg, bool) or leg < 0 or leg > 5:
        raise ValueError("leg: %r, allowed 0..5 (legs 1..6)" % (leg,))


def _check_joint(joint):
    if not isinstance(joint, int) or isinstance(joint, bool) or joint < 0 or joint > 2:
        raise ValueError("joint: %r, allowed 0 coxa, 1 femur, 2 tibia" % (joint,))


def _servo_ready(r, leg, joint, name, value, unit):
    """ValueError for a bad leg, joint or value; else Robot._can_move()'s code."""
    _check_leg(leg)
    _check_joint(joint)
    if not isinstance(value, int) or isinstance(value, bool):
        raise ValueError("%s: need a whole number (%s), got %r" % (name, unit, value))
    return r._can_move()


def foot(r, leg, x, y, z):
    """Leg `leg` (0..5)'s foot to (x, y, z), 0.1 mm in its leg frame, its three servos driven
    from the next frame on; the other servos keep their pulses (mode JOG). Returns OK, or
    JOG_IK / JOG_SERVO (jog_code, jog_excess say why) or WALKING_NOW / BUSY, changing nothing."""
    _check_leg(leg)
    code = r._can_move()
    if code != OK:
        return code
    k = 3 * leg
    a = r._angles
    lg = r.geometry.legs[leg]
    code = lg.ik(x, y, z, a, k)
    if code != OK:
        r.jog_code = code
        r.jog_excess = lg.excess
        return _JOG_IK
    p = r._pulses
    for j in range(k, k + 3):
        code = r.servos[j].pulse(a[j], p, j)
        if code != OK:
            return r._servo_refused(j, code, r.servos[j].excess)
    for j in range(k, k + 3):
        r.angles[j] = a[j]
        r.pulses[j] = p[j]
    r.mode = _JOG
    return OK


def joint(r, leg, joint, cdeg):
    """One servo (leg 0..5, joint 0 coxa 1 femur 2 tibia) to cdeg, inside the robot file's joint
    limit and the servo's calibrated range; only that servo changes (mode JOG)."""
    code = _servo_ready(r, leg, joint, "angle", cdeg, "cdeg")
    if code != OK:
        return code
    lim = r.geometry.legs[leg].limits
    if cdeg < lim[2 * joint]:
        r.jog_code = 3 + 2 * joint  # hexapod.leg COXA_LOW, FEMUR_LOW, TIBIA_LOW
        r.jog_excess = lim[2 * joint] - cdeg
        return _JOG_IK
    if cdeg > lim[2 * joint + 1]:
        r.jog_code = 4 + 2 * joint
        r.jog_excess = cdeg - lim[2 * joint + 1]
        return _JOG_IK
    k = 3 * leg + joint
    s = r.servos[k]
    code = s.pulse(cdeg, r._pulses, k)
    if code != OK:
        return r._servo_refused(k, code, s.excess)
    r.angles[k] = cdeg
    r.pulses[k] = r._pulses[k]
    r.mode = _JOG
    return OK


def pulse(r, leg, joint, pulse_us):
    """One servo to a raw pulse width (us) inside its calibrated min..max (calibration); its
    angle becomes the servo map's inverse of it. Only that servo changes (mode JOG)."""
    code = _servo_ready(r, leg, joint, "pulse", pulse_us, "us")
    if code != OK:
        return code
    k = 3 * leg + joint
    s = r.servos[k]
    if pulse_us < s.min_us:
        return r._servo_refused(k, 1, s.min_us - pulse_us)  # hexapod.servo BELOW_MIN
    if pulse_us > s.max_us:
        return r._servo_refused(k, 2, pulse_us - s.max_us)  # ABOVE_MAX
    r.angles[k] = s.angle(pulse_us)
    r.pulses[k] = pulse_us
    r.mode = _JOG
    return OK
