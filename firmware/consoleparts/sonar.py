"""The console's `sonar` (each sensor's last distance and status): console.py hands it here
(Console._part) and loads and lets go this module as consoleparts/more.py, which held it until
2026-11-28 (that module's import, 14-16 ms on the emulated Pico, left too little of a walking
frame). The console names the command in an err reply.
"""


def command(con, word, args):
    """The reply to `sonar` with its arguments on console con."""
    return _sonar(con, args)


def _sonar(con, args):
    import hexapod.sensors  # (`import a.b`, not `from a import b`: that allocates 32 B a call)
    import hexapod.units

    sensors = hexapod.sensors
    format_fixed = hexapod.units.format_fixed

    con._args(args, 0, "no arguments")
    r = con.runner
    parts = ["ok"]
    for k in range(len(r.distances)):
        st = r.sonar_status[k]
        d = r.distances[k]
        parts.append(sensors.SENSOR_NAMES[k])
        parts.append(format_fixed(d, 1) if st == sensors.OK and d >= 0 else "-")
        parts.append(sensors.STATUS_NAMES[st] if 0 <= st < len(sensors.STATUS_NAMES) else "unknown")
    return " ".join(parts)
