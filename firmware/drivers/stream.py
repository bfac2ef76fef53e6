"""Telemetry lines for the console's `stream on [HZ] | off` (docs/console.md, "Telemetry"):
every ceil(50/HZ)-th frame, after the frame's work, one line '~T' and 46 integers about the
loop, made in a buffer made once by an integer writer of its own (no str formatting: nothing
allocated a frame), written only when the output can take it now, else dropped and counted.

The console imports this module at the first `stream` (as it does selftest): a board that never
streams keeps its heap and its names.
"""

import sys
from array import array

from micropython import const

from hexapod import follow, sensors, tick

_digits_fast = None
if sys.implementation.name == "micropython":
    try:
        from drivers._stream_viper import digits as _digits_fast
    except Exception:  # no viper emitter on this build
        _digits_fast = None

_FIELDS = const(46)
_NONE = const(-0x3FFFFFFF)  # a field with no value, written '-' (no reading is ever this; _stream_viper copies it)
_SIZE = const(555)  # '~T', 46 fields of a space and at most 11 characters (-1073741823), '\n'
FRAME_HZ = 50
HZ_MAX = 25
HZ_DEFAULT = 10


class Stream:
    """The telemetry of one console; out.write(buf, n) sends buf's first n bytes if the output
    takes them now and returns how many it took (0: none, the line is dropped)."""

    def __init__(self, out):
        self.out = out
        self.hz = 0  # lines a second asked for; 0: off
        self.every = 0  # frames from one line to the next: ceil(FRAME_HZ / hz); 0: off
        self.due = 0  # frames until the next line
        self.sent = 0
        self.dropped = 0
        self.buf = bytearray(_SIZE)
        self.buf[0] = 126  # '~'
        self.buf[1] = 84  # 'T'
        self.vals = array("i", bytes(4 * _FIELDS))

    def frame(self, runner):
        """Once a frame after its work (Console.poll): the line, when this frame is due one (the
        every-th frame after `stream on`, and every every-th after that)."""
        if not self.every:
            return
        self.due -= 1
        if self.due > 0:
            return
        self.due = self.every
        n = self.line(runner)
        if self.out.write(self.buf, n) == n:
            self.sent += 1
        else:
            self.dropped += 1

    def line(self, runner):
        """The loop's state now as the line in self.buf (docs/console.md's table, in its
        order); returns its length in bytes, '\\n' included."""
        v = self.vals
        r = runner.robot
        f = runner.follower
        v[0] = runner.frames
        v[1] = r.mode
        v[2] = r.gait
        v[3] = r.walker.phase if r.mode == tick.WALKING else 0
        on = f.mode != follow.OFF
        v[4] = f.mode
        v[5] = (1 if f.side == "left" else 2) if on else 0
        v[6] = r.asked_vx  # 0.1 mm/s
        v[7] = r.asked_vy
        v[8] = r.asked_yaw  # 0.01 deg/s
        p = r.pulses
        for k in range(18):
            v[9 + k] = p[k]
        d = runner.distances
        s = runner.sonar_status
        for k in range(5):
            v[27 + k] = d[k] if s[k] == sensors.OK else _NONE
            v[32 + k] = s[k]
        v[37] = f.error if on else 0  # 0.1 mm
        v[38] = f.output if on else 0  # 0.01 deg/s
        b = runner.battery
        v[39] = _NONE if b is None else b.level_mv
        v[40] = runner.held
        v[41] = r.overruns
        v[42] = runner.bank.failed_frames
        v[43] = runner.sonar_faults
        v[44] = runner.frame_us  # the last whole frame's time, us (runner.wait)
        v[45] = runner.frame_us_max  # the most since the last line
        runner.frame_us_max = 0
        if _digits_fast is not None:
            return _digits_fast(self.buf, 2, v, _FIELDS)
        return digits(self.buf, 2, v, _FIELDS)


def digits(buf, at, vals, count):
    """Each of vals[0:count] as ' ' and ASCII decimal (or ' -' for _NONE) into buf from at, then
    '\\n'; returns the end. Small-int arithmetic into a bytearray only: nothing allocated."""
    for k in range(count):
        x = vals[k]
        buf[at] = 32
        at += 1
        if x < 0:
            buf[at] = 45  # '-': a sign, or the whole field when there is no value
            at += 1
            if x == _NONE:
                continue
            x = -x
        end = at + 1
        t = x // 10
        while t:
            end += 1
            t //= 10
        at = end
        while True:  # from the last digit back
            end -= 1
            buf[end] = 48 + x % 10
            x //= 10
            if not x:
                break
    buf[at] = 10
    return at + 1


class PollWriter:
    """MicroPython: out to a stream (sys.stdout) only when select.poll says it can take bytes
    now (POLLOUT); a port's USB CDC says so while its transmit FIFO has room, a pty or pipe
    while its buffer has."""

    def __init__(self, stream=None):
        import select
        import sys

        stream = sys.stdout if stream is None else stream
        self._poll = select.poll()
        self._poll.register(stream, select.POLLOUT)
        self._src = getattr(stream, "buffer", stream)
        self._poll.ipoll(0)  # its first call makes the (stream, event) tuple it hands out: now, not in a frame

    def write(self, buf, n):
        for ev in self._poll.ipoll(0):
            if ev[1] & 4:  # POLLOUT (not an error or hang-up alone)
                return self._src.write(buf, n)  # MicroPython streams take a length: no slice made
            return 0
        return 0


def command(con, args):
    """`stream` (ask), `stream on [HZ]`, `stream off` on console con; returns the reply. A refusal
    raises ValueError naming what is allowed, having changed nothing."""
    t = con.telemetry
    if not args:
        if t is None or not t.every:
            return "ok stream off"
        return "ok stream %d sent %d dropped %d" % (t.hz, t.sent, t.dropped)
    if args == ["off"]:
        if t is not None:
            t.hz = t.every = 0
        return "ok stream off"
    if args[0] != "on" or len(args) > 2:
        raise ValueError("need on [HZ], off or nothing (ask), got %r" % (" ".join(args)[:20],))
    hz = HZ_DEFAULT
    if len(args) == 2:
        text = args[1]
        if not text.isdigit() or len(text) > 2 or not 1 <= int(text) <= HZ_MAX:
            raise ValueError("HZ %r: allowed a whole number 1..%d (lines a second)" % (text[:20], HZ_MAX))
        hz = int(text)
    if t is None:
        t = Stream(writer(con))
        con.telemetry = t
    t.hz = hz
    t.every = t.due = -(-FRAME_HZ // hz)
    con.runner.frame_us_max = 0  # the first line's worst: the frames since this command
    t.sent = t.dropped = 0
    return "ok stream %d" % hz


def writer(con):
    """A PollWriter on sys.stdout for a console on a board's serial port; ValueError where none can be."""
    import sys

    if con.write is None:
        raise ValueError("this console has no raw output to stream to")
    if sys.implementation.name != "micropython":
        raise ValueError(
            "not on %s: streaming needs MicroPython's select.poll on the console's output" % (sys.implementation.name,)
        )
    return PollWriter()
