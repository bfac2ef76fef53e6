"""The console's `selftest` (issue 20, point 4) on the stub board, both runtimes: every check's line,
faults found with the hint naming their likely cause, no PCA9685 register written, bad input
refused with nothing changed; `selftest servos L` through the jog path; the link collecting a
multi-line reply; `hexapod doctor` against the virtual board.

Expected values are worked by hand from the data sheets and the board file, not read from the
code: PRE_SCALE = round(25 MHz / (4096 x 50 Hz)) - 1 = round(122.07) - 1 = 121 = 0x79; MODE1 after
the driver's start-up = AI (0x20: SLEEP cleared, ALLCALL cleared, RESTART cleared by writing it);
a PCA9685 after power-on/brownout: MODE1 0x11 (SLEEP | ALLCALL), PRE_SCALE 0x1E; the sonars stand
30, 40, 50, 60, 70 cm away; the calibration file's CRC is CRC-16/CCITT-FALSE (binascii.crc_hqx
with 0xFFFF) of every byte before its crc line."""

import binascii
import json
import os
import tomllib

import pytest

from hexapod_host import ROOT
from hexapod_host.commands import cli, doctor
from hexapod_host.serial.link import Link
from tests.console_rig import clean_stubs  # noqa: F401 (autouse fixture)

FIX = ": fix the cause (docs/console.md, faults), then `faults clear`"
HINT_0x41 = "is its A0 jumper bridged (and no other)? is its VCC on 3V3? SDA and SCL wired through? common ground"


def cal_crc():
    """The CRC of the scenario's calibration file (the default robot's rows, trim 0), by hand."""
    # robots/default_cal.py: right legs all direction 1; left legs coxa 1, femur and tibia -1; 600..2400 us
    rows = []
    for k in range(18):
        d = -1 if k >= 9 and k % 3 else 1
        rows.append("%d %s 0 %d 600 2400\n" % (k // 3 + 1, ("coxa", "femur", "tibia")[k % 3], d))
    body = "hexapod-cal 2\n" + "".join(rows)  # save writes version 2 (the tibia at its -90 degree reference)
    return binascii.crc_hqx(body.encode(), 0xFFFF)


def test_selftest_passes_on_the_stub_board_and_writes_no_register(rt):
    lines, frames, before, after, loaded, same = rt.call("scenarios.selftest:checks")
    heap = lines[8]
    assert lines[:8] == [
        "ok board pico robot default",
        "ok version 0.1.0",
        "ok i2c found 0x40 0x41",
        "ok pca9685 0x40 MODE1 0x20 PRE_SCALE 0x79 (50 Hz at osc 25000000 Hz)",
        "ok pca9685 0x41 MODE1 0x20 PRE_SCALE 0x79 (50 Hz at osc 25000000 Hz)",
        "ok calibration hexapod_cal.txt crc %04x (in force: file)" % cal_crc(),
        "ok reset_cause power_on",
        "ok faults none",  # the fault log: nothing went wrong since power-up
    ]
    if rt.name == "cpython":
        assert heap == "ok heap n/a (no gc.mem_free on this runtime)"
    else:
        free = int(heap.split()[3])
        assert heap == "ok heap free %d bytes" % free and 16384 <= free <= 4 * 1024 * 1024
    assert lines[9:] == [
        "ok supply n/a (no battery monitor configured)",
        # 58.3 us a cm at 20 degC, the model's rounding to whole us: within 0.1 mm of the distance
        "ok sonar front ok 300.0 mm",
        "ok sonar left_front ok 400.1 mm",
        "ok sonar left_rear ok 500.0 mm",
        "ok sonar right_front ok 600.0 mm",
        "ok sonar right_rear ok 700.1 mm",
        "ok selftest 15 checks, 0 failed",
    ]
    # the round robin: 5 slots (neighbours 2 ticks apart), each sensor's echo collected a tick after
    # its ping, so 6 frames from the line to the end line
    assert frames == 6
    assert before == after  # every register and latched output of both PCA9685 models
    assert not loaded and same  # the module left the heap; robot, calibration, mode untouched


def test_selftest_standing_moves_no_servo(rt):
    lines, frames, before, after, loaded, same = rt.call("scenarios.selftest:checks", standing=True)
    assert lines[-1] == "ok selftest 15 checks, 0 failed"
    assert before == after and same  # a standing robot's pulses, register by register


@pytest.mark.parametrize(
    "fault, errs",
    [
        (
            "detach_0x41",
            [
                "err i2c found 0x40, missing 0x41: " + HINT_0x41 + " with the Pico?",
                "err pca9685 0x41: no answer: " + HINT_0x41 + " with the Pico?",
                # absent from build on: the loop's first frame (0) found it missing
                "err faults 1 logged (oldest first) i2c 0x41 frame 0" + FIX,
                "err selftest 15 checks, 3 failed",
            ],
        ),
        (
            "unplug_0x41",
            [
                "err i2c found 0x40, missing 0x41: " + HINT_0x41 + " with the Pico?",
                "err pca9685 0x41: no answer: " + HINT_0x41 + " with the Pico?",
                # unplugged after frames 0-4: frame 5, the one the selftest line arrives in, fails
                "err faults 1 logged (oldest first) i2c 0x41 frame 5" + FIX,
                "err selftest 15 checks, 3 failed",
            ],
        ),
        (
            "brownout_0x41",
            [
                "err pca9685 0x41 MODE1 0x11 PRE_SCALE 0x1e, the driver wrote MODE1 0x20 PRE_SCALE 0x79: it reset "
                "since start-up (a brownout: servo power sagging into its VCC? VCC on 3V3, not on the servo "
                "supply) or another I2C master writes it; the loop sets it up again within 10 frames",
                "err selftest 15 checks, 1 failed",
            ],
        ),
        (
            "no_echo_left_rear",
            [
                # pico.py: left_rear trigger GP10, echo GP11
                "err sonar left_rear no_echo: the echo never rose: module on 5 V? trigger on pin 10, echo on pin "
                "11? the echo's 1k/2k divider in place? common ground with the Pico?",
                "err selftest 15 checks, 1 failed",
            ],
        ),
        (
            "cal_corrupt",
            [
                "err calibration hexapod_cal.txt checksum mismatch (corrupt): the robot file's defaults are in use "
                "at boot (in force now: defaults): calibrate and 'save' (docs/jog.md)",
                "err selftest 15 checks, 1 failed",
            ],
        ),
        (
            "cal_missing",
            [
                "err calibration no hexapod_cal.txt: the robot file's defaults are in use at boot (in force now: "
                "defaults): calibrate and 'save' (docs/jog.md)",
                "err selftest 15 checks, 1 failed",
            ],
        ),
    ],
)
def test_selftest_names_each_fault_and_its_likely_cause(rt, fault, errs):
    lines, frames, before, after, loaded, same = rt.call("scenarios.selftest:checks", fault)
    assert [x for x in lines if x.startswith("err")] == errs
    assert len(lines) == 16 and frames == 6 and same and not loaded
    assert before[0] == after[0]  # chip 0x40 untouched whatever happened to 0x41
    if fault in ("no_echo_left_rear", "cal_corrupt", "cal_missing"):
        assert before == after


@pytest.mark.parametrize("mode", ["relaxed", "standing", "sitting"])
def test_bad_selftest_lines_are_refused_and_change_nothing(rt, mode):
    out, same, loaded = rt.call("scenarios.selftest:bad_lines", mode)
    by = {line: got for line, got in out}
    assert all(len(got) == 1 and got[0].startswith("err selftest: ") for got in by.values()), by
    assert same and not loaded
    allowed = "allowed nothing (the hardware checks) or 'servos L' (leg 1..6)"
    assert by["selftest foo"] == ["err selftest: 'foo', " + allowed]
    assert by["selftest SERVOS 2"] == ["err selftest: 'SERVOS', " + allowed]
    assert by["selftest servos 7"] == ["err selftest: leg '7', allowed 1..6"]
    assert by["selftest servos x"] == ["err selftest: leg 'x', allowed 1..6"]
    assert by["selftest servos 2.0"] == ["err selftest: leg '2.0', allowed 1..6"]
    assert by["selftest servos"] == ["err selftest: need servos L (leg 1..6), got 0 arguments"]
    assert by["selftest servos 2 3"] == ["err selftest: need servos L (leg 1..6), got 2 arguments"]
    if mode != "sitting":
        assert by["selftest servos 2"] == [
            "err selftest: the robot is %s; servos are swept only while it sits (body on the ground, no leg "
            "carries it): 'sit' first" % mode
        ]


def test_servo_sweep_moves_only_that_leg_slowly_and_comes_back(rt):
    lines, frames, seen, others, mode, before, after = rt.call("scenarios.selftest:sweep", 2)
    # pico.py leg 2: 10 us a degree, direction 1: +-10 degrees is +-100 us around each pulse held
    c, f, t = before
    assert lines[0] == "ok servo 2 coxa swept -10.00..10.00 deg at 20 deg/s, pulses %d..%d us" % (c - 100, c + 100)
    assert lines[1].startswith("ok servo 2 femur swept ") and lines[1].endswith("pulses %d..%d us" % (f - 100, f + 100))
    assert lines[2].startswith("ok servo 2 tibia swept ") and lines[2].endswith("pulses %d..%d us" % (t - 100, t + 100))
    assert lines[3:] == ["ok selftest servos 2: 3 joints swept, 0 failed"]
    # 40 degrees of travel a joint at 0.4 degree a frame (20 deg/s at 50 Hz): 100 frames, 3 joints,
    # and the frame in which the line arrived
    assert frames == 301
    assert not others  # the other 15 servos' outputs never changed
    half_count = 20000 / 4096 / 2  # us: the PCA9685 model's whole-us output of a 4.88 us count
    for a, b in zip(seen, seen[1:], strict=False):
        assert max(abs(x - y) for x, y in zip(a, b, strict=True)) <= 4 + 2 * half_count + 1  # 4 us a frame
    for j in range(3):
        got = [s[j] for s in seen]
        assert abs(min(got) - (before[j] - 100)) <= half_count + 1
        assert abs(max(got) - (before[j] + 100)) <= half_count + 1
    assert mode == "sitting" and after == before


def test_servo_sweep_refused_by_a_calibrated_range_goes_back(rt):
    p, r1, lines, pulses, mode = rt.call("scenarios.selftest:sweep_refused")
    assert r1 == ["ok leg 2 joint femur centre_us 1500 ref_deg 0.00 trim 0 dir 1 min_us 600 max_us %d" % (p + 50)]
    assert lines[0].startswith("ok servo 2 coxa swept ")
    # 50 us of room is 5 degrees; the first step past it (5.2 degrees, 13 steps of 0.4) is refused
    assert lines[1].startswith("err servo 2 femur: refused at ")
    assert "the pulse would be 2 us above its calibrated 600..%d us); it went back to " % (p + 50) in lines[1]
    assert lines[2].startswith("ok servo 2 tibia swept ")
    assert lines[3] == "err selftest servos 2: 3 joints swept, 1 failed"
    assert pulses[1] == p


def test_a_new_line_cuts_a_sweep_short_with_its_end_line_first(rt):
    replies, mode = rt.call("scenarios.selftest:sweep_cut_short")
    assert replies[0] == (
        "err selftest servos 3: cut short by a new line during the coxa; the leg stays where it is "
        "('sit' brings it home)"
    )
    assert replies[1].startswith("ok leg 3 angles ") and mode == "jog"


def test_firmware_version_matches_the_package():
    from hexapod import VERSION

    with open(os.path.join(ROOT, "pyproject.toml"), "rb") as f:
        assert tomllib.load(f)["project"]["version"] == VERSION


# -- the host: link and doctor ----------------------------------------------------------------

RECORDED = [
    "ok board pico robot default",
    "ok version 0.1.0",
    "err i2c found 0x40, missing 0x41: " + HINT_0x41 + " with the Pico?",
    "ok pca9685 0x40 MODE1 0x20 PRE_SCALE 0x79 (50 Hz at osc 25000000 Hz)",
    "err pca9685 0x41: no answer: " + HINT_0x41 + " with the Pico?",
    "ok calibration hexapod_cal.txt crc 1234 (in force: file)",
    "ok reset_cause power_on",
    "ok heap free 150000 bytes",
    "ok supply n/a (no battery monitor configured)",
    "ok sonar front ok 300.0 mm",
    "ok sonar left_front ok 400.1 mm",
    "err sonar left_rear no_echo: the echo never rose: module on 5 V? trigger on pin 10, echo on pin 11?",
    "ok sonar right_front ok 600.0 mm",
    "ok sonar right_rear ok 700.1 mm",
    "err selftest 14 checks, 3 failed",
]


class FakePort:
    """A board's lines; its replies (ok/err) come tagged with the request written last, as the
    firmware tags them (docs/console.md)."""

    def __init__(self, lines):
        self.lines = [(x + "\r\n").encode() for x in lines]
        self.written = b""

    def write(self, b):
        self.written += b

    def flush(self):
        pass

    def readline(self):
        if not self.lines:
            return b""
        line = self.lines.pop(0)
        if line.startswith((b"ok", b"err")):
            line = self.written.splitlines()[-1].split(b" ", 1)[0] + b" " + line
        return line

    def close(self):
        pass


def test_link_collects_a_multi_line_reply_up_to_its_end_line():
    port = FakePort(["boot: relaxed", *RECORDED, "ok leg 2 angles 0.00 0.00 0.00 pulses 0 0 0 foot 240.0 0.0 32.0"])
    link = Link(port, timeout=0.5, name="/dev/fake")
    assert link.request_lines("selftest") == RECORDED
    assert link.request("get 2").startswith("ok leg 2 ")  # the next reply is the next request's
    assert link.other == ["boot: relaxed"]
    port = FakePort(["err selftest: 'foo', allowed nothing (the hardware checks) or 'servos L' (leg 1..6)"])
    assert Link(port, timeout=0.5).request("selftest foo").startswith("err selftest: 'foo'")


def test_doctor_report_from_a_recorded_reply():
    data = doctor.parse(RECORDED)
    assert data["board"] == "pico" and data["robot"] == "default" and data["firmware"] == "0.1.0"
    assert data["i2c"] == ["0x40"] and data["failed"] == 3 and not data["passed"]
    text = doctor.report(data, "/dev/ttyACM0", "0.1.0")
    assert text[3:7] == [
        "board:    pico (robot default)",
        "firmware: 0.1.0",
        "i2c:      0x40",
        "result:   14 checks, 3 failed (err selftest 14 checks, 3 failed)",
    ]
    i = text.index("failed checks:")
    assert text[i + 1 : i + 7] == [
        "  i2c found 0x40, missing 0x41",
        "      hint: " + HINT_0x41 + " with the Pico?",
        "  pca9685 0x41 no answer",
        "      hint: " + HINT_0x41 + " with the Pico?",
        "  sonar left_rear no_echo",
        "      hint: the echo never rose: module on 5 V? trigger on pin 10, echo on pin 11?",
    ]
    assert text[-15:] == ["  " + x for x in RECORDED]


@pytest.fixture
def vboard(virtual_board):
    """start() -> pty path of a virtual board with no calibration filesystem (conftest's), its
    link closed: the port is free for the command under test."""

    def start():
        path, link = virtual_board("")
        link.close()
        return path

    return start


def test_doctor_against_the_virtual_board(vboard, capsys):
    path = vboard()
    assert cli.main(["doctor", "--port", path, "--timeout", "10"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[3:7] == [
        "board:    pico (robot default)",
        "firmware: 0.1.0",
        "i2c:      0x40 0x41",
        "result:   15 checks, 0 failed (ok selftest 15 checks, 0 failed)",
    ]
    assert "failed checks:" not in out and out[-1] == "  ok selftest 15 checks, 0 failed"
    with Link.open(path, timeout=10) as link:
        assert link.request("fault unplug 0x41") == "ok fault unplug 0x41"
        assert link.request("fault no_echo 2") == "ok fault no_echo 2"
        # The loop logs the sonar when its next ping is collected (5 frames at most): wait for that
        # outcome itself, not for a time, so the report below is the same on a busy machine.
        for _ in range(200):
            if "sonar left_rear" in link.request("faults"):
                break
    assert cli.main(["doctor", "--port", path, "--timeout", "10", "--json"]) == 1
    data = json.loads(capsys.readouterr().out)
    assert data["i2c"] == ["0x40"] and data["failed"] == 4 and data["board"] == "pico"
    failed = {c["check"]: c["hint"] for c in data["checks"] if not c["ok"]}
    assert sorted(failed) == ["faults", "i2c", "pca9685 0x41", "sonar left_rear"]
    assert failed["faults"] == FIX[2:]
    logged = next(c["detail"] for c in data["checks"] if c["check"] == "faults")
    # the unplugged chip's first failed frame, then the sonar's first lost echo (a later frame)
    assert logged.startswith("2 logged (oldest first) i2c 0x41 frame ") and "; sonar left_rear frame " in logged
    assert failed["pca9685 0x41"] == HINT_0x41 + " with the Pico?"
    assert failed["sonar left_rear"].startswith("the echo never rose: module on 5 V? trigger on pin 10, echo on pin 11")


def test_doctor_usage_and_an_unreachable_port(tmp_path, capsys):
    with pytest.raises(SystemExit) as stop:
        cli.main(["doctor"])
    assert stop.value.code == 2
    with pytest.raises(SystemExit) as stop:
        cli.main(["doctor", "--port", "/dev/null", "--timeout", "0"])
    assert stop.value.code == 2 and "--timeout 0.0: allowed a positive number of seconds" in capsys.readouterr().err
    assert cli.main(["doctor", "--port", str(tmp_path / "ttyNONE")]) == 1
    assert "no such port" in capsys.readouterr().err
