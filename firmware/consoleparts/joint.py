"""The console's servo jog commands (`joint`, `pulse`: one servo to an angle or a pulse) and the
joint and number checks the calibration commands (consoleparts/caledit.py) share: loaded on demand
and let go as consoleparts/jog.py (Console._calibration). The console names the command in an err
reply.
"""

JOINTS = ("coxa", "femur", "tibia")  # calstore's (no import at the top: each cost ~0.4 ms; tests/test_calstore.py)


def command(con, word, args):
    """The reply to a servo jog command line's word and arguments on console con."""
    return _COMMANDS[word](con, args)


def joint_of(text):
    """0, 1, 2 for coxa, femur, tibia; ValueError for anything else."""
    for j in range(3):
        if JOINTS[j] == text:
            return j
    raise ValueError("joint %r, allowed coxa, femur, tibia" % (text[:20],))


def whole(name, text, lo, hi, unit):
    """text as a whole number within lo..hi; ValueError naming `name` and `unit` otherwise."""
    body = text[1:] if text[:1] in ("-", "+") else text
    if not body.isdigit() or len(body) > 9:
        raise ValueError("%s %r is not a whole number (%s)" % (name, text[:20], unit))
    v = int(text)
    if v < lo or v > hi:
        raise ValueError("%s %d is outside %d..%d %s" % (name, v, lo, hi, unit))
    return v


def _joint(con, args):
    con._args(args, 3, "L J DEG (leg 1..6, coxa|femur|tibia, degrees)")
    leg = con._leg(args[0])
    j = joint_of(args[1])
    a = con._num("angle", args[2], 2, -18000, 18000, "degrees")
    con._no_follow()
    con._battery_ok()
    from consoleparts.jog import jogged

    return jogged(con, leg, con.robot.jog_joint(leg, j, a))


def _pulse(con, args):
    con._args(args, 3, "L J US (leg 1..6, coxa|femur|tibia, microseconds)")
    leg = con._leg(args[0])
    j = joint_of(args[1])
    s = con.robot.servos[3 * leg + j]
    us = whole("pulse", args[2], s.min_us, s.max_us, "us (this servo's calibrated range)")
    con._no_follow()
    con._battery_ok()
    from consoleparts.jog import jogged

    return jogged(con, leg, con.robot.jog_pulse(leg, j, us))


_COMMANDS = {
    "joint": _joint,
    "pulse": _pulse,
}
