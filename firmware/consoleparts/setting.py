"""The console's setting commands (`height`, `pid`, `stream`; `wall` is consoleparts/wall.py's):
console.py hands them here (Console._part), as it hands the reporting ones to consoleparts/more.py,
and loads and lets go this module the same way (two smaller compiles on CircuitPython than one;
docs/flashing.md). The console names the command in an err reply; the replies are the console's as
before.
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


def _pid(con, args):
    import hexapod.units  # (`import a.b`, not `from a.b import c`: that allocates 32 B a call)

    format_fixed = hexapod.units.format_fixed

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
    "pid": _pid,
    "stream": _stream,
}
