"""The console's telemetry on the stub board (tests/test_console_stream.py): `stream on [HZ] | off`
through a sink that keeps each line, the rate, replies and drops, the heap of a streaming frame,
and the select.poll writer. The viper twin of the integer writer: scenarios.stream_digits."""

import _stub_clock as clock
from scenarios.console_rig import Board

from drivers import stream


class Sink:
    """The telemetry's writer in tests: keeps each line; refusing every `refuse_every`-th line
    asked (0: none) as an output with no room would (the console drops it and counts it)."""

    def __init__(self, refuse_every=0):
        self.lines = []
        self.refuse_every = refuse_every
        self.asked = 0

    def write(self, buf, n):
        self.asked += 1
        if self.refuse_every and self.asked % self.refuse_every == 0:
            return 0
        self.lines.append(bytes(buf[:n]).decode())
        return n


def streaming(refuse_every=0):
    """A fresh Board whose console streams to a Sink: (board, sink)."""
    b = Board()
    sink = Sink(refuse_every)
    b.con.telemetry = stream.Stream(sink)
    return b, sink


def fresh(said):
    """`stream on 25` on a fresh board, said (the reply comes in say's frame) or run directly and
    2 frames: [the reply, the lines]."""
    b, sink = streaming()
    if said:
        reply = b.say("stream on 25")
    else:
        reply = b.con.do("stream on 25")
        b.frames(2)
    return [reply, sink.lines]


def standing():
    """`stand`, 150 frames, `stream on 25`, 2 frames: [the lines, `stream`'s reply]."""
    b, sink = streaming()
    b.say("stand")
    b.frames(150)
    b.con.do("stream on 25")
    b.frames(2)
    return [sink.lines, b.con.do("stream")]


def frame_times(busy_us):
    """Stand, 150 frames, `stream on 25`, then one frame per busy time, kept busy that long on the
    virtual clock between its step and its wait (where the console's work goes): each line's last
    two fields (frame_us, frame_us_max)."""
    b, sink = streaming()
    b.say("stand")
    b.frames(150)
    b.con.do("stream on 25")
    r = b.r
    for busy in busy_us:
        r.step()
        clock.advance_us(busy)
        b.con.poll()
        r.wait()
    return [line.split()[-2:] for line in sink.lines]


def walking_then_following():
    """Stand, `walk 50 -20 10` streaming 40 frames; stop, `wall left 40`, 40 frames: [the walk's
    lines, [the last line, `status`]]."""
    b, sink = streaming()
    b.say("stand")
    b.frames(150)
    b.say("walk 50 -20 10")
    b.con.do("stream on 25")
    b.frames(40)
    walk = list(sink.lines)
    del sink.lines[:]
    b.say("stop")
    b.frames(120)
    b.say("wall left 40")
    b.frames(40)
    return [walk, [sink.lines[-1], b.con.do("status")]]


def rates(hzs):
    """For each HZ, `stream on HZ` and 300 frames: {HZ: the lines' frame numbers}, and "off": the
    lines in 100 frames after `stream off`."""
    b, sink = streaming()
    out = {}
    hz = None
    for hz in hzs:
        b.con.do("stream on %d" % hz)
        del sink.lines[:]
        b.frames(300)
        out[hz] = [int(line.split()[1]) for line in sink.lines]
    b.con.do("stream off")
    b.frames(100)
    out["off"] = len(sink.lines) - len(out[hz])  # after the last rate
    return out


def replies(lines, refuse_every):
    """Each line's reply with the output refusing every refuse_every-th line; after
    `#7 stream on 25`, 59 more frames (60 with say's)."""
    b, sink = streaming(refuse_every)
    out = []
    for line in lines:
        out.append(b.say(line))
        if line == "#7 stream on 25":
            b.frames(59)
    return out


def no_output(lines, write_stdout=False):
    """A console with no telemetry writer (and, write_stdout, sys.stdout.write as its raw
    output): [(each line's reply, still no telemetry)]."""
    import sys

    b = Board()
    b.con.telemetry = None
    if write_stdout:
        b.con.write = sys.stdout.write
    return [(b.con.do(line), b.con.telemetry is None) for line in lines]


def refused_rate(line):
    """line's reply on a fresh streaming board, and (telemetry hz, every) after it."""
    b, _ = streaming()
    return [b.con.do(line), (b.con.telemetry.hz, b.con.telemetry.every)]


class Null:
    """Takes every line, keeps none (the sink keeps them: that allocates)."""

    n = 0

    def write(self, buf, n):
        self.n += 1
        return n


def frame_heap():
    """Standing, streaming at 25 Hz through Null, then through the board's own writer (select.poll
    on the VM's stdout): prints `stream on 25`'s replies, the lines, then (heap bytes of 50 frames
    through each, lines Null took, the writer's class, the viper writer present)."""
    import sys

    from scenarios.heap import heap_bytes

    b = Board()
    null = Null()
    b.con.telemetry = stream.Stream(null)
    b.say("stand")
    b.frames(150)
    print(repr(b.con.do("stream on 25")))
    a = heap_bytes(b.frames, 50)
    b.con.telemetry = None
    b.con.write = sys.stdout.write
    print(repr(b.con.do("stream on 25")))
    c = heap_bytes(b.frames, 50)
    print(repr((a, c, null.n, type(b.con.telemetry.out).__name__, stream._digits_fast is not None)))


def poll_port():
    """The select.poll writer on a port with no room for 20 frames, then with room for 20:
    [[lines written, `stream`'s reply], lines written, `stream`'s reply, the first line's start]."""
    import io

    class Port(io.IOBase):
        # a port for select.poll in the VM (io.IOBase with ioctl): POLLOUT only while it has room
        def __init__(self):
            self.room = False
            self.got = []

        def ioctl(self, req, arg):
            if req == 3:  # MP_STREAM_POLL: POLLOUT (4) while there is room
                return arg & 4 if self.room else 0
            return -1  # no file descriptor: poll asks this method

        def write(self, buf, n):
            self.got.append(bytes(buf[:n]))
            return n

    b = Board()
    port = Port()
    b.con.telemetry = stream.Stream(stream.PollWriter(port))
    b.con.do("stream on 25")
    b.frames(20)  # 10 lines due, no room: every one dropped, nothing written
    a = (len(port.got), b.con.do("stream"))
    port.room = True
    b.frames(20)
    return [a, len(port.got), b.con.do("stream"), port.got[0][:3]]
