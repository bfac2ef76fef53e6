"""A snapshot (source.py) as world-frame geometry for the 3-D view: plain numbers, no UI, so
it can be checked by hand. World frame: the room's x, y (mm), z up from the ground."""

import math

from hexapod_host.view.support import support

NO_ECHO_MM = 150.0  # a beam with no reading is drawn this long, grey
# hexapod.sensors.STATUS_NAMES drawn red: the names every source's snapshot carries (these were
# drivers.hcsr04's prose names, which no snapshot holds: no beam was ever drawn red).
FAULTS = ("no_echo", "stuck", "too_close")


def to_world(body, p):
    """A body-frame point (x, y, z mm; z from the coxa plane) in the world: the body's yaw and
    place, lifted by its height above the ground."""
    c, s = math.cos(body["yaw"]), math.sin(body["yaw"])
    x, y, z = p
    return [body["x"] + c * x - s * y, body["y"] + s * x + c * y, body["z"] + z]


def beam_state(status):
    """How a sonar's beam is drawn: "ok" (a reading), "fault" (red) or "none" (nothing heard in range)."""
    if status == "ok":
        return "ok"
    return "fault" if status in FAULTS else "none"


def geometry(described, snap):
    """World-frame geometry of one snapshot: the body (centre, yaw, half sizes), the sonar
    brackets and 18 links as [start, end] (coxa, femur, tibia of legs 1-6), 6 feet with their
    stance flags, 5 beams (start, end, state, reading), the support polygon's corners and the
    centre of mass, in the air and on the ground, with its margin (support.support). mm and rad."""
    body = snap["body"]
    links, feet = [], []
    for leg in snap["legs"]:
        pts = [to_world(body, p) for p in leg]
        links += [[pts[k], pts[k + 1]] for k in range(3)]
        feet.append(pts[3])
    beams = []
    for (x, y, h), d, status in zip(described["sensors"], snap["distances"], snap["sonar_status"], strict=True):
        state = beam_state(status)
        start = to_world(body, (x, y, 0.0))
        r = d if state == "ok" and d is not None else NO_ECHO_MM
        a = body["yaw"] + h
        end = [start[0] + r * math.cos(a), start[1] + r * math.sin(a), start[2]]
        beams.append({"start": start, "end": end, "state": state, "mm": d})
    brackets = [
        [to_world(body, (x1, y1, 0.0)), to_world(body, (x2, y2, 0.0))] for x1, y1, x2, y2 in described["brackets"]
    ]
    held = support(snap["legs"], snap["stance"])
    return {
        "support": {
            **held,
            "polygon": [to_world(body, (x, y, 0.0))[:2] + [0.0] for x, y in held["polygon"]],
            "com": to_world(body, held["com"]),
            "com_ground": to_world(body, held["com"][:2] + [0.0])[:2] + [0.0],
        },
        "brackets": brackets,
        "body": {"centre": [body["x"], body["y"], body["z"]], "yaw": body["yaw"], "half": described["body_half"]},
        "links": links,
        "feet": feet,
        "stance": list(snap["stance"]),
        "beams": beams,
    }


def segment_pose(start, end):
    """Where a unit cylinder along y goes to stand for the segment start -> end: its centre,
    a rotation matrix taking y onto the segment, and the segment's length (the y scale)."""
    d = [e - s for s, e in zip(start, end, strict=True)]
    n = math.sqrt(sum(v * v for v in d))
    centre = [(s + e) / 2 for s, e in zip(start, end, strict=True)]
    if n == 0.0:
        return centre, [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], 0.0
    y = [v / n for v in d]
    # x: horizontal and square to the segment (any square axis will do for a round link); for a
    # vertical segment, the world's x.
    h = math.hypot(y[0], y[1])
    x = [y[1] / h, -y[0] / h, 0.0] if h > 1e-9 else [1.0, 0.0, 0.0]
    z = [x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]]
    return centre, [[x[k], y[k], z[k]] for k in range(3)], n
