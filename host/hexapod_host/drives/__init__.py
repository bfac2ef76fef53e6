"""Driver command streams (issue 22 point 4): one JSON object a line, checked in full before anything runs.

A line is a walk command from its time on, replacing the one before:

    {"t_ms": 0, "vx": 40, "vy": 0, "yaw": 0}
    {"t_ms": 1500, "vx": 0, "vy": 30, "yaw": 0, "gait": "ripple"}
    {"t_ms": 4000, "stop": true}

- t_ms: whole ms from the stream's start (the robot standing), 0..T_MS_MAX, strictly increasing;
  a line takes effect at the first 20 ms tick at or after its time.
- vx, vy: mm/s, yaw: deg/s (positive = left), each optional (absent: 0), within the console's walk
  limits (hexapod.limits: +-300.0 mm/s to 0.1 mm/s, +-90.00 deg/s to 0.01 deg/s).
- gait: optional, one of hexapod.gait.NAMES, asked as the console asks it (wait=False); absent: keep.
- stop: optional true/false; true is the console's `stop` and carries no speed.

The shipped streams live here as package data (`NAMES`); `resolve(name_or_path)` finds either.
"""

import json
import math
import os

from hexapod.gait import NAMES as NAMES_OF_GAITS
from hexapod.limits import SPEED_MAX, YAW_RATE_MAX

HERE = os.path.dirname(os.path.abspath(__file__))
NAMES = ("joystick", "reversals", "gait_tour")  # shipped streams: HERE/NAME.jsonl
T_MS_MAX = 600000  # ten minutes: a stream longer than this is a mistake, not a drive
KEYS = ("t_ms", "vx", "vy", "yaw", "gait", "stop")
# key: (scale to the core's unit, the core's limit, the unit shown, decimals the console takes)
SPEEDS = {
    "vx": (10, SPEED_MAX, "mm/s", 1),
    "vy": (10, SPEED_MAX, "mm/s", 1),
    "yaw": (100, YAW_RATE_MAX, "deg/s", 2),
}


class StreamError(ValueError):
    """A bad stream: the message names the file, the line, the field and what is allowed."""


def resolve(spec):
    """A shipped stream's name (NAMES) -> its path; anything else is taken as a path."""
    if spec in NAMES and not os.path.exists(spec):
        return os.path.join(HERE, spec + ".jsonl")
    return spec


def load(spec):
    """Read and check a stream file (or a shipped stream's name): parse()'s commands; StreamError."""
    path = resolve(spec)
    try:
        with open(path, "rb") as f:
            raw = f.read(4 * 1024 * 1024 + 1)
    except OSError as err:
        raise StreamError("%s: cannot read: %s" % (spec, err.strerror or err)) from None
    if len(raw) > 4 * 1024 * 1024:
        raise StreamError("%s: over 4 MB: not a drive" % spec)
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as err:
        raise StreamError("%s: not UTF-8 text (byte %d)" % (spec, err.start)) from None
    return parse(text, spec)


def parse(text, name="stream"):
    """The stream's lines -> [(line, t_ms, vx, vy, yaw, gait, stop)]: vx, vy in 0.1 mm/s, yaw in cdeg/s,
    gait a gait number or -1 (keep), stop 0 or 1. StreamError at the first bad line."""
    lines = text.split("\n")
    if lines and lines[-1] == "":
        lines.pop()  # the last line's newline
    if not lines:
        raise StreamError("%s: empty: need at least one line like %s" % (name, '{"t_ms": 0, "vx": 40}'))
    out = []
    last = -1
    for n, line in enumerate(lines, 1):
        cmd = _line(name, n, line.rstrip("\r"), last)
        last = cmd[1]
        out.append(cmd)
    return out


def _line(name, n, line, last):
    where = "%s line %d" % (name, n)
    if not line.strip():
        raise StreamError("%s: empty line: every line is one JSON object" % where)
    try:
        obj = json.loads(line, parse_constant=_no_constant, object_pairs_hook=_no_twice)
    except ValueError as err:
        raise StreamError("%s: not JSON (%s)" % (where, err)) from None
    if not isinstance(obj, dict):
        raise StreamError("%s: a JSON %s, need an object like %s" % (where, type(obj).__name__, '{"t_ms": 0}'))
    for key in obj:
        if key not in KEYS:
            raise StreamError("%s: unknown key %r, allowed %s" % (where, key[:30], ", ".join(KEYS)))
    if "t_ms" not in obj:
        raise StreamError("%s: t_ms missing: every line needs its time (whole ms)" % where)
    t = obj["t_ms"]
    if not _whole(t) or t < 0 or t > T_MS_MAX:
        raise StreamError("%s: t_ms: %s, allowed a whole number of ms 0..%d" % (where, _show(t), T_MS_MAX))
    if t <= last:
        raise StreamError("%s: t_ms: %d is not after the line before's %d: times must increase" % (where, t, last))
    values = []
    for key in ("vx", "vy", "yaw"):
        values.append(_speed(where, key, obj.get(key, 0)))
    gait = -1
    if "gait" in obj:
        g = obj["gait"]
        if g not in NAMES_OF_GAITS:
            raise StreamError("%s: gait: %s, allowed %s" % (where, _show(g), ", ".join(NAMES_OF_GAITS)))
        gait = NAMES_OF_GAITS.index(g)
    stop = obj.get("stop", False)
    if not isinstance(stop, bool):
        raise StreamError("%s: stop: %s, allowed true or false" % (where, _show(stop)))
    if stop and any(values):
        key = ("vx", "vy", "yaw")[[bool(v) for v in values].index(True)]
        raise StreamError("%s: stop: true with %s %s: a stop carries no speed" % (where, key, _show(obj[key])))
    return (n, t, values[0], values[1], values[2], gait, int(stop))


def _speed(where, key, v):
    scale, limit, unit, decimals = SPEEDS[key]
    top = limit / scale
    allowed = "allowed %s..%s %s in steps of %s" % (-top, top, unit, 10.0**-decimals if decimals else 1)
    if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
        raise StreamError("%s: %s: %s, %s" % (where, key, _show(v), allowed))
    fine = v * scale
    whole = round(fine)
    if abs(fine - whole) > 1e-6 * max(1.0, abs(fine)):
        raise StreamError("%s: %s: %s has more decimals than the console takes, %s" % (where, key, v, allowed))
    if whole < -limit or whole > limit:
        raise StreamError("%s: %s: %s is outside the console's walk limits, %s" % (where, key, v, allowed))
    return int(whole)


def _whole(v):
    return isinstance(v, int) and not isinstance(v, bool)


def _show(v):
    text = json.dumps(v)
    return text if len(text) <= 30 else text[:27] + "..."


def _no_twice(pairs):
    """A JSON object whose keys are all different (json keeps the last of a repeated key silently)."""
    seen = {}
    for key, value in pairs:
        if key in seen:
            raise ValueError("key %r twice" % key[:30])
        seen[key] = value
    return seen


def _no_constant(name):
    raise ValueError("%s is not a number JSON allows" % name)
