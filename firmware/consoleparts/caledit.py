"""The console's calibration commands (`cal`, `trim`, `dir`, `range`), and the joint and number
checks the jog commands (consoleparts/jog.py) share: loaded on demand and let go as those
(Console._calibration). The console names the command in an err reply.
"""

# No import at the module's top (each cost its import ~0.4 ms on the emulated Pico): calstore's
# JOINTS and TRIM_MAX, hexapod.tick's JOG_SERVO written out (tests/test_calstore.py compares them).
JOINTS = ("coxa", "femur", "tibia")
TRIM_MAX = 300
JOG_SERVO = 27


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
    return cal_line(con, _servo(con, args, 2, "L J (leg 1..6, coxa|femur|tibia)"))


def cal_line(con, k):
    """'ok leg L joint J centre_us C ref_deg R trim T dir D min_us A max_us B' for servo 0..17."""
    from hexapod.units import format_fixed

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


def _servo(con, args, n, usage):
    con._args(args, n, usage)
    return 3 * con._leg(args[0]) + joint_of(args[1])


def _set_cal(con, k, trim, direction, lo, hi):
    r = con.robot
    code = r.calibrate(k, con.base[k][0] + trim, direction, lo, hi)
    if code == JOG_SERVO:
        from hexapod.units import format_fixed

        return "err leg %d %s: at %s deg it would need %d us, outside %d..%d us" % (
            k // 3 + 1,
            JOINTS[k % 3],
            format_fixed(r.angles[k], 2),
            lo - r.jog_excess if r.jog_code == 1 else hi + r.jog_excess,
            lo,
            hi,
        )
    if code:
        return con._refused(code)
    con.trims[k] = trim
    con.cal_source = "changed"
    return cal_line(con, k)


def _trim(con, args):
    k = _servo(con, args, 3, "L J US (leg 1..6, coxa|femur|tibia, us)")
    c = con.base[k][0]
    lo = -TRIM_MAX if c - TRIM_MAX >= 500 else 500 - c
    hi = TRIM_MAX if c + TRIM_MAX <= 2500 else 2500 - c
    t = whole("trim", args[2], lo, hi, "us (centre_us %d + trim within 500..2500)" % c)
    s = con.robot.servos[k]
    return _set_cal(con, k, t, s.direction, s.min_us, s.max_us)


def _dir(con, args):
    k = _servo(con, args, 3, "L J D (leg 1..6, coxa|femur|tibia, 1 or -1)")
    if args[2] not in ("1", "-1", "+1"):
        raise ValueError("direction %r, allowed 1 or -1" % (args[2][:20],))
    s = con.robot.servos[k]
    return _set_cal(con, k, con.trims[k], int(args[2]), s.min_us, s.max_us)


def _range(con, args):
    k = _servo(con, args, 4, "L J MIN MAX (leg 1..6, coxa|femur|tibia, us)")
    lo = whole("min_us", args[2], 500, 2500, "us")
    hi = whole("max_us", args[3], 500, 2500, "us")
    if lo >= hi:
        raise ValueError("min_us %d must be below max_us %d" % (lo, hi))
    s = con.robot.servos[k]
    return _set_cal(con, k, con.trims[k], s.direction, lo, hi)


_COMMANDS = {
    "cal": _cal,
    "trim": _trim,
    "dir": _dir,
    "range": _range,
}
