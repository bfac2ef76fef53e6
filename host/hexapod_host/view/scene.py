"""A snapshot (source.py) as world-frame geometry for the 3-D view: plain numbers, no UI, so
it can be checked by hand. World frame: the room's x, y (mm), z up from the ground."""

import math

import numpy as np

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
    centres, rots, lengths = segment_poses([[start, end]])
    return centres[0].tolist(), rots[0].tolist(), float(lengths[0])


def segment_poses(segments):
    """segment_pose for many segments at once (n x [start, end], any unit): numpy arrays of the
    centres (n x 3), rotations (n x 3 x 3) and lengths (n). One numpy pass for the 30-odd links,
    brackets and beams a redraw places: a third of the Python loop's time."""
    seg = np.asarray(segments, dtype=float).reshape(-1, 2, 3)
    start, end = seg[:, 0], seg[:, 1]
    d = end - start
    n = np.sqrt((d * d).sum(axis=1))
    centre = (start + end) / 2
    y = np.divide(d, n[:, None], out=np.zeros_like(d), where=n[:, None] > 0.0)
    # x: horizontal and square to the segment (any square axis will do for a round link); for a
    # vertical segment, the world's x.
    h = np.hypot(y[:, 0], y[:, 1])
    level = h > 1e-9
    safe = np.where(level, h, 1.0)
    x = np.zeros_like(d)
    x[:, 0] = np.where(level, y[:, 1] / safe, 1.0)
    x[:, 1] = np.where(level, -y[:, 0] / safe, 0.0)
    z = np.cross(x, y)
    rot = np.stack([x, y, z], axis=2)  # rot[i][k] = [x[k], y[k], z[k]]: the columns are x, y, z
    rot[n == 0.0] = np.eye(3)  # a point: no direction to turn to
    return centre, rot, n
