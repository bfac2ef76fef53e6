"""A 2-D room for the wall-following simulator, read from JSON (cm and degrees).

    {"walls": [[x1, y1, x2, y2], ...], "follow": "left" | "right",
     "start": {"wall": 0, "along": 20}, "finish": [x1, y1, x2, y2], "time_limit_s": 180}

Optional: "name" and "note" (text). The robot starts on wall `start.wall`, `along` cm from its
first point, facing from its first point to its second, on the `follow` side (the wall on its
left for "left"). Crossing `finish` ends a trial. `load` raises WorldError naming the file, the
key and what is allowed; nothing runs on a bad file. Shipped worlds live in worlds/ next to
this module and are found by name ("wall", "corridor", ...).
"""

import json
import math
import os

WORLDS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "worlds")
DEFAULT = "wall"
KEYS = ("walls", "follow", "start", "finish", "time_limit_s")
OPTIONAL = ("name", "note")
SIZE_CM = 10000.0  # largest |coordinate|: 100 m
TIME_MAX_S = 3600
WALLS_MAX = 200


class WorldError(ValueError):
    """A world file that cannot be run: the message names the file, the key and what is allowed."""


def shipped():
    """Names of the shipped worlds, sorted."""
    return sorted(f[:-5] for f in os.listdir(WORLDS) if f.endswith(".json"))


def path_of(name_or_path):
    """A shipped world's file for its name, else the path as given."""
    if os.sep not in name_or_path and not name_or_path.endswith(".json"):
        return os.path.join(WORLDS, name_or_path + ".json")
    return name_or_path


class World:
    """A checked world: walls and finish in mm, the rest as given."""

    def __init__(self, data, source):
        self.source = source
        self.name = data.get("name") or os.path.splitext(os.path.basename(source))[0]
        self.walls = [tuple(10.0 * v for v in w) for w in data["walls"]]
        self.finish = tuple(10.0 * v for v in data["finish"])
        self.follow = data["follow"]
        self.start_wall = data["start"]["wall"]
        self.start_along = 10.0 * data["start"]["along"]
        self.time_limit_s = data["time_limit_s"]

    def start_frame(self, side=None):
        """(point, unit direction, unit normal toward the robot) of the start, mm; side
        overrides the world's follow side."""
        x1, y1, x2, y2 = self.walls[self.start_wall]
        n = math.hypot(x2 - x1, y2 - y1)
        ux, uy = (x2 - x1) / n, (y2 - y1) / n
        px, py = x1 + ux * self.start_along, y1 + uy * self.start_along
        # The wall on the robot's left: the robot is on the wall's right, normal (uy, -ux).
        nx, ny = (uy, -ux) if (side or self.follow) == "left" else (-uy, ux)
        return (px, py), (ux, uy), (nx, ny)


def _is_number(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _segment(where, v):
    if not isinstance(v, list) or len(v) != 4:
        raise WorldError("%s: need [x1, y1, x2, y2] (cm), got %s" % (where, json.dumps(v)))
    for k, c in enumerate(v):
        if not _is_number(c):
            raise WorldError("%s[%d]: %s is not a number (cm)" % (where, k, json.dumps(c)))
        if abs(c) > SIZE_CM:
            raise WorldError("%s[%d]: %g is outside -%g..%g cm" % (where, k, c, SIZE_CM, SIZE_CM))
    if v[0] == v[2] and v[1] == v[3]:
        raise WorldError("%s: zero length (both ends at %g, %g cm)" % (where, v[0], v[1]))


def check(data, source="world"):
    """A World from parsed JSON, or WorldError naming the first thing wrong."""
    pre = "world %s: " % source
    try:
        if not isinstance(data, dict):
            raise WorldError("need a JSON object with keys %s" % ", ".join(KEYS))
        for k in KEYS:
            if k not in data:
                raise WorldError("%s is missing (need %s)" % (k, ", ".join(KEYS)))
        for k in data:
            if k not in KEYS and k not in OPTIONAL:
                raise WorldError("%s: unknown key (allowed %s)" % (k, ", ".join(KEYS + OPTIONAL)))
        for k in OPTIONAL:
            if k in data and not isinstance(data[k], str):
                raise WorldError("%s: need text, got %s" % (k, json.dumps(data[k])))
        walls = data["walls"]
        if not isinstance(walls, list) or not 1 <= len(walls) <= WALLS_MAX:
            raise WorldError("walls: need a list of 1..%d [x1, y1, x2, y2] (cm)" % WALLS_MAX)
        for i, w in enumerate(walls):
            _segment("walls[%d]" % i, w)
        if data["follow"] not in ("left", "right"):
            raise WorldError('follow: %s, allowed "left" or "right"' % json.dumps(data["follow"]))
        start = data["start"]
        if not isinstance(start, dict) or set(start) != {"wall", "along"}:
            raise WorldError('start: need {"wall": index, "along": cm}, got %s' % json.dumps(start))
        wi = start["wall"]
        if not isinstance(wi, int) or isinstance(wi, bool) or not 0 <= wi < len(walls):
            raise WorldError("start.wall: %s, allowed 0..%d (an index into walls)" % (json.dumps(wi), len(walls) - 1))
        x1, y1, x2, y2 = walls[wi]
        length = math.hypot(x2 - x1, y2 - y1)
        along = start["along"]
        if not _is_number(along) or not 0 <= along <= length:
            raise WorldError("start.along: %s, allowed 0..%g cm (wall %d's length)" % (json.dumps(along), length, wi))
        _segment("finish", data["finish"])
        t = data["time_limit_s"]
        if not _is_number(t) or not 0 < t <= TIME_MAX_S:
            raise WorldError("time_limit_s: %s, allowed a number in 0..%d (s), above 0" % (json.dumps(t), TIME_MAX_S))
    except WorldError as err:
        raise WorldError(pre + str(err)) from None
    return World(data, source)


def load(name_or_path):
    """Read and check a world file (a shipped world's name or a path)."""
    path = path_of(name_or_path)
    try:
        with open(path) as f:
            text = f.read()
    except OSError as err:
        raise WorldError(
            "world %s: cannot read (%s); shipped worlds: %s" % (name_or_path, err.strerror, ", ".join(shipped()))
        ) from None
    try:
        data = json.loads(text)
    except ValueError as err:
        raise WorldError("world %s: not JSON (%s)" % (name_or_path, err)) from None
    return check(data, name_or_path)
