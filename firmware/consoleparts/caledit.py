"""The console's `cal` (a servo's calibration in force) and the line and servo checks the
calibration setting commands (consoleparts/calset.py: `trim`, `dir`, `range`) share, with the
joint check of consoleparts/joint.py: loaded on demand and let go as the jog commands
(Console._calibration). The console names the command in an err reply.
"""

from consoleparts.joint import JOINTS, joint_of  # (loaded before this module: console.NEEDS)


def command(con, word, args):
    """The reply to a calibration command line's word and arguments on console con."""
    return _COMMANDS[word](con, args)


def _cal(con, args):
    return cal_line(con, servo_index(con, args, 2, "L J (leg 1..6, coxa|femur|tibia)"))


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


def servo_index(con, args, n, usage):
    """0..17: the servo a command's first two words (leg, joint) name, after its n words' check."""
    con._args(args, n, usage)
    return 3 * con._leg(args[0]) + joint_of(args[1])


_COMMANDS = {
    "cal": _cal,
}
