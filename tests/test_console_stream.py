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
from tests.console_rig import clean_stubs  # noqa: F401 (autouse fixture)

# The console streaming to a sink that keeps each line: tests/scenarios/console_stream.py.
SCENARIO = "scenarios.console_stream:"

# seed 004's leg (robots/default.py), mm; the shipped robot stands with each foot 130 mm out from
# its coxa axis and 80 mm below it (NEUTRAL_REACH, BODY_HEIGHT).
LEG = dict(coxa=30.0, femur=85.0, tibia=125.0, femur_offset=32.0)
WALLS = [3000 + 1000 * k for k in range(5)]  # the rig's sonar walls, 0.1 mm, hexapod.sensors order


def call(rt, name, *args):
    return rt.call(SCENARIO + name, *args)


def fields(line):
    assert line.startswith("~T ") and line.endswith("\n"), line
    return line[3:-1].split(" ")


def test_a_fresh_relaxed_board_streams_no_pulse_and_no_battery(rt):
    reply, lines = call(rt, "fresh", True)
    assert reply == "ok stream 25"
    # say() ran frames until the reply: one frame here, the line comes every second frame
    assert lines == []
    (line,) = call(rt, "fresh", False)[1]
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
    lines, reply = call(rt, "standing")
    (line,) = lines
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
    assert reply == "ok stream 25 sent 1 dropped 0"


def test_walking_and_wall_following_fields_match_status(rt):
    walk, last = call(rt, "walking_then_following")
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
    line, status = last
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
    lines = call(rt, "frame_times", [3000, 1000, 5000, 2000, 1000, 4000])
    # Worked by hand: a frame takes its busy time plus the sonar's trigger, 2 us low and 10 us high
    # (drivers/hcsr04.py, the HC-SR04 datasheet's 10 us pulse), on the virtual clock. The line in
    # frame 2 says frame 1's time (the last whole one; its own is not over) and the worst since
    # `stream on`; frame 4's, frame 3's and the worst of frames 2-3; frame 6's, frame 5's (1,012 us)
    # and the worst of frames 4-5 (2,012 us).
    assert lines == [["3012", "3012"], ["5012", "5012"], ["1012", "2012"]]


# HZ -> ceil(50 / HZ) frames from line to line, and the lines in 300 frames, worked by hand.
RATES = {25: (2, 150), 17: (3, 100), 10: (5, 60), 7: (8, 37), 3: (17, 17), 1: (50, 6)}


def test_one_line_every_ceil_50_over_hz_frames(rt):
    out = call(rt, "rates", sorted(RATES))
    for hz, (every, count) in RATES.items():
        assert every == math.ceil(50 / hz)
        got = out[hz]
        assert len(got) == count, (hz, len(got))
        assert [b - a for a, b in zip(got, got[1:], strict=False)] == [every] * (count - 1), hz
    assert out["off"] == 0  # `stream off`: no line in 100 frames


def test_replies_tags_and_dropped_lines(rt):
    lines = ["stream", "#7 stream on 25", "#8 stream", "stream on", "stream", "stream off", "stream"]
    out = call(rt, "replies", lines, 3)  # the output refuses every third line
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
    out = call(rt, "no_output", ["stream on x", "stream on 5", "stream", "stream off"])
    assert out == [
        ("err stream: HZ 'x': allowed a whole number 1..25 (lines a second)", True),
        ("err stream: this console has no raw output to stream to", True),
        ("ok stream off", True),
        ("ok stream off", True),
    ]


def test_a_streaming_frame_allocates_nothing(mp):
    # Through a writer that keeps nothing, then through the board's own writer: select.poll (POLLOUT) on the VM's
    # stdout and its stream.write(buf, n). The scenario prints: the lines are the VM's stdout.
    out = mp.run("from scenarios.console_stream import frame_heap\nframe_heap()\n").splitlines()
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
    same, first = mp.call("scenarios.stream_digits:digits_same", rows)
    assert same == 100
    # the last row's first three fields, written by hand from the row
    last = ["-" if x == -0x3FFFFFFF else str(x) for x in rows[-1][:3]]
    assert first == last


@pytest.mark.parametrize("hz", ["0", "26", "x", "-5", "1.5"])
def test_a_refused_rate_names_the_range(rt, hz):
    reply, state = call(rt, "refused_rate", "stream on " + hz)
    assert reply == "err stream: HZ %r: allowed a whole number 1..25 (lines a second)" % hz
    assert state == (0, 0)


def test_a_line_goes_out_only_when_poll_says_the_output_takes_it(mp):
    a, written, reply, head = call(mp, "poll_port")
    assert a == (0, "ok stream 25 sent 0 dropped 10")
    assert (written, reply, head) == (10, "ok stream 25 sent 10 dropped 10", b"~T ")


def test_stream_is_refused_where_there_is_no_select_poll_output():
    # CPython (and CircuitPython, by the same test on sys.implementation.name): a console with raw
    # output but no MicroPython stream to poll refuses `stream on` by name and makes nothing.
    from hexapod_host.testing.runtimes import CPythonRuntime

    out = CPythonRuntime().call(SCENARIO + "no_output", ["stream on 5"], True)
    assert out[0] == (
        "err stream: not on cpython: streaming needs MicroPython's select.poll on the console's output",
        True,
    )
