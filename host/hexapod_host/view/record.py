"""Recordings of the view (`hexapod view ... --record FILE.mcap`): every snapshot the player
publishes, with its time, in an MCAP file (the `mcap` package), JSON messages described by a
JSON Schema. docs/view.md states the layout:

- topic SNAPSHOT_TOPIC, schema SNAPSHOT_SCHEMA (encoding "jsonschema"), message encoding
  "json": one message per snapshot that differs from the one before (a paused source is
  written once), log_time and publish_time = the host's clock (ns since 1970) when published;
- topic DESCRIBE_TOPIC, schema DESCRIBE_SCHEMA: one message, the source's describe(), first.

The file is written under a temporary name beside the asked one and renamed to it by close():
a run stopped by Ctrl-C or an error leaves the finished file or nothing, never half of one.
"""

import json
import os
import time

from mcap.writer import CompressionType, Writer

SNAPSHOT_TOPIC = "/hexapod/snapshot"
DESCRIBE_TOPIC = "/hexapod/describe"
SNAPSHOT_SCHEMA = "hexapod.view.Snapshot"
DESCRIBE_SCHEMA = "hexapod.view.Describe"
PROFILE = "hexapod-view"
PART = ".part"  # the name the file has while it is being written

_NUM = {"type": "number"}
_NUM_OR_NULL = {"type": ["number", "null"]}
_POINT = {"type": "array", "items": _NUM, "minItems": 3, "maxItems": 3}


def _array(items, n):
    return {"type": "array", "items": items, "minItems": n, "maxItems": n}


def _object(props):
    return {"type": "object", "required": list(props), "properties": props}


# The snapshot (source.py's docstring has the units). Every key is required: a replay draws
# them all, and a file that lacks one is refused before the page opens.
SNAPSHOT = {
    "$schema": "https://json-schema.org/draft/2020-12/schema",
    "title": SNAPSHOT_SCHEMA,
    "description": "One frame of hexapod view's source: mm, cdeg (angles), us (pulses), rad (yaw), s",
    **_object(
        {
            "frame": {"type": "integer"},
            "time_s": _NUM,
            "pulses": _array({"type": "integer"}, 18),
            "angles": _array(_NUM, 18),
            "legs": _array(_array(_POINT, 4), 6),
            "stance": _array({"type": "boolean"}, 6),
            "body": _object({"x": _NUM, "y": _NUM, "z": _NUM, "yaw": _NUM}),
            "distances": _array(_NUM_OR_NULL, 5),
            "sonar_status": _array({"type": "string"}, 5),
            "mode": {"type": "string"},
            "follow": _object(
                {
                    "mode": {"type": "string"},
                    "side": {"type": ["string", "null"]},
                    "setpoint_mm": _NUM,
                    "error_mm": _NUM,
                    "output_dps": _NUM,
                    "sensor_state": {"type": "array", "items": {"type": "string"}},
                }
            ),
            "counters": {"type": "object", "additionalProperties": {"type": "integer"}},
            "extra": {"type": "object"},
        }
    ),
}

DESCRIBE = {
    "$schema": "https://json-schema.org/draft/2020-12/schema",
    "title": DESCRIBE_SCHEMA,
    "description": "What does not change while hexapod view runs: sonar mounts, body outline, the room (mm, rad)",
    **_object(
        {
            "source": {"type": "string"},
            "sensors": _array(_POINT, 5),
            "body_half": _array(_NUM, 2),
            "brackets": {"type": "array", "items": _array(_NUM, 4)},
        }
    ),
}

_TYPES = {
    "object": lambda v: isinstance(v, dict),
    "array": lambda v: isinstance(v, list),
    "string": lambda v: isinstance(v, str),
    "boolean": lambda v: isinstance(v, bool),
    "integer": lambda v: isinstance(v, int) and not isinstance(v, bool),
    "number": lambda v: isinstance(v, int | float) and not isinstance(v, bool),
    "null": lambda v: v is None,
}


def problem(schema, value, where="snapshot"):
    """What in value does not fit schema (the subset of JSON Schema the two schemas above use:
    type, required, properties, additionalProperties, items, minItems, maxItems), or None."""
    kinds = schema.get("type")
    if kinds is not None:
        kinds = [kinds] if isinstance(kinds, str) else kinds
        if not any(_TYPES[k](value) for k in kinds):
            return "%s: %s, expected %s" % (where, type(value).__name__, " or ".join(kinds))
    if isinstance(value, dict):
        for key in schema.get("required", ()):
            if key not in value:
                return "%s: no %r" % (where, key)
        for key, sub in schema.get("properties", {}).items():
            if key in value:
                why = problem(sub, value[key], "%s.%s" % (where, key))
                if why:
                    return why
        extra = schema.get("additionalProperties")
        if isinstance(extra, dict):
            for key, v in value.items():
                if key not in schema.get("properties", {}):
                    why = problem(extra, v, "%s.%s" % (where, key))
                    if why:
                        return why
    if isinstance(value, list):
        lo, hi = schema.get("minItems", 0), schema.get("maxItems", len(value))
        if not lo <= len(value) <= hi:
            return "%s: %d items, expected %s" % (where, len(value), lo if lo == hi else "%d..%d" % (lo, hi))
        if "items" in schema:
            for i, v in enumerate(value):
                why = problem(schema["items"], v, "%s[%d]" % (where, i))
                if why:
                    return why
    return None


def _json(value):
    return json.dumps(value, separators=(",", ":"), allow_nan=False).encode()


class Recorder:
    """Writes snapshots into path (an .mcap file) under path + PART until close()."""

    def __init__(self, path, described, clock=time.time_ns):
        self.path, self.clock = path, clock
        self.part = path + PART
        self.written = 0
        self._last = None
        self._file = open(self.part, "wb")  # noqa: SIM115 (closed by close())
        try:
            self._writer = Writer(self._file, compression=CompressionType.ZSTD)
            self._writer.start(profile=PROFILE)
            ids = {}
            for topic, name, schema in (
                (DESCRIBE_TOPIC, DESCRIBE_SCHEMA, DESCRIBE),
                (SNAPSHOT_TOPIC, SNAPSHOT_SCHEMA, SNAPSHOT),
            ):
                sid = self._writer.register_schema(name=name, encoding="jsonschema", data=_json(schema))
                ids[topic] = self._writer.register_channel(topic=topic, message_encoding="json", schema_id=sid)
            self._snapshots = ids[SNAPSHOT_TOPIC]
            now = self.clock()
            self._writer.add_message(ids[DESCRIBE_TOPIC], log_time=now, data=_json(described), publish_time=now)
        except BaseException:
            self._abandon()
            raise

    def write(self, snap):
        """One snapshot, stamped now; the same snapshot again (a paused source) is not written."""
        if self._file is None or snap == self._last:
            return
        self._last = snap
        now = self.clock()
        self._writer.add_message(
            self._snapshots, log_time=now, data=_json(snap), publish_time=now, sequence=self.written
        )
        self.written += 1

    def close(self):
        """Finish the file (its summary and footer) and give it its name. Safe to call twice."""
        if self._file is None:
            return
        try:
            self._writer.finish()
            self._file.close()
            self._file = None
            os.replace(self.part, self.path)
        except BaseException:
            self._abandon()
            raise

    def _abandon(self):
        if self._file is not None:
            self._file.close()
            self._file = None
        if os.path.exists(self.part):
            os.remove(self.part)
