"""A recording as a view source (`hexapod view --replay FILE.mcap`): the snapshots of a
record.py file played on their own clock, paused, stepped, scrubbed and sped up by the page.

The whole file is read and checked when it is opened (every message against the schema, the
file's CRCs, its end): a bad file is a ReplayError naming what is wrong before the page starts.
With a world (`--world W`), a recording without a room is replayed in that world's room: its
walls drawn, the body moved by its recorded feet (inroom.py).
"""

import bisect
import json
import struct

from mcap.exceptions import McapError
from mcap.reader import NonSeekingReader

from hexapod_host.view import inroom, record
from hexapod_host.view.source import Source

WHAT = "an MCAP file written by hexapod view --record"


class ReplayError(Exception):
    """A file that cannot be replayed, with what is wrong in it."""


def _decoded(path, i, data, schema):
    try:
        value = json.loads(data)
    except (ValueError, UnicodeDecodeError) as err:
        raise ReplayError("%s: message %d is not JSON (%s)" % (path, i, err)) from None
    why = record.problem(schema, value)
    if why:
        raise ReplayError("%s: message %d does not fit %s: %s" % (path, i, schema["title"], why))
    return value


def load(path):
    """(described, [log_time ns], [snapshot JSON bytes]) of a recording, checked; else ReplayError."""
    try:
        f = open(path, "rb")  # noqa: SIM115
    except OSError as err:
        raise ReplayError("%s: cannot read: %s" % (path, err.strerror or err)) from None
    described, times, data = None, [], []
    with f:
        if not f.read(1):
            raise ReplayError("%s: empty file; expected %s" % (path, WHAT))
        f.seek(0)
        try:
            for schema, channel, message in NonSeekingReader(f, validate_crcs=True).iter_messages(log_time_order=False):
                name = schema.name if schema else None
                if channel.topic == record.SNAPSHOT_TOPIC and name == record.SNAPSHOT_SCHEMA:
                    times.append(message.log_time)
                    data.append(message.data)
                elif channel.topic == record.DESCRIBE_TOPIC and name == record.DESCRIBE_SCHEMA and described is None:
                    described = _decoded(path, 0, message.data, record.DESCRIBE)
                elif channel.topic in (record.SNAPSHOT_TOPIC, record.DESCRIBE_TOPIC):
                    raise ReplayError(
                        "%s: topic %s has schema %r, expected %r"
                        % (
                            path,
                            channel.topic,
                            name,
                            record.SNAPSHOT_SCHEMA
                            if channel.topic == record.SNAPSHOT_TOPIC
                            else record.DESCRIBE_SCHEMA,
                        )
                    )
        except ReplayError:
            raise
        except McapError as err:
            raise ReplayError(
                "%s: not a whole MCAP file (%s: %s); expected %s" % (path, type(err).__name__, err, WHAT)
            ) from None
        except (ValueError, EOFError, KeyError, IndexError, UnicodeDecodeError, OSError, struct.error) as err:
            # The mcap package's CRC mismatch is a ValueError; a cut-off record can surface as any of these.
            raise ReplayError("%s: damaged MCAP file (%s: %s)" % (path, type(err).__name__, err)) from None
    if described is None:
        raise ReplayError(
            "%s: no %s message on %s; expected %s" % (path, record.DESCRIBE_SCHEMA, record.DESCRIBE_TOPIC, WHAT)
        )
    if not times:
        raise ReplayError("%s: no snapshots on %s (an empty recording)" % (path, record.SNAPSHOT_TOPIC))
    order = sorted(range(len(times)), key=times.__getitem__)  # log time order, the writer's order when it is sane
    times, data = [times[i] for i in order], [data[i] for i in order]
    for i, d in enumerate(data):
        _decoded(path, i + 1, d, record.SNAPSHOT)
    return described, times, data


class ReplaySource(Source):
    """A recording played on its own clock (the time each snapshot was published, so a
    recording made at 2x plays back at 2x when the page's speed is 1x): step() moves the clock
    one frame_s on and shows the last snapshot published by then; seek() jumps."""

    name = "replay"
    steppable = True

    def __init__(self, path, world=None):
        self.path = path
        described, self.times, self.data = load(path)
        self.recorded = described
        self.world = world
        self.poses = None  # with a world: the body's (x, y, yaw) in it per snapshot
        if world is not None:
            try:
                inroom.check(described, world)
            except inroom.NotPlaceable as err:
                raise ReplayError("%s: %s" % (path, err)) from None
            self.poses = inroom.poses([json.loads(d) for d in self.data], world, described.get("board", "pico"))
        self.duration_s = (self.times[-1] - self.times[0]) / 1e9
        self.clock_s = 0.0
        self.index = 0
        self._cached = (None, None)

    def describe(self):
        d = {**self.recorded, "source": "replay of %s" % self.recorded["source"]}
        w = self.world
        if w is not None:
            d.update(world=w.name, walls=[list(x) for x in w.walls], finish=list(w.finish))
        return d

    def seek(self, seconds):
        """Show the recording at `seconds` from its start (clamped to the recording)."""
        self.clock_s = min(max(0.0, float(seconds)), self.duration_s)
        self.index = max(0, bisect.bisect_right(self.times, self.times[0] + round(self.clock_s * 1e9)) - 1)

    def step(self):
        self.seek(self.clock_s + self.frame_s)

    def done(self):
        return self.clock_s >= self.duration_s

    def restart(self):
        self.seek(0.0)

    def __len__(self):
        return len(self.data)

    def snapshot(self):
        i, snap = self._cached
        if i != self.index:
            snap = json.loads(self.data[self.index])
            if self.poses is not None:
                x, y, yaw = self.poses[self.index]
                snap["body"].update(x=x, y=y, yaw=yaw)
            self._cached = (self.index, snap)
        return snap
