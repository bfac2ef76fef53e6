"""A minimal reader of the firmware's telemetry line (`~T ...`, /work/notes/telemetry-spec.md,
docs/console.md once the `stream` command lands), for the view's board sources until the host's
own parser (hexapod_host.serial.telemetry) is on this branch; then this file goes.

parse(line) -> dict with the spec's names; lists for the 18 pulses (us), the five distances
(0.1 mm, None for `-`) and sonar statuses (indices); None for any other `-`. ValueError naming
the field for a malformed line."""

PREFIX = "~T"
SCALARS = ("frame", "mode", "gait", "phase", "follow_mode", "follow_side", "vx", "vy", "yaw")
COUNTERS = ("wall_error", "wall_out", "battery_mv", "held", "overruns", "bus_failed", "sonar_faults")
FIELDS = len(SCALARS) + 18 + 5 + 5 + len(COUNTERS)  # 44


def _int(text, name):
    if text == "-":
        return None
    try:
        return int(text)
    except ValueError:
        raise ValueError("telemetry field %s: %r is not a whole number or '-'" % (name, text[:20])) from None


def parse(line):
    words = line.split()
    if not words or words[0] != PREFIX:
        raise ValueError("not a telemetry line (starts %r, not %r)" % (line[:8], PREFIX))
    f = words[1:]
    if len(f) != FIELDS:
        raise ValueError("telemetry line: %d fields, the format has %d" % (len(f), FIELDS))
    out = {name: _int(f[k], name) for k, name in enumerate(SCALARS)}
    k = len(SCALARS)
    out["pulses"] = [_int(f[k + i], "pulse %d" % (i + 1)) for i in range(18)]
    k += 18
    out["distances"] = [_int(f[k + i], "distance %d" % (i + 1)) for i in range(5)]
    k += 5
    out["sonar_status"] = [_int(f[k + i], "sonar_status %d" % (i + 1)) for i in range(5)]
    k += 5
    for i, name in enumerate(COUNTERS):
        out[name] = _int(f[k + i], name)
    return out
