"""hexapod_host.serial.telemetry.parse against lines written by hand (docs/console.md "Telemetry"),
malformed lines refused naming their field, and Link skipping `~` lines while it waits for a reply."""

import pytest

from hexapod_host.serial import telemetry
from hexapod_host.serial.link import Link

# A standing robot (docs/console.md's example), and a walking, wall-following one with a battery,
# a faulted sonar and a held frame: written by hand, field by field.
# The frame times last: 2870 us the frame before the line, 3120 us the most since the line before.
OLD_STANDING = (
    "~T 153 3 0 0 0 0 0 0 0 1500 1581 1492 1500 1581 1492 1500 1581 1492 1500 1419 1508 1500 1419 1508 "
    "1500 1419 1508 3000 4001 5000 6000 7001 0 0 0 0 0 0 0 - 0 0 0 0\n"
)
STANDING = OLD_STANDING.replace("\n", " 2870 3120\n")
WALKING = (
    "~T 9001 4 2 17 1 1 1200 -300 -1500 1490 1600 1400 1510 1620 1380 1500 1590 1410 1505 1415 1590 "
    "1495 1400 1600 1500 1420 1580 - 812 795 - 6000 2 0 0 1 0 -17 -352 7410 1 3 0 12 21004 23950\r\n"
)


def test_a_standing_line():
    t = telemetry.parse(STANDING)
    assert t == {
        "frame": 153,
        "mode": 3,
        "gait": 0,
        "phase": 0,
        "follow_mode": 0,
        "follow_side": 0,
        "vx": 0,
        "vy": 0,
        "yaw": 0,
        "pulses": [1500, 1581, 1492] * 3 + [1500, 1419, 1508] * 3,
        "distances": [3000, 4001, 5000, 6000, 7001],
        "sonar_status": [0, 0, 0, 0, 0],
        "wall_error": 0,
        "wall_out": 0,
        "battery_mv": None,
        "held": 0,
        "overruns": 0,
        "bus_failed": 0,
        "sonar_faults": 0,
        "frame_us": 2870,
        "frame_us_max": 3120,
    }
    assert telemetry.parse(STANDING.encode()) == t  # bytes from a port too
    assert telemetry.COUNT == 46 and len(telemetry.NAMES) == 46


def test_a_line_from_firmware_before_the_frame_times():
    t = telemetry.parse(OLD_STANDING)  # 44 fields: read, the frame times None
    assert (t["frame"], t["pulses"][1], t["sonar_faults"]) == (153, 1581, 0)
    assert (t["frame_us"], t["frame_us_max"]) == (None, None)


def test_a_walking_line_with_negatives_dashes_and_crlf():
    t = telemetry.parse(WALKING)
    assert (t["frame"], t["mode"], t["gait"], t["phase"]) == (9001, 4, 2, 17)
    assert (t["follow_mode"], t["follow_side"], t["vx"], t["vy"], t["yaw"]) == (1, 1, 1200, -300, -1500)
    assert t["pulses"][9:12] == [1505, 1415, 1590]
    assert t["distances"] == [None, 812, 795, None, 6000]
    assert t["sonar_status"] == [2, 0, 0, 1, 0]
    assert (t["wall_error"], t["wall_out"], t["battery_mv"]) == (-17, -352, 7410)
    assert (t["held"], t["overruns"], t["bus_failed"], t["sonar_faults"]) == (1, 3, 0, 12)
    assert (t["frame_us"], t["frame_us_max"]) == (21004, 23950)  # an overrun's frame


def _swap(line, k, word):
    """line with its field k (1-based after '~T') replaced by word."""
    words = line.rstrip("\n").split(" ")
    words[k] = word
    return " ".join(words) + "\n"


BAD = [
    ("", "prefix"),
    ("ok stream 25\n", "prefix"),
    ("~X 1 2\n", "prefix"),
    ("~T\n", "prefix"),
    (STANDING.replace("~T ", "~T  ", 1), r"field 1 \(frame\)"),
    (OLD_STANDING.replace(" 0 0 0 0\n", " 0 0 0\n"), r"field 44 \(sonar_faults\): missing \(43 of 46"),
    (STANDING.replace(" 3120\n", "\n"), r"field 46 \(frame_us_max\): missing \(45 of 46 fields, or 44 from older"),
    (STANDING[: STANDING.index(" 1500")] + "\n", r"field 10 \(pulses\[0\]\): missing"),
    (STANDING.replace("\n", " 5\n"), r"47 fields, expected 46 \(extra after frame_us_max\)"),
    (_swap(STANDING, 1, "x"), r"field 1 \(frame\): 'x' is not a decimal integer"),
    (_swap(STANDING, 1, "-"), r"field 1 \(frame\): '-', allowed only an integer"),
    (_swap(STANDING, 1, "-5"), r"field 1 \(frame\): -5 is outside 0\.\."),
    (_swap(STANDING, 2, "6"), r"field 2 \(mode\): 6 is outside 0\.\.5"),
    (_swap(STANDING, 3, "4"), r"field 3 \(gait\): 4 is outside 0\.\.3"),
    (_swap(STANDING, 5, "7"), r"field 5 \(follow_mode\): 7 is outside 0\.\.6"),
    (_swap(STANDING, 6, "3"), r"field 6 \(follow_side\): 3 is outside 0\.\.2"),
    (_swap(STANDING, 7, "1.5"), r"field 7 \(vx\): '1\.5' is not a decimal integer"),
    (_swap(STANDING, 9, "+3"), r"field 9 \(yaw\): '\+3' is not a decimal integer"),
    (_swap(STANDING, 12, "2501"), r"field 12 \(pulses\[2\]\): 2501 is outside 0\.\.2500"),
    (_swap(STANDING, 27, "0x5dc"), r"field 27 \(pulses\[17\]\): '0x5dc' is not a decimal integer"),
    (_swap(STANDING, 28, "-"), r"field 28 \(distances\[0\]\): - with sonar_status 0"),
    (_swap(STANDING, 33, "2"), r"field 28 \(distances\[0\]\): 3000 with sonar_status 2"),
    (_swap(STANDING, 37, "7"), r"field 37 \(sonar_status\[4\]\): 7 is outside 0\.\.6"),
    (_swap(STANDING, 38, "--1"), r"field 38 \(wall_error\): '--1' is not a decimal integer"),
    (_swap(STANDING, 39, "1e3"), r"field 39 \(wall_out\): '1e3' is not a decimal integer"),
    (_swap(STANDING, 40, "-7"), r"field 40 \(battery_mv\): -7 is outside 0\.\."),
    (_swap(STANDING, 41, "-"), r"field 41 \(held\): '-', allowed only an integer"),
    (_swap(STANDING, 42, "007"), r"field 42 \(overruns\): '007' is not a decimal integer"),
    (_swap(STANDING, 43, "\u0663"), r"field 43 \(bus_failed\): .* is not a decimal integer"),
    (_swap(STANDING, 44, ""), r"field 44 \(sonar_faults\): '' is not a decimal integer"),
    (_swap(STANDING, 45, "-"), r"field 45 \(frame_us\): '-', allowed only an integer"),
    (_swap(STANDING, 46, "-3"), r"field 46 \(frame_us_max\): -3 is outside 0\.\."),
    (STANDING.encode().replace(b"153", b"1\xff3"), "not ASCII"),
]


@pytest.mark.parametrize(("line", "why"), BAD)
def test_a_malformed_line_is_refused_naming_its_field(line, why):
    with pytest.raises(ValueError, match=why):
        telemetry.parse(line)


class FakePort:
    """A board streaming: `~T` lines arrive before, around and inside the reply's wait."""

    def __init__(self, reply_after):
        self.out = []
        self.reply_after = reply_after
        self.lines = []

    def write(self, data):
        self.out.append(data)
        tag = data.split()[0]
        self.lines = [STANDING.encode()] * self.reply_after + [tag + b" ok frames 1\r\n", WALKING.encode()]

    def flush(self):
        pass

    def readline(self):
        return self.lines.pop(0) if self.lines else b""

    def close(self):
        pass


def test_link_skips_telemetry_and_keeps_none_of_it():
    port = FakePort(reply_after=30)
    link = Link(port, timeout=2, name="fake", first_tag=5)
    assert link.request("status") == "ok frames 1"
    assert link.other == [] and link.late == []
    assert port.out == [b"#5 status\n"]


def test_send_and_doctor_get_their_replies_from_a_board_streaming_at_25_hz(virtual_board, capsys):
    import json
    import time

    from hexapod_host.commands import cli

    path, link = virtual_board("")
    assert link.request("stream on 25") == "ok stream 25"
    # the board's own lines: ~T ... every second frame (25 a second), each parses; read until five
    # came (the deadline only stops a hang: the host's timing is not what is tested)
    end = time.monotonic() + 60
    raw = b""
    lines = []
    while len(lines) < 5:
        assert time.monotonic() < end, raw[:300]
        raw += link.port.read(4096)
        lines = [x for x in raw.split(b"\n")[1:-1] if x.startswith(b"~")]
    for x in lines:
        t = telemetry.parse(x)
        assert t["mode"] == 0 and t["pulses"] == [0] * 18
    assert link.request("status").startswith("ok frames ")
    assert not [x for x in link.other if x.startswith("~")]
    link.close()
    assert cli.main(["send", "--port", path, "status", "get 2"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0].startswith("ok frames ") and out[1].startswith("ok leg 2 angles 0.00 "), out
    assert cli.main(["doctor", "--port", path, "--json"]) in (0, 1)
    report = json.loads(capsys.readouterr().out)
    assert "~" not in json.dumps(report)
    with Link.open(path, timeout=10) as again:
        words = again.request("stream").split()
        assert words[:3] == ["ok", "stream", "25"] and int(words[4]) >= len(lines), words  # counted as sent
