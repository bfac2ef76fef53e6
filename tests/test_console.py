"""The serial console on the board's loop (docs/console.md): replies, jogging against the float
IK oracle, refusals that change nothing, the line reader's limits, walk expiry, calibration
commands. Core/console logic runs on CPython and in the MicroPython VM, bit-identically."""

import re

import pytest

from hexapod_host.testing import reference
from tests.console_rig import clean_stubs  # noqa: F401 (autouse fixture)

SCENARIO = "scenarios.console_lines:"

# seed 004's leg (robots/default.py), mm
LEG = dict(coxa=30.0, femur=85.0, tibia=125.0, femur_offset=32.0)
LEG_LINE = re.compile(
    r"^ok leg (\d) angles (-?\d+\.\d\d) (-?\d+\.\d\d) (-?\d+\.\d\d) pulses (\d+) (\d+) (\d+) "
    r"foot (-?\d+\.\d) (-?\d+\.\d) (-?\d+\.\d)$"
)


def call(runtime, name, *args):
    """The scenario tests/scenarios/console_lines.py:name on runtime, in a 4 MB VM heap."""
    return runtime.call(SCENARIO + name, *args)


def test_jogging_matches_the_float_ik_and_the_servo_map(rt):
    replies = call(rt, "replies", ["foot 2 130 0 -80", "nudge 2 5 -10 2.5", "get 2"])[0]
    for reply, (x, y, z) in zip(replies, [(130, 0, -80), (135, -10, -77.5), (135, -10, -77.5)], strict=True):
        m = LEG_LINE.match(reply)
        assert m, reply
        angles = [float(v) for v in m.group(2, 3, 4)]
        want = reference.ik(x, y, z, **LEG)
        assert max(abs(a - w) for a, w in zip(angles, want, strict=True)) <= 0.011
        # default_cal leg 2: coxa, femur 1500 us at 0, tibia 1500 at -90 deg (2400 at 0), direction 1, 10 us/deg
        pulses = [int(v) for v in m.group(5, 6, 7)]
        assert [
            abs(p - q) <= 0.5 + 1e-9
            for p, q in zip(
                pulses, [1500 + 10 * a for a in (angles[0], angles[1])] + [2400 + 10 * angles[2]], strict=True
            )
        ] == [True] * 3
        foot = [float(v) for v in m.group(8, 9, 10)]
        assert max(abs(f - w) for f, w in zip(foot, (x, y, z), strict=True)) <= 0.1


def test_commands_reply_one_line_each_on_both_runtimes(both_runtimes):
    lines = [
        "help",
        "get 1",
        "foot 2 130 0 -80",
        "joint 2 femur 12.5",
        "pulse 2 tibia 1600",
        "cal 2 femur",
        "trim 2 femur 20",
        "dir 2 coxa -1",
        "range 2 tibia 700 2300",
        "stand",
        "gait ripple",
        "gait",
        "pid",
        "pid 20 0.25 2",
        "sonar",
        "wall off",
        "stop",
        "defaults",
        "save",
        "load",
    ]
    cp, mp = both_runtimes.call(SCENARIO + "replies", lines, 120)
    assert cp == mp
    replies, _, unsafe = cp
    assert unsafe == []
    assert len(replies) == len(lines)
    assert replies[0] == (
        "ok help status stand sit relax foot nudge joint pulse get walk stop gait height sonar wall pid "
        "cal trim dir range save load defaults echo selftest faults stream"
    )
    assert replies[3].startswith("ok leg 2 angles 0.00 12.50 ") and " pulses 1500 1625 " in replies[3]
    assert " angles 0.00 12.50 -80.00 pulses 1500 1625 1600 " in replies[4]  # 2400 + 10 x -80
    assert replies[5] == "ok leg 2 joint femur centre_us 1500 ref_deg 0.00 trim 0 dir 1 min_us 600 max_us 2400"
    assert replies[6] == "ok leg 2 joint femur centre_us 1500 ref_deg 0.00 trim 20 dir 1 min_us 600 max_us 2400"
    assert replies[7] == "ok leg 2 joint coxa centre_us 1500 ref_deg 0.00 trim 0 dir -1 min_us 600 max_us 2400"
    # the tibia's centre_us is its pulse at the -90 degree knee (robots/default_cal.py REFERENCE)
    assert replies[8] == "ok leg 2 joint tibia centre_us 1500 ref_deg -90.00 trim 0 dir 1 min_us 700 max_us 2300"
    assert replies[9] == "ok mode moving"
    assert replies[10:12] == ["ok gait ripple", "ok gait ripple"]
    assert replies[12:14] == ["ok pid 25.000 0.500 1.000", "ok pid 20.000 0.250 2.000"]
    assert replies[14].startswith("ok front 300.0 ok left_front ")
    assert replies[15:17] == ["ok wall off", "ok mode standing"]
    assert replies[17] == "ok defaults"
    assert replies[18:] == [
        "err save: no calibration file on this board",
        "err load: no calibration file on this board",
    ]


def test_trim_dir_range_move_a_held_servo_by_what_the_map_says(rt):
    r, channels, _ = call(
        rt,
        "replies",
        [
            "joint 3 femur 20",
            "trim 3 femur -35",
            "dir 3 femur -1",
            "range 3 femur 1400 1500",
            "range 3 femur 1200 1500",
            "get 3",
        ],
    )
    assert " pulses 0 1700 0 " in r[0]  # 1500 + 20 deg x 10 us; the leg's other servos stay limp
    assert r[1].endswith("trim -35 dir 1 min_us 600 max_us 2400")
    assert r[2].endswith("trim -35 dir -1 min_us 600 max_us 2400")  # 1465 - 200 = 1265 us now
    assert r[3] == "err range: leg 3 femur: at 20.00 deg it would need 1265 us, outside 1400..1500 us"
    assert r[4].endswith("min_us 1200 max_us 1500")
    assert " pulses 0 1265 0 " in r[5]
    assert abs(channels[7] - 1265) <= 3  # the PCA9685 model: 4.9 us per count at 50 Hz


BAD = [
    "foot 7 100 0 -80",
    "foot 0 100 0 -80",
    "foot 2 100 0",
    "foot 2 100 0 -80 1",
    "foot 2 abc 0 -80",
    "foot 2 1e2 0 -80",
    "foot 2 600 0 -80",
    "foot 2 300 0 -80",
    "foot 2 30 0 30",
    "foot 2 -130 0 -80",
    "foot 2 0x10 0 -80",
    "foot 2 nan 0 -80",
    "foot 2 -- 0 -80",
    "foot 2 1.2.3 0 -80",
    "foot two 100 0 -80",
    "nudge 2 0 0 200",
    "nudge 1 0 0 1",
    "joint 2 knee 10",
    "joint 2 femur 95",
    "joint 2 tibia 5",
    "joint 2 coxa 181",
    "joint 2 femur",
    "pulse 2 femur 2401",
    "pulse 2 femur 599",
    "pulse 2 femur 1500.5",
    "pulse 2 femur -1500",
    "pulse 2 elbow 1500",
    "get 9",
    "get",
    "get 2 3",
    "walk 1 2",
    "walk 400 0 0",
    "walk 0 0 91",
    "walk a b c",
    "gait trot",
    "wall up 8",
    "wall left 3",
    "wall left 51",
    "wall left",
    "pid 1 2",
    "pid -1 0 0",
    "pid 101 0 0",
    "cal 2",
    "cal 2 foot",
    "trim 2 femur 301",
    "trim 2 femur -301",
    "trim 2 tibia 301",
    "trim 2 tibia -301",
    "trim 2 femur 1.5",
    "dir 2 femur 0",
    "dir 2 femur 2",
    "range 2 femur 1500 1500",
    "range 2 femur 400 2400",
    "range 2 femur 600 2600",
    "range 2 femur 2000 1000",
    "save 1",
    "load now",
    "defaults x",
    "status x",
    "jump",
    "STAND",
    "stand up",
    "foot 2 +-1 0 0",
    "foot 2 . 0 0",
    "foot 2 1234567890 0 0",
    "walk 0.0.0 0 0",
]


def test_bad_lines_are_refused_and_change_nothing(rt):
    replies, changed, unsafe = call(rt, "refusals", "foot 2 130 0 -80", BAD)
    assert changed == []
    assert len(replies) == len(BAD)
    for line, reply in zip(BAD, replies, strict=True):
        word = line.split()[0]
        assert reply.startswith("err %s: " % word) or reply.startswith("err unknown command"), (line, reply)
        assert "internal" not in reply
    assert unsafe == []
    by = dict(zip(BAD, replies, strict=True))
    assert by["foot 7 100 0 -80"] == "err foot: leg '7', allowed 1..6"
    assert by["foot 2 600 0 -80"] == "err foot: x 600 is outside -500.0..500.0 mm"
    assert by["foot 2 1e2 0 -80"] == "err foot: x '1e2' is not a decimal number (mm)"
    assert by["joint 2 femur 95"] == "err joint: femur above its limit by 5.00 deg"
    assert by["pulse 2 femur 2401"] == "err pulse: pulse 2401 is outside 600..2400 us (this servo's calibrated range)"
    assert by["nudge 1 0 0 1"] == "err nudge: leg 1 has a limp servo: place it with 'foot' first"
    assert by["walk 1 2"] == "err walk: need VX VY WZ (mm/s, mm/s, deg/s), got 2 arguments"
    assert by["jump"] == "err unknown command 'jump' (help lists them)"
    # 130 mm beyond reach: the float IK's reach is femur + tibia from the femur joint
    far = reference.ik(300, 0, -80, **LEG)
    assert far is None and by["foot 2 300 0 -80"].startswith("err foot: too far: ")
    d = ((300 - 30) ** 2 + (-80 - 32) ** 2) ** 0.5 - 210
    # far outside, leg.solve quarters the coordinates: its excess is good to +-0.5 mm
    assert abs(float(by["foot 2 300 0 -80"].split()[4]) - d) <= 0.5


def test_line_reader_limits(rt):
    out = call(rt, "reader_limits")
    assert [x.split()[2] for x in out[0]] == ["1", "2", "3"]  # \r\n, \r, \n end a line; blank lines: no reply
    n1, replies = out[1]
    assert n1 == 0 and replies[0] == "err line too long (at most 95 characters)" and replies[1].startswith("ok leg 4 ")
    assert out[2][0] == "err non-text byte 0xff in line (allowed: printable ASCII)"
    assert out[2][1] == "err non-text byte 0x00 in line (allowed: printable ASCII)"
    assert out[2][2].startswith("ok leg 5 ")  # a tab separates words
    assert out[3] == "err unknown command 'xxxxxxxxxxxxxxxxxxxx'"[:30]  # exactly 95 characters is a line


def test_walk_expires_unless_renewed(rt):
    reply, seen = call(rt, "walk_expiry")
    assert reply == "ok walk 60.0 0.0 0.00 timeout_ms 1000"
    (after,) = seen
    assert 1000 <= after <= 1040  # stopping within two 20 ms frames after the 1 s deadline


def test_idle_console_frame_allocates_nothing(mp):
    assert call(mp, "idle_heap") == [0, 0]


@pytest.mark.parametrize("start", ["relaxed", "standing"])
def test_jog_changes_only_that_legs_channels(rt, start):
    reply, (before, after, bad) = call(rt, "jog_one_leg", start)
    m = LEG_LINE.match(reply)
    assert bad == []
    changed = [k for k in range(18) if before[k] != after[k]]
    assert set(changed) <= {3, 4, 5} and after[3:6] != before[3:6]
    want = reference.ik(140, 10, -70, **LEG)
    for k, (centre, a) in enumerate(zip((1500, 1500, 2400), want, strict=True)):
        assert abs(after[3 + k] - (centre + 10 * a)) <= 2.6  # half a PCA9685 count (2.44 us) + IK 0.01 deg
    assert int(m.group(5)) == after[3] or abs(int(m.group(5)) - after[3]) <= 3


def test_while_following_a_wall_jogs_and_walks_are_refused_until_wall_off(rt):
    lines = ["stand", "wall left 40", "foot 2 130 0 -80", "joint 1 coxa 5", "walk 50 0 0", "relax", "wall off", "stop"]
    r = call(rt, "replies", lines, 120)[0]
    assert r[0] == "ok mode moving" and r[1] == "ok wall left setpoint 40.00"
    for reply, word in zip(r[2:6], ("foot", "joint", "walk", "relax"), strict=True):
        assert reply == "err %s: the robot is following a wall; 'wall off' first" % word
    assert r[6] == "ok wall off" and r[7].startswith("ok mode ")


def test_wall_takes_a_form_crab_by_default(rt):
    """`wall SIDE CM` follows in form crab (sideways to the set point); a third word picks the form
    (yaw: the PID turns, no sideways speed); a bad form is refused with the allowed ones."""
    lines = ["wall left 12", "wall left 12 yaw", "wall left 12 crab", "wall left 12 zigzag", "wall off"]
    out = call(rt, "wall_forms", lines)
    (r0, f0, c0), (r1, f1, c1), (r2, f2, c2), (r3, f3, c3), (r4, _, _) = out
    assert (r0, f0) == ("ok wall left setpoint 12.00", "crab") and c0[1] != 0, out[0]
    assert (r1, f1) == ("ok wall left setpoint 12.00 form yaw", "yaw") and c1[1] == 0 and c1[2] != 0, out[1]
    assert (r2, f2) == ("ok wall left setpoint 12.00 form crab", "crab") and c2[1] != 0, out[2]
    assert r3 == "err wall: form 'zigzag', allowed yaw, sweeps, crab" and f3 == "crab", out[3]
    assert r4 == "ok wall off"


def test_backspace_and_echo(rt):
    """A person in a terminal: backspace (0x08 or 0x7f) takes back the line's last character,
    `echo on` sends typed characters back; tools (echo off, the default) see only replies."""
    chunks = [
        (b"get 2x\x7f\r", 3),
        (b"echo\necho on\n", 5),  # the first reporting command waits for its modules (a frame each)
        (b"gex\x08t\t1\r\n", 3),
        (b"\x7f\x7f\n", 3),
        (b"get 3\x01\x7f\n", 3),
        (b"get\x01 3\x7f\n", 3),
        (b"x" * 96 + b"\x7f\n", 5),
        (b"x" * 97 + b"\x7f\x7f\x7f\n", 5),
        (b"echo off\nget 4\n", 3),
    ]
    out = call(rt, "backspace_and_echo", chunks)
    assert out[0][0][0].startswith("ok leg 2 ") and out[0][1] == ""  # the typo went; echo off: nothing raw
    assert out[1] == [["ok echo off", "ok echo on"], ""]
    (reply,), raw = out[2]
    assert reply.startswith("ok leg 1 ") and raw == "gex\b \bt 1\r\n"  # a tab echoes as a space
    assert out[3] == [[], "\r\n"]  # nothing to take back, a blank line: no reply
    (reply,), raw = out[4]
    assert reply.startswith("ok leg 3 ") and raw == "get 3\r\n"  # the unechoed 0x01 is not rubbed out
    assert out[5] == [["err non-text byte 0x01 in line (allowed: printable ASCII)"], "get 3\b \b\r\n"]
    # 96 characters less one is exactly a line again; the 96th was never echoed
    (reply,), raw = out[6]
    assert reply == "err unknown command 'xxxxxxxxxxxxxxxxxxxx' (help lists them)" and raw == "x" * 95 + "\r\n"
    (reply,), raw = out[7]
    assert reply.startswith("err unknown command") and raw == "x" * 95 + "\b \b\r\n"
    assert out[8][0][0] == "ok echo off" and out[8][0][1].startswith("ok leg 4 ") and out[8][1] == "echo off\r\n"


def test_echo_refuses_bad_words(rt):
    replies, again, echo = call(rt, "echo_words", ["echo maybe", "echo on off", "echo ON", "echo 1", "echo on"])
    out = replies + [again, echo]
    need = "err echo: need on, off or nothing (ask), got %r"
    assert out[:4] == [need % "maybe", need % "on off", need % "ON", need % "1"]
    assert out[4] == "err echo: this console has no raw output to echo to"  # the rig's console has none
    assert out[5] == need % "on off" and out[6] is False  # refused: echo stays off


def test_tibia_trim_has_room_both_ways_at_its_reference(both_runtimes):
    """The tibia is calibrated at its -90 degree knee (1500 us), mid-range: trims of +-10 and
    +-300 us act at once; before, its reference was angle 0 at 2400 us, the end of its range, and
    a held servo there refused any trim up. The pulses for an angle are unchanged by the
    reference: 2400 us at 0 degrees, as seed 001's map gives (1500 + 10 us per degree x 90)."""
    lines = [
        "joint 2 tibia 0",
        "joint 2 tibia -90",
        "trim 2 tibia 10",
        "get 2",
        "trim 2 tibia -10",
        "get 2",
        "trim 2 tibia 300",
        "trim 2 tibia -300",
        "get 2",
        "joint 5 tibia -90",
        "trim 5 tibia 10",
        "get 5",
        "dir 5 tibia 1",
        "get 5",
        "joint 5 tibia -80",
    ]
    cp, mp = both_runtimes.call(SCENARIO + "replies", lines)
    assert cp == mp
    r, _, unsafe = cp
    pulses = [LEG_LINE.match(x).group(7) if LEG_LINE.match(x) else x for x in r]
    assert pulses[0] == "2400" and pulses[1] == "1500"
    assert r[2].endswith("trim 10 dir 1 min_us 600 max_us 2400") and pulses[3] == "1510"
    assert r[4].endswith("trim -10 dir 1 min_us 600 max_us 2400") and pulses[5] == "1490"
    assert r[6].endswith(" trim 300 dir 1 min_us 600 max_us 2400")
    assert r[7].endswith(" trim -300 dir 1 min_us 600 max_us 2400") and pulses[8] == "1200"
    # leg 5 is mirrored (direction -1): at -90 degrees 1500 us, trimmed +10 -> 1510; flipping its
    # direction mirrors it about the reference, so -90 degrees stays 1510 us and -80 goes to 1610.
    assert pulses[9] == "1500" and pulses[11] == "1510"
    assert r[12].endswith("trim 10 dir 1 min_us 600 max_us 2400") and pulses[13] == "1510"
    assert pulses[14] == "1610"
    assert unsafe == []


WALL_D = re.compile(r" wall_d (\S+) ")


def test_status_shows_no_wall_distance_as_a_dash(rt):
    """`wall_d` is '-' while there is no distance: following off (was 0.0), and following with
    both left sonars hearing nothing (was -0.1, the follower's -1 sentinel); with both left
    sonars 120.0 mm from a wall parallel to the body, the distance: 120 mm within the driver's
    echo rounding (1 us of echo is 0.17 mm)."""
    r = call(rt, "wall_status", None) + call(rt, "wall_status", 1200)
    assert r[2] == "ok wall left setpoint 12.00" and r[5] == r[2]
    assert WALL_D.search(r[0]).group(1) == "-" and " wall off " in r[0]
    assert WALL_D.search(r[3]).group(1) == "-" and " wall left " in r[3]
    assert abs(float(WALL_D.search(r[6]).group(1)) - 120.0) <= 0.2, r[6]


def test_status_answers_without_importing_the_reporting_module(mp):
    """`status`, the command tools poll, lives in console.py: its first use after 30 s without a
    reporting command took ~34 ms on the emulated Pico, the module's import (docs/pico.md); `help`
    still loads consoleparts.more (the VM: hexapod.release and the imports are MicroPython's)."""
    assert call(mp, "status_imports") == [True, False, True]


def test_a_command_waits_for_its_modules_one_import_a_frame(mp):
    """A line whose command needs modules not loaded yet (a fresh board: the VM's hexapod.release
    and imports are MicroPython's) waits: poll imports one module a frame, in console.BEFORE's
    order (the package first; `foot`: caledit, hexapod.jog, then consoleparts.jog), and runs
    the line in the frame after the last, so no frame pays two imports nor an import and the
    command (each import fits a frame's slack on the emulated Pico; one module's import in the
    command's frame made it late, docs/pico.md). The line after it keeps its place; the replies
    and the refusal are do()'s with every module loaded, and the robot ends as there."""
    lines = [b"help\nget 1\n", b"#5 pid\n", b"foot 9 0 0 0\n", b"foot 2 130 5 -80\n", b"sonar\n"]
    got, direct, same_state = call(mp, "deferred_imports", lines)
    shown = [[f for f in frames if f is not None] for frames in got]
    # every frame imports at most one module; the line's own frame (the first) only reads it
    assert all(f is None or len(f[0]) <= 1 for frames in got for f in frames)
    # a waiting line is never answered in its own frame; a loaded one is (foot again)
    assert [g[0] is None for g in got] == [True, True, True, False, True]
    assert shown[0] == [[["consoleparts"], []], [["consoleparts.more"], []], [[], direct[0:2]]]
    assert shown[1] == [[["consoleparts.setting"], []], [[], [direct[2]]]] and direct[2].startswith("#5 ok pid ")
    chain = ["consoleparts.caledit", "hexapod.jog", "consoleparts.jog"]
    assert shown[2] == [[[m], []] for m in chain] + [[[], ["err foot: leg '9', allowed 1..6"]]]
    assert direct[3] == "err foot: leg '9', allowed 1..6"
    assert shown[3] == [[[], [direct[4]]]] and direct[4].startswith("ok leg 2 ")
    assert shown[4] == [[["consoleparts.sonar"], []], [[], [direct[5]]]] and direct[5].startswith("ok front ")
    assert same_state
