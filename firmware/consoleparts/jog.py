"""The console's foot jog commands (`foot`, `nudge`: one leg's foot to a point in its frame):
console.py hands them here (Console._calibration), loaded on demand as the servo jog commands
(consoleparts/joint.py), the calibration commands (consoleparts/caledit.py) and the calibration
file's (consolecal.py), and let go with them when the session ends. consolecal held all five
until 2026-11-28: its import (36 ms on the emulated Pico) made its command's frame late; each of
the five now imports in a frame's slack (Console._waiting). None runs while walking. The console
names the command in an err reply.
"""


def command(con, word, args):
    """The reply to a jog command line's word and arguments on console con."""
    return _COMMANDS[word](con, args)


def _foot(con, args):
    con._args(args, 4, "L X Y Z (leg 1..6, mm in the leg frame)")
    leg = con._leg(args[0])
    x = con._num("x", args[1], 1, -5000, 5000, "mm")
    y = con._num("y", args[2], 1, -5000, 5000, "mm")
    z = con._num("z", args[3], 1, -5000, 5000, "mm")
    con._no_follow()
    con._battery_ok()
    return jogged(con, leg, con.robot.jog_foot(leg, x, y, z))


def jogged(con, leg, code):
    if code:
        return con._refused(code)
    con._walking = False
    return con.leg_line(leg)


def _nudge(con, args):
    con._args(args, 4, "L DX DY DZ (leg 1..6, mm in the leg frame)")
    leg = con._leg(args[0])
    d = [con._num(n, args[k + 1], 1, -1000, 1000, "mm") for k, n in enumerate(("dx", "dy", "dz"))]
    con._no_follow()
    con._battery_ok()
    r = con.robot
    k = 3 * leg
    if not (r.pulses[k] and r.pulses[k + 1] and r.pulses[k + 2]):
        raise ValueError("leg %d has a limp servo: place it with 'foot' first" % (leg + 1))
    foot = [0, 0, 0]
    r.geometry.legs[leg].fk(r.angles[k], r.angles[k + 1], r.angles[k + 2], foot, 0)
    return jogged(con, leg, r.jog_foot(leg, foot[0] + d[0], foot[1] + d[1], foot[2] + d[2]))


_COMMANDS = {
    "foot": _foot,
    "nudge": _nudge,
}
