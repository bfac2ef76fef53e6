"""The console's servo jog commands (`joint`, `pulse`: one servo to an angle or a pulse), with the
checks of consoleparts/caledit.py: loaded on demand and let go as consoleparts/jog.py
(Console._calibration). The console names the command in an err reply.
"""

from consoleparts.caledit import joint_of, whole  # (both loaded before this one: console.BEFORE)
from consoleparts.jog import jogged


def command(con, word, args):
    """The reply to a servo jog command line's word and arguments on console con."""
    return _COMMANDS[word](con, args)


def _joint(con, args):
    con._args(args, 3, "L J DEG (leg 1..6, coxa|femur|tibia, degrees)")
    leg = con._leg(args[0])
    j = joint_of(args[1])
    a = con._num("angle", args[2], 2, -18000, 18000, "degrees")
    con._no_follow()
    con._battery_ok()
    return jogged(con, leg, con.robot.jog_joint(leg, j, a))


def _pulse(con, args):
    con._args(args, 3, "L J US (leg 1..6, coxa|femur|tibia, microseconds)")
    leg = con._leg(args[0])
    j = joint_of(args[1])
    s = con.robot.servos[3 * leg + j]
    us = whole("pulse", args[2], s.min_us, s.max_us, "us (this servo's calibrated range)")
    con._no_follow()
    con._battery_ok()
    return jogged(con, leg, con.robot.jog_pulse(leg, j, us))


_COMMANDS = {
    "joint": _joint,
    "pulse": _pulse,
}
