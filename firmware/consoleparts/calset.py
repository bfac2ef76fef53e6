"""The console's calibration setting commands (`trim`, `dir`, `range`: a servo's calibration
changed), with the checks of consoleparts/caledit.py: loaded on demand and let go as the
jog commands (Console._calibration). The console names the command in an err reply.
"""

from consoleparts.caledit import JOINTS, cal_line, servo_index, whole  # (loaded before this one: console.BEFORE)

# Written out, not imported (each import at the top cost this module's ~0.4 ms on the emulated
# Pico): calstore's TRIM_MAX, hexapod.tick's JOG_SERVO (tests/test_calstore.py compares them).
TRIM_MAX = 300
JOG_SERVO = 27


def command(con, word, args):
    """The reply to a calibration setting command line's word and arguments on console con."""
    return _COMMANDS[word](con, args)


def _set_cal(con, k, trim, direction, lo, hi):
    r = con.robot
    code = r.calibrate(k, con.base[k][0] + trim, direction, lo, hi)
    if code == JOG_SERVO:
        import hexapod.units

        format_fixed = hexapod.units.format_fixed

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
    k = servo_index(con, args, 3, "L J US (leg 1..6, coxa|femur|tibia, us)")
    c = con.base[k][0]
    lo = -TRIM_MAX if c - TRIM_MAX >= 500 else 500 - c
    hi = TRIM_MAX if c + TRIM_MAX <= 2500 else 2500 - c
    t = whole("trim", args[2], lo, hi, "us (centre_us %d + trim within 500..2500)" % c)
    s = con.robot.servos[k]
    return _set_cal(con, k, t, s.direction, s.min_us, s.max_us)


def _dir(con, args):
    k = servo_index(con, args, 3, "L J D (leg 1..6, coxa|femur|tibia, 1 or -1)")
    if args[2] not in ("1", "-1", "+1"):
        raise ValueError("direction %r, allowed 1 or -1" % (args[2][:20],))
    s = con.robot.servos[k]
    return _set_cal(con, k, con.trims[k], int(args[2]), s.min_us, s.max_us)


def _range(con, args):
    k = servo_index(con, args, 4, "L J MIN MAX (leg 1..6, coxa|femur|tibia, us)")
    lo = whole("min_us", args[2], 500, 2500, "us")
    hi = whole("max_us", args[3], 500, 2500, "us")
    if lo >= hi:
        raise ValueError("min_us %d must be below max_us %d" % (lo, hi))
    s = con.robot.servos[k]
    return _set_cal(con, k, con.trims[k], s.direction, lo, hi)


_COMMANDS = {
    "trim": _trim,
    "dir": _dir,
    "range": _range,
}
