"""The console's reporting commands (`help`, `echo`, `faults`; `status` is console.py's, `sonar`
consoleparts/sonar.py's): console.py hands them here (Console._part; the setting commands are
consoleparts/setting.py's). The console
imports this module at the first of them; MicroPython keeps it while they keep coming (let go
CAL_KEEP_MS after the last one); CircuitPython, which compiles a module's source at each import,
compiles it for the command and lets it go after (hexapod.release), so the console's own compile
and the running loop's heap are smaller (docs/flashing.md). The console names the command in
an err reply; the replies are the console's as before.
"""


def command(con, word, args):
    """The reply to one of these commands' word and arguments on console con (None: it comes later)."""
    return _COMMANDS[word](con, args)


def _help(con, args):
    import console  # (in the functions: each module-level import cost the module's import ~0.5 ms)

    con._args(args, 0, "no arguments")
    return "ok " + console.COMMANDS


def _echo(con, args):
    if len(args) > 1 or (args and args[0] not in ("on", "off")):
        raise ValueError("need on, off or nothing (ask), got %r" % (" ".join(args)[:20],))
    if args and args[0] == "on" and con.write is None:
        raise ValueError("this console has no raw output to echo to")
    if args:
        con.echo = args[0] == "on"
    return "ok echo " + ("on" if con.echo else "off")


def _faults(con, args):
    if len(args) > 1 or (args and args[0] != "clear"):
        raise ValueError("need clear or nothing (list), got %r" % (" ".join(args)[:20],))
    import console

    log = con.runner.faultlog
    if args:
        log.clear()
        return "ok faults cleared"
    return "ok faults " + console.fault_text(log, con.runner.bank)


_COMMANDS = {
    "help": _help,
    "echo": _echo,
    "faults": _faults,
}
