"""The board's telemetry lines (`stream on [HZ]`, docs/console.md "Telemetry") read back.

    parse("~T 120 3 0 0 0 0 0 0 0 1500 ...")  -> {"frame": 120, "mode": 3, ..., "pulses": [18 us], ...}

A line is '~T' and 46 ASCII decimal integers separated by one space, '-' where there is no value
(a sonar's distance while its status is not ok, the battery when none is configured). parse()
gives a dict with the format's field names (pulses, distances and sonar_status as lists; '-' as
None) and raises ValueError naming the field for a line that does not follow the format. A line
of the first 44 alone (firmware from before the frame time, 2026-11-27) is read too, its frame
times None.
"""

from hexapod import follow, gait, sensors, tick

PREFIX = "~"  # no reply, notice or REPL line starts with it: a client skips these lines
TAG = "~T"

# (name, how many values, lo, hi, '-' allowed); in the line's order (docs/console.md's table).
# Bounds are what the firmware can send; None: unbounded on that side.
FIELDS = (
    ("frame", 1, 0, None, False),
    ("mode", 1, 0, len(tick.MODE_NAMES) - 1, False),
    ("gait", 1, 0, len(gait.NAMES) - 1, False),
    ("phase", 1, 0, None, False),
    ("follow_mode", 1, 0, len(follow.MODE_NAMES) - 1, False),
    ("follow_side", 1, 0, 2, False),
    ("vx", 1, None, None, False),  # 0.1 mm/s
    ("vy", 1, None, None, False),  # 0.1 mm/s
    ("yaw", 1, None, None, False),  # 0.01 deg/s
    ("pulses", 18, 0, 2500, False),  # us, legs 1-6 x coxa femur tibia; 0: none sent
    ("distances", 5, 0, None, True),  # 0.1 mm, hexapod.sensors order
    ("sonar_status", 5, 0, len(sensors.STATUS_NAMES) - 1, False),
    ("wall_error", 1, None, None, False),  # 0.1 mm
    ("wall_out", 1, None, None, False),  # 0.01 deg/s
    ("battery_mv", 1, 0, None, True),
    ("held", 1, 0, None, False),
    ("overruns", 1, 0, None, False),
    ("bus_failed", 1, 0, None, False),
    ("sonar_faults", 1, 0, None, False),
    ("frame_us", 1, 0, None, False),  # the last whole frame's time (runner.wait), us
    ("frame_us_max", 1, 0, None, False),  # the most since the line before, us
)
COUNT = sum(f[1] for f in FIELDS)  # 46
OLD_COUNT = COUNT - 2  # a line without the frame times (older firmware)


def is_telemetry(line):
    """True for a line the board streams (text or bytes): a client waiting for replies skips it."""
    return line[:1] in (PREFIX, PREFIX.encode())


def _names():
    """The name of each of the COUNT values in order ('pulses[3]' for a list's fourth)."""
    out = []
    for name, n, *_ in FIELDS:
        out.extend([name] if n == 1 else ["%s[%d]" % (name, k) for k in range(n)])
    return out


NAMES = _names()


def parse(line):
    """One telemetry line (with or without its line end) -> dict of the format's fields; ValueError
    naming the field (and its position, 1-based after '~T') when the line is malformed."""
    if isinstance(line, bytes):
        try:
            line = line.decode("ascii")
        except UnicodeDecodeError:
            raise ValueError("telemetry line: not ASCII") from None
    line = line.rstrip("\r\n")
    if not line.startswith(TAG + " "):
        raise ValueError("telemetry line: prefix %r, expected %r and a space" % (line[:3], TAG))
    words = line[len(TAG) + 1 :].split(" ")
    values = [_value(k, w) for k, w in enumerate(words[:COUNT])]  # the first bad word names its field
    if len(words) < COUNT and len(words) != OLD_COUNT:
        k = len(words)
        raise ValueError(
            "telemetry field %d (%s): missing (%d of %d fields, or %d from older firmware)"
            % (k + 1, NAMES[k], k, COUNT, OLD_COUNT)
        )
    if len(words) > COUNT:
        raise ValueError("telemetry: %d fields, expected %d (extra after frame_us_max)" % (len(words), COUNT))
    out = {"frame_us": None, "frame_us_max": None}  # an older firmware's line has none
    at = 0
    for name, n, lo, hi, dash in FIELDS:
        if at >= len(values):
            break
        part = values[at : at + n]
        for k, v in enumerate(part):
            if v is None:
                if not dash:
                    raise ValueError(
                        "telemetry field %d (%s): '-', allowed only an integer" % (at + k + 1, NAMES[at + k])
                    )
            elif (lo is not None and v < lo) or (hi is not None and v > hi):
                raise ValueError(
                    "telemetry field %d (%s): %d is outside %s..%s"
                    % (at + k + 1, NAMES[at + k], v, lo, "" if hi is None else hi)
                )
        out[name] = part[0] if n == 1 else part
        at += n
    for k in range(5):  # a distance exactly when its sonar's reading is ok
        if (out["distances"][k] is None) != (out["sonar_status"][k] != sensors.OK):
            raise ValueError(
                "telemetry field %d (distances[%d]): %s with sonar_status %d (a distance only when it is %d, ok)"
                % (
                    NAMES.index("distances[%d]" % k) + 1,
                    k,
                    words[NAMES.index("distances[%d]" % k)],
                    out["sonar_status"][k],
                    sensors.OK,
                )
            )
    return out


def _value(k, word):
    """Field k's word as an int, '-' as None; ValueError naming the field."""
    if word == "-":
        return None
    body = word[1:] if word[:1] == "-" else word
    if not body.isdigit() or not body.isascii() or (len(body) > 1 and body[0] == "0"):
        raise ValueError("telemetry field %d (%s): %r is not a decimal integer" % (k + 1, NAMES[k], word[:20]))
    return int(word)
