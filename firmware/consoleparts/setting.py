"""The console's setting commands (`height`, `wall`, `pid`, `stream`): console.py hands them
here (Console._part), as it hands the reporting ones to consoleparts/more.py, and loads and lets go
this module the same way (two smaller compiles on CircuitPython than one; docs/flashing.md). The
console names the command in an err reply; the replies are the console's as before.
"""


def command(con, word, args):
    """The reply to one of these commands' word and arguments on console con (None: it comes later)."""
    return _COMMANDS[word](con, args)


def _height(con, args):
    if args:
        con._args(args, 1, "MM (the body's standing height)")
        g = con.robot.geometry
        h = con._num("height", args[0], 1, g.body_height_min, g.body_height_max, "mm")
        # Standing: the feet move there (checked over the next frames, like a gait); else the
        # next stand goes to it.
        return con._later("height", con.robot.set_height(h, wait=False))
    return con._ok_late("height")


def _wall(con, args):
    from hexapod import limits  # (in the functions: each module-level import cost the module's import ~0.5 ms)
    from hexapod.units import format_fixed

    if len(args) == 1 and args[0] == "off":
        con.runner.follow_off()
        return "ok wall off"
    if len(args) != 3:
        con._args(args, 2, "left|right CM [FORM], or off")
    if args[0] not in limits.SIDES:
        raise ValueError("side %r, allowed left, right or off" % (args[0][:20],))
    cm = con._num("set point", args[1], 2, limits.SETPOINT_MIN, limits.SETPOINT_MAX, "cm")
    form = args[2] if len(args) == 3 else "crab"
    if form not in limits.FORMS:
        raise ValueError("form %r, allowed %s" % (form[:20], ", ".join(limits.FORMS)))
    con._battery_ok()
    con._walking = False
    code = con.runner.follow(args[0], cm, form=form)
    if code:
        return con._refused(code)
    reply = "ok wall %s setpoint %s" % (args[0], format_fixed(cm, 2))
    return reply + " form " + form if len(args) == 3 else reply


def _pid(con, args):
    from hexapod.units import format_fixed

    p = con.runner.follower.pid
    if args:
        con._args(args, 3, "KP KI KD (each 0..100, 3 decimals)")
        top = 100000  # hexapod.pid.GAIN_MAX
        kp = con._num("kp", args[0], 3, 0, top, "")
        ki = con._num("ki", args[1], 3, 0, top, "")
        kd = con._num("kd", args[2], 3, 0, top, "")
        con.runner.follower.set_gains(kp, ki, kd)
    return "ok pid %s %s %s" % (format_fixed(p.kp, 3), format_fixed(p.ki, 3), format_fixed(p.kd, 3))


def _stream(con, args):
    from drivers import stream  # only now: a board that never streams keeps its heap and names

    return stream.command(con, args)


_COMMANDS = {
    "height": _height,
    "wall": _wall,
    "pid": _pid,
    "stream": _stream,
}
