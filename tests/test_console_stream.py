"""The console's telemetry (`stream on [HZ] | off`, docs/console.md "Telemetry"; issue 23) on the
board's loop, on CPython and in the MicroPython VM: the line of a known state against values
worked by hand, the fields of a walking and a wall-following robot against `status`, the rate
(every ceil(50/HZ)-th frame) by counting lines, the replies (tags, sent and dropped), the heap (0
bytes a streaming frame, through the real select.poll writer on the VM's stdout too) and the
viper twin of the integer writer against the plain one."""

import ast
import math
import random

import pytest

from hexapod_host.serial import telemetry
from hexapod_host.testing import reference
from tests.console_rig import RIG, clean_stubs  # noqa: F401 (autouse fixture)

# The telemetry's writer in tests: keeps each line; `take` says which lines the output takes
# (a line not taken is dropped by the console and counted).
SINK = """
from drivers import stream


class Sink:
    def __init__(self, take=None):
        self.lines = []
        self.take = take
        self.asked = 0

    def write(self, buf, n):
        self.asked += 1
        if self.take is not None and not self.take(self.asked):
            return 0
        self.lines.append(bytes(buf[:n]).decode())
        return n


sink = Sink()
con.telemetry = stream.Stream(sink)
"""

# seed 004's leg (robots/default.py), mm; the shipped robot stands with each foot 130 mm out from
# its coxa axis and 80 mm below it (NEUTRAL_REACH, BODY_HEIGHT).
LEG = dict(coxa=30.0, femur=85.0, tibia=125.0, femur_offset=32.0)
WALLS = [3000 + 1000 * k for k in range(5)]  # the rig's sonar walls, 0.1 mm, hexapod.sensors order


def run(rt, body):
    return rt.run(RIG + SINK + body, heapsize="4m")


def fields(line):
    assert line.startswith("~T ") and line.endswith("\n"), line
    return line[3:-1].split(" ")


def test_a_fresh_relaxed_board_streams_no_pulse_and_no_battery(rt):
    out = run(rt, 'print(repr(say("stream on 25")))\nprint(repr(sink.lines))\n').splitlines()
    assert ast.literal_eval(out[0]) == "ok stream 25"
    lines = ast.literal_eval(out[1])
    # say() ran frames until the reply: one frame here, the line comes every second frame
    assert lines == []
    out = run(rt, 'con.do("stream on 25")\nframes(2)\nprint(repr(sink.lines))\n').splitlines()
    (line,) = ast.literal_eval(out[-1])
    f = fields(line)
    assert len(f) == 46
    # frame 2; relaxed, tripod, no phase; not following; no walk; no pulse sent (relaxed from
    # power-up: 18 zeros)
    assert f[:27] == ["2", "0", "0", "0", "0", "0", "0", "0", "0"] + ["0"] * 18
    # the sonars: each either read (status 0, its wall within the driver's 0.2 mm) or not yet
    # (a status of 1..6 and '-' in its place)
    for k in range(5):
        if f[32 + k] == "0":
            assert abs(int(f[27 + k]) - WALLS[k]) <= 2, (k, f)
        else:
            assert f[27 + k] == "-" and 1 <= int(f[32 + k]) <= 6, (k, f)
    # no follower: 0 0; the pico board file has no battery: '-'; the counters 0
    assert f[37:44] == ["0", "0", "-", "0", "0", "0", "0"]


def test_a_standing_board_streams_its_hand_worked_pulses(rt):
    body = """
say("stand")
frames(150)
con.do("stream on 25")
frames(2)
print(repr(sink.lines))
print(repr(con.do("stream")))
"""
    out = run(rt, body).splitlines()
    (line,) = ast.literal_eval(out[-2])
    f = fields(line)
    # Worked by hand: the foot (130, 0, -80) mm -> coxa 0, femur 8.11, tibia -90.83 deg; the
    # calibration (robots/default_cal.py): 1500 us at the reference (0, 0, -90 deg), 10 us a
    # degree, legs 4-6's femur and tibia mirrored (direction -1):
    #   femur 1500 + 81.1 = 1581, tibia 1500 - 8.3 = 1492; mirrored 1419, 1508.
    right = [1500, 1581, 1492]
    left = [1500, 1419, 1508]
    assert [int(v) for v in f[9:27]] == right * 3 + left * 3
    # ... and the float IK oracle agrees with the hand working
    t1, t2, t3 = reference.ik(130.0, 0.0, -80.0, **LEG)
    assert [round(1500 + 10 * t1), round(1500 + 10 * t2), round(1500 + 10 * (t3 + 90))] == right
    assert f[0] == "153"  # say's frame, 150 more, then the second frame after `stream on`
    assert f[1:9] == ["3", "0", "0", "0", "0", "0", "0", "0"]  # standing, tripod, still
    assert f[32:37] == ["0"] * 5  # every sonar read by now
    assert all(abs(int(f[27 + k]) - WALLS[k]) <= 2 for k in range(5)), f
    assert f[37:44] == ["0", "0", "-", "0", "0", "0", "0"]
    # each frame's time on the virtual clock: the sonar trigger's 2 + 10 us (docs/console.md's example)
    assert f[44:] == ["12", "12"]
    assert ast.literal_eval(out[-1]) == "ok stream 25 sent 1 dropped 0"


def test_walking_and_wall_following_fields_match_status(rt):
    body = """
say("stand")
frames(150)
say("walk 50 -20 10")
con.do("stream on 25")
frames(40)
walk = list(sink.lines)
del sink.lines[:]
say("stop")
frames(120)
say("wall left 40")
frames(40)
print(repr(walk))
print(repr((sink.lines[-1], con.do("status"))))
"""
    out = run(rt, body).splitlines()
    walk = ast.literal_eval(out[-2])
    assert len(walk) == 20
    phases = []
    for line in walk:
        f = fields(line)
        # walking (4), tripod; the walk command as the console took it: 50 mm/s = 500 x 0.1 mm/s,
        # -20 mm/s = -200, 10 deg/s = 1000 x 0.01 deg/s
        assert f[1:3] == ["4", "0"] and f[6:9] == ["500", "-200", "1000"], f
        phases.append(int(f[3]))
    # the tripod's cycle is 1 s, 50 ticks: the phase goes 2 ticks from one line to the next, mod 50
    assert all(0 <= p < 50 for p in phases)
    assert [(b - a) % 50 for a, b in zip(phases, phases[1:], strict=False)] == [2] * 19
    line, status = ast.literal_eval(out[-1])
    f = fields(line)
    words = status.split()
    s = dict(zip(words[1::2], words[2::2], strict=False))
    assert s["wall"] == "left" and f[5] == "1"  # 1 left
    modes = ("off", "following", "corner", "lost", "searching", "blocked", "stopped")  # hexapod.follow
    assert modes[int(f[4])] == s["wall_mode"] and f[4] != "0"
    # status prints them in mm (1 decimal) and deg/s (2 decimals); the line has the raw integers
    assert int(f[37]) == round(float(s["wall_error"]) * 10)
    assert int(f[38]) == round(float(s["wall_out"]) * 100)
    assert f[40:44] == [s["held"], s["overruns"], s["bus_failed"], s["sonar_faults"]]


def test_the_frame_times_are_the_last_frame_and_the_worst_since_the_line_before(rt):
    # Six frames, each kept busy a known time on the virtual clock between its step and its wait
    # (where the console's work goes), streaming at 25 Hz: a line in every second frame's poll.
    body = """
say("stand")
frames(150)
con.do("stream on 25")
for busy in (3000, 1000, 5000, 2000, 1000, 4000):
    r.step()
    clock.advance_us(busy)
    con.poll()
    r.wait()
print(repr([line.split()[-2:] for line in sink.lines]))
"""
    lines = ast.literal_eval(run(rt, body).splitlines()[-1])
    # Worked by hand: a frame takes its busy time plus the sonar's trigger, 2 us low and 10 us high
    # (drivers/hcsr04.py, the HC-SR04 datasheet's 10 us pulse), on the virtual clock. The line in
    # frame 2 says frame 1's time (the last whole one; its own is not over) and the worst since
    # `stream on`; frame 4's, frame 3's and the worst of frames 2-3; frame 6's, frame 5's (1,012 us)
    # and the worst of frames 4-5 (2,012 us).
    assert lines == [["3012", "3012"], ["5012", "5012"], ["1012", "2012"]]


# HZ -> ceil(50 / HZ) frames from line to line, and the lines in 300 frames, worked by hand.
RATES = {25: (2, 150), 17: (3, 100), 10: (5, 60), 7: (8, 37), 3: (17, 17), 1: (50, 6)}


def test_one_line_every_ceil_50_over_hz_frames(rt):
    body = """
out = {}
for hz in %r:
    con.do("stream on %%d" %% hz)
    del sink.lines[:]
    frames(300)
    out[hz] = [int(line.split()[1]) for line in sink.lines]
con.do("stream off")
frames(100)
out["off"] = len(sink.lines) - len(out[hz])  # after the last rate
print(repr(out))
""" % (sorted(RATES),)
    out = ast.literal_eval(run(rt, body).splitlines()[-1])
    for hz, (every, count) in RATES.items():
        assert every == math.ceil(50 / hz)
        got = out[hz]
        assert len(got) == count, (hz, len(got))
        assert [b - a for a, b in zip(got, got[1:], strict=False)] == [every] * (count - 1), hz
    assert out["off"] == 0  # `stream off`: no line in 100 frames


def test_replies_tags_and_dropped_lines(rt):
    body = """
sink.take = lambda k: k % 3 != 0  # the output refuses every third line
for line in ["stream", "#7 stream on 25", "#8 stream", "stream on", "stream", "stream off", "stream"]:
    print(repr(say(line)))
    if line == "#7 stream on 25":
        frames(59)  # with say's frame: 60 frames, 30 lines due, 10 of them refused
"""
    out = [ast.literal_eval(x) for x in run(rt, body).splitlines()]
    assert out == [
        "ok stream off",
        "#7 ok stream 25",
        "#8 ok stream 25 sent 20 dropped 10",
        "ok stream 10",  # the default rate; the counts start again
        "ok stream 10 sent 0 dropped 0",
        "ok stream off",
        "ok stream off",
    ]


def test_no_raw_output_refuses_stream_and_makes_nothing(rt):
    body = """
con.telemetry = None
for line in ["stream on x", "stream on 5", "stream", "stream off"]:
    print(repr((con.do(line), con.telemetry is None)))
"""
    out = [ast.literal_eval(x) for x in run(rt, body).splitlines()]
    assert out == [
        ("err stream: HZ 'x': allowed a whole number 1..25 (lines a second)", True),
        ("err stream: this console has no raw output to stream to", True),
        ("ok stream off", True),
        ("ok stream off", True),
    ]


def test_a_streaming_frame_allocates_nothing(mp):
    from hexapod_host.testing.runtimes import HEAP_PROBE

    # Through a writer that keeps nothing, then through the board's own writer: select.poll (POLLOUT) on the VM's
    # stdout and its stream.write(buf, n).
    src = (
        RIG
        + SINK
        + HEAP_PROBE
        + """
import sys


class Null:  # takes every line, keeps none (the sink keeps them: that allocates)
    n = 0

    def write(self, buf, n):
        self.n += 1
        return n


null = Null()
con.telemetry = stream.Stream(null)
say("stand")
frames(150)
print(repr(con.do("stream on 25")))
a = heap_bytes(frames, 50)
con.telemetry = None
con.write = sys.stdout.write
print(repr(con.do("stream on 25")))
b = heap_bytes(frames, 50)
print(repr((a, b, null.n, type(con.telemetry.out).__name__, stream._digits_fast is not None)))
"""
    )
    out = mp.run(src, heapsize="4m").splitlines()
    a, b, n, writer, viper = ast.literal_eval(out[-1])
    assert (a, b) == (0, 0)
    assert n == 50 and writer == "PollWriter" and viper
    lines = [x for x in out if telemetry.is_telemetry(x)]
    assert len(lines) == 50  # the board's writer's: two runs of 50 frames at 25 Hz
    for x in lines:
        t = telemetry.parse(x)
        assert t["mode"] == 3 and t["pulses"][:3] == [1500, 1581, 1492]
    assert out[0] == "'ok stream 25'"


def test_the_viper_writer_equals_the_plain_one(mp):
    rng = random.Random(23)
    picks = [0, 9, 10, 99, 100, 999, 1000, 9999, 10000, 1073741823, -1, -10, -1073741822, -0x3FFFFFFF]
    rows = []
    for _ in range(100):
        row = [
            rng.choice(picks) if rng.random() < 0.3 else rng.randint(-(10 ** rng.randint(1, 9)), 10**9)
            for _ in range(44)
        ]
        rows.append(row)
    src = """
from array import array
from drivers import stream
rows = %r
same = 0
for row in rows:
    v = array("i", row)
    a = bytearray(531)
    b = bytearray(531)
    n = stream.digits(a, 2, v, 44)
    m = stream._digits_fast(b, 2, v, 44)
    same += n == m and a == b
print(same, bytes(a[:n]).decode().split(" ")[1:4])
""" % (rows,)
    out = mp.run(src, heapsize="4m").split()
    assert out[0] == "100"
    # the last row's first three fields, written by hand from the row
    last = ["-" if x == -0x3FFFFFFF else str(x) for x in rows[-1][:3]]
    assert ast.literal_eval(" ".join(out[1:])) == last


@pytest.mark.parametrize("hz", ["0", "26", "x", "-5", "1.5"])
def test_a_refused_rate_names_the_range(rt, hz):
    out = run(
        rt, "print(repr(con.do(%r)))\nprint(repr((con.telemetry.hz, con.telemetry.every)))\n" % ("stream on " + hz)
    )
    reply, state = [ast.literal_eval(x) for x in out.splitlines()]
    assert reply == "err stream: HZ %r: allowed a whole number 1..25 (lines a second)" % hz
    assert state == (0, 0)


# A port for select.poll in the VM (io.IOBase with ioctl): POLLOUT only while it has room.
PORT = """
import io
from drivers import stream


class Port(io.IOBase):
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
"""


def test_a_line_goes_out_only_when_poll_says_the_output_takes_it(mp):
    src = (
        RIG
        + PORT
        + """
port = Port()
con.telemetry = stream.Stream(stream.PollWriter(port))
con.do("stream on 25")
frames(20)  # 10 lines due, no room: every one dropped, nothing written
a = (len(port.got), con.do("stream"))
port.room = True
frames(20)
print(repr((a, len(port.got), con.do("stream"), port.got[0][:3])))
"""
    )
    a, written, reply, head = ast.literal_eval(mp.run(src, heapsize="4m").splitlines()[-1])
    assert a == (0, "ok stream 25 sent 0 dropped 10")
    assert (written, reply, head) == (10, "ok stream 25 sent 10 dropped 10", b"~T ")


def test_stream_is_refused_where_there_is_no_select_poll_output():
    # CPython (and CircuitPython, by the same test on sys.implementation.name): a console with raw
    # output but no MicroPython stream to poll refuses `stream on` by name and makes nothing.
    from hexapod_host.testing.runtimes import CPythonRuntime

    body = """
import sys
con.telemetry = None
con.write = sys.stdout.write
print(repr((con.do("stream on 5"), con.telemetry is None)))
"""
    out = CPythonRuntime().run(RIG + SINK + body).splitlines()[-1]
    assert ast.literal_eval(out) == (
        "err stream: not on cpython: streaming needs MicroPython's select.poll on the console's output",
        True,
    )
