"""The console's `wall` command (wall following on and off): console.py hands it here
(Console._part) and loads and lets go this module as consoleparts/setting.py, which held it until
2026-11-28 (that module's import, 16.7 ms on the emulated Pico, was more than a frame's slack).
The console names the command in an err reply.
"""


def command(con, word, args):
    """The reply to `wall` with its arguments on console con."""
    return _wall(con, args)


def _wall(con, args):
    # In the function (a module-level import cost the module's import ~0.5 ms), as `import a.b` (a
    # `from a import b` allocates 32 B a call).
    import hexapod.limits
    import hexapod.units

    limits = hexapod.limits
    format_fixed = hexapod.units.format_fixed

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
