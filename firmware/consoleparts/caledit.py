"""The console's `cal` (a servo's calibration in force), and the checks and the line the servo jog
commands (consoleparts/joint.py) and the calibration setting ones (consoleparts/calset.py) share:
loaded on demand and let go as the jog commands (Console._calibration). The console names the
command in an err reply.
"""

JOINTS = ("coxa", "femur", "tibia")  # calstore's (not imported: each import cost ~0.4 ms; tests/test_calstore.py)


def command(con, word, args):
    """The reply to a calibration command line's word and arguments on console con."""
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


def _cal(con, args):
    return cal_line(con, servo_index(con, args, 2, "L J (leg 1..6, coxa|femur|tibia)"))


def cal_line(con, k):
    """'ok leg L joint J centre_us C ref_deg R trim T dir D min_us A max_us B' for servo 0..17."""
    import hexapod.units  # (`import a.b`, not `from a.b import c`: that allocates 32 B a call)

    format_fixed = hexapod.units.format_fixed

    s = con.robot.servos[k]
    return "ok leg %d joint %s centre_us %d ref_deg %s trim %d dir %d min_us %d max_us %d" % (
        k // 3 + 1,
        JOINTS[k % 3],
        con.base[k][0],
        format_fixed(s.ref_cdeg, 2),
        con.trims[k],
        s.direction,
        s.min_us,
        s.max_us,
    )


def servo_index(con, args, n, usage):
    """0..17: the servo a command's first two words (leg, joint) name, after its n words' check."""
    con._args(args, n, usage)
    return 3 * con._leg(args[0]) + joint_of(args[1])


_COMMANDS = {
    "cal": _cal,
}
