"""hexapod view's board source and driving without a browser or a board: hand-written telemetry
lines (the format of /work/notes/telemetry-spec.md) and replies through a fake serial line, the
snapshot they make against a hand-worked case, replies paired with their tags among telemetry
lines, and the Driver's lines for keys, stick, buttons, the deadman and the one driving tab.
The page on the real virtual board: tests/test_view_drive_browser.py."""

import contextlib
import queue
import re
import time

import pytest

from hexapod_host.view.board import BoardSource
from hexapod_host.view.board_link import BoardLink
from hexapod_host.view.drive import Driver, NotOwner

# tests/test_view.py's hand-worked pulses on boards/pico.py: legs 1 (RF) and 5 (LM) at coxa 0,
# femur +30, tibia -120 degrees (the tibia straight down), the other four straight out.
PULSES = [1500, 1800, 1200] + [1500, 1500, 2400] * 2 + [1500, 1500, 600] + [1500, 1200, 1800] + [1500, 1500, 600]
# frame 1234, walking (4), tetrapod (1), phase 7, following (1) the left wall (1), walk 80 mm/s
# forward (0.1 mm/s) turning 5 deg/s (cdeg/s); the pulses; front no echo, the left pair 123.4 and
# 120.0 mm, right front out of range, right rear waiting; wall error -3.5 mm, output 12.5 deg/s;
# no battery; held 0, overruns 2, bus_failed 1, sonar_faults 3.
LINE = "~T 1234 4 1 7 1 1 800 0 500 %s - 1234 1200 - - 2 0 0 1 5 -35 1250 - 0 2 1 3" % " ".join(map(str, PULSES))


class FakePort:
    """A serial line to a pretend board: answers each tagged request with replies[command]
    (default 'ok'), and lets a test put any line on it (put)."""

    def __init__(self, replies=None):
        self.replies = replies or {}
        self.after = {}
        self.written = []
        self.lines = queue.Queue()
        self.closed = False

    def write(self, data):
        text = data.decode()
        self.written.append(text)
        tag, _, line = text.strip().partition(" ")
        self.put("%s %s" % (tag, self.replies.get(line, "ok")))
        for more in self.after.get(line, ()):  # a multi-line reply's other lines
            self.put("%s %s" % (tag, more))

    def flush(self):
        pass

    def put(self, line):
        self.lines.put((line + "\n").encode())

    def readline(self):
        try:
            return self.lines.get(timeout=0.01)
        except queue.Empty:
            return b""

    def close(self):
        self.closed = True


@contextlib.contextmanager
def source(replies=None, port=None):
    """(a board source on a fake line, the line) for a with block, closed after it: the line is
    port, or one answering replies (`stream on 25` with ok unless replies say otherwise)."""
    port = port or FakePort({"stream on 25": "ok stream 25", **(replies or {})})
    src = BoardSource(BoardLink(port, "fake").start(), "pico")
    try:
        yield src, port
    finally:
        src.close()


def test_stream_on_25_is_asked_first_and_its_reply_kept():
    with source() as (src, port):
        assert re.fullmatch(r"#\d+ stream on 25\n", port.written[0])
        assert src.stream_reply == "ok stream 25"
    assert port.closed


def _until(cond, timeout=10.0):
    # The link's reader thread takes the fake port's lines: wait for it, not for a time.
    end = time.monotonic() + timeout
    while not cond() and time.monotonic() < end:
        time.sleep(0.005)
    return cond()


def test_a_board_that_powers_up_again_is_asked_for_its_stream_and_maps_again():
    with source() as (src, port):
        asked = [w.split(" ", 1)[1].strip() for w in port.written]
        # the fake answers `cal 1 coxa` with a bare ok: the reading stops there (test_view_boardcal)
        assert asked == ["stream on 25", "selftest", "cal 1 coxa"]
        src.step()  # no power-up line: nothing asked
        assert len(port.written) == 3 and src.restarts == 0
        port.put("hello")  # a notice that is not a power-up line
        port.put("boot: relaxed, no pulse until `stand` (the board file's boot setting)")
        assert _until(lambda: src.link.boots == 1)
        src.step()
        again = [w.split(" ", 1)[1].strip() for w in port.written[3:]]
        assert again == ["stream on 25"] + [
            "cal %d %s" % (k // 3 + 1, j) for k, j in enumerate(["coxa", "femur", "tibia"] * 6)
        ]
        assert src.restarts == 1
        assert _until(lambda: (src.step(), src.stream_reply)[1] == "ok stream 25 (again, after power-up 1)")
        n = len(port.written)
        src.step()
        src.step()
        assert len(port.written) == n  # asked once per power-up line
        assert src.snapshot()["extra"]["stream"] == "ok stream 25 (again, after power-up 1)"


def test_a_board_without_the_stream_command_still_serves_a_resting_robot():
    with source({"stream on 25": "err unknown command 'stream' (help lists them)"}) as (src, _):
        s = src.snapshot()
        assert s["extra"]["stream"].startswith("err unknown command 'stream'")
        assert s["frame"] == 0 and s["mode"] == "-"
        assert s["pulses"] == [0] * 18
        assert s["angles"] == [0, 0, -9000] * 6  # limp joints drawn at their reference angles
        assert s["distances"] == [None] * 5


def test_the_board_is_what_its_selftest_says():
    # selftest's first line names the board (docs/console.md); the rest of its lines come later
    port = FakePort({"stream on 25": "ok stream 25", "selftest": "ok board esp32_devkit robot default"})
    port.after = {"selftest": ["ok version 0.1.0", "ok selftest 14 checks, 0 failed"]}
    with source(port=port) as (src, _):
        assert [w.split(" ", 1)[1] for w in port.written[:2]] == ["stream on 25\n", "selftest\n"]
        assert src.board == "esp32_devkit"  # drawn through its own board file, not pico's
        d = src.describe()
        assert (d["board"], d["board_said"]) == ("esp32_devkit", "board esp32_devkit, robot default")
        assert src.snapshot()["extra"]["board"] == "board esp32_devkit, robot default"


def test_a_board_this_host_has_no_file_for_is_named_and_drawn_as_pico():
    with source({"selftest": "ok board hexbot9 robot big"}) as (src, _):
        assert src.board == "pico"
        assert src.board_text() == "board hexbot9, robot big, drawn with boards/pico.py"


def test_firmware_without_selftest_leaves_the_board_unknown():
    with source({"selftest": "err unknown command 'selftest' (help lists them)"}) as (src, _):
        assert src.board == "pico"
        assert src.describe()["board_said"] == (
            "board unknown ('selftest' answered \"err unknown command 'selftest' (help lists them)\")"
        )


def wait(predicate, n=500):
    """predicate() true within n tries of the fake line's 10 ms read (the reader thread's pace)."""
    for _ in range(n):
        if predicate():
            return True
        time.sleep(0.01)
    return False


def test_a_telemetry_line_as_the_snapshot():
    with source({"wall left 12": "ok wall left setpoint 12.00"}) as (src, port):
        tag = src.command("wall left 12")  # telemetry has no set point: the reply gives it
        assert wait(lambda: src.reply(tag) is not None)
        port.put(LINE)
        assert wait(lambda: src.link.telemetry_lines == 1)
        s = src.snapshot()
        assert s["frame"] == 1234 and s["time_s"] == 24.68
        assert s["pulses"] == PULSES
        assert s["angles"][0:3] == [0, 3000, -12000]  # leg 1: 1500, 1800, 1200 us
        assert s["angles"][12:15] == [0, 3000, -12000]  # leg 5, mirrored: 1500, 1200, 1800 us
        assert s["angles"][3:6] == [0, 0, 0]
        assert s["stance"] == [True, False, False, False, True, False]  # the two tibias straight down
        # Robots/default.py: femur joint 32 mm above the coxa plane, knee 85 sin 30 = 42.5 mm above
        # that, tibia 125 mm: the foot 50.5 mm below the coxa plane.
        assert s["body"]["z"] == pytest.approx(50.5, abs=1e-6)
        assert s["distances"] == [None, 123.4, 120.0, None, None]
        assert s["sonar_status"] == ["no_echo", "ok", "ok", "out_of_range", "wait"]
        assert s["mode"] == "walking"
        f = s["follow"]
        assert (f["mode"], f["side"], f["error_mm"], f["output_dps"]) == ("following", "left", -3.5, 12.5)
        assert f["setpoint_mm"] == 120.0
        assert s["counters"] == {"frames": 1234, "held": 0, "overruns": 2, "bus_failed": 1, "sonar_faults": 3}
        x = s["extra"]
        assert (x["gait"], x["phase"], x["walk"], x["battery_mv"]) == ("tetrapod", 7, [80.0, 0.0, 5.0], None)
        assert (x["frame_us"], x["frame_us_max"]) == (None, None)  # a line from before the frame times
        port.put(LINE.replace("~T 1234", "~T 1236") + " 3395 4431")  # the firmware's frame times, us
        assert wait(lambda: src.link.telemetry_lines == 2)
        x = src.snapshot()["extra"]
        assert (x["frame_us"], x["frame_us_max"]) == (3395, 4431)


def test_replies_pair_with_their_tags_among_telemetry_lines():
    port = FakePort()
    link = BoardLink(port, "fake", first_tag=41)
    for line in (LINE, "#41 working", LINE.replace("~T 1234", "~T 1236"), "held: leg 2: too far", "#7 ok late"):
        link.feed(line)
    link.feed("~T 1238 4 1")  # cut short: refused, the last good line kept
    link.feed("#41 ok gait tetrapod")
    assert link.reply("#41") == "ok gait tetrapod"
    assert link.reply("#7") == "ok late"  # another request's: kept under its own tag
    assert link.reply("#42") is None
    assert link.telemetry["frame"] == 1236 and link.telemetry_lines == 2
    assert link.malformed == 1 and "telemetry field 4 (phase): missing (3 of 46 fields" in link.last_error
    assert list(link.notices) == ["held: leg 2: too far"]


def test_a_line_the_board_would_refuse_is_not_sent():
    port = FakePort()
    link = BoardLink(port, "fake")
    with pytest.raises(ValueError, match="non-text character"):
        link.send("walk 80 0 0\x03")
    assert port.written == []


class Recorder:
    """A drivable source that keeps the lines it is given."""

    drivable = True

    def __init__(self):
        self.lines = []

    def command(self, line):
        self.lines.append(line)
        return "#%d" % len(self.lines)

    def reply(self, tag):
        return None


def driving_tab1():
    """(recorder, driver): a Driver on a Recorder, the drive claimed by tab1."""
    src = Recorder()
    d = Driver(src)
    assert d.claim("tab1")
    return src, d


def test_keys_walk_add_up_and_the_last_one_let_go_stops():
    src, d = driving_tab1()
    d.key("tab1", "w", True)
    d.key("tab1", "a", True)
    d.key("tab1", "w", True)  # a repeat changes nothing
    d.key("tab1", "w", False)
    d.key("tab1", "q", True)
    d.key("tab1", "a", False)
    d.key("tab1", "q", False)
    assert src.lines == ["walk 80 0 0", "walk 80 80 0", "walk 0 80 0", "walk 0 80 20", "walk 0 0 20", "stop"]


def test_held_renews_the_walk_and_let_go_does_not():
    src, d = driving_tab1()
    d.renew()  # nothing held: nothing sent
    d.key("tab1", "s", True)
    d.renew()
    d.renew()
    d.key("tab1", "s", False)
    d.renew()
    assert src.lines == ["walk -80 0 0"] * 3 + ["stop"]


def test_space_stops_at_once_and_the_stick_turns():
    src, d = driving_tab1()
    d.key("tab1", "d", True)
    d.key("tab1", " ", True)
    d.renew()  # the space let go of D too
    d.stick_move("tab1", 0.5, 1.0)  # up and half right: forward, turning right at half the rate
    d.stick_move("tab1", 0.0, -2.0)  # clamped to -1
    d.stick_move("tab1", None, None)
    assert src.lines == ["walk 0 -80 0", "stop", "walk 80 0 -10", "walk -80 0 0", "stop"]


def test_losing_the_keyboard_lets_go_of_the_keys():
    src, d = driving_tab1()
    d.key("tab1", "w", True)
    d.key("tab1", "q", True)
    d.let_go("tab1")  # the window lost focus: no keyup will come for W or Q
    d.renew()
    d.let_go("tab1")  # nothing held: nothing more sent
    assert src.lines == ["walk 80 0 0", "walk 80 0 20", "stop"]
    assert d.owner == "tab1"  # still this tab's to drive


def test_only_the_owning_tab_drives_and_its_going_stops_the_robot():
    src = Recorder()
    d = Driver(src)
    assert d.claim("tab1") and not d.claim("tab2")
    d.key("tab1", "w", True)
    for act in (
        lambda: d.key("tab2", "w", True),
        lambda: d.key("tab2", " ", True),
        lambda: d.command("tab2", "stand"),
        lambda: d.stick_move("tab2", 0, 1),
        lambda: d.wall("tab2", "left", 12),
        lambda: d.height("tab2", 70),
    ):
        with pytest.raises(NotOwner, match="another tab drives; this one is view-only"):
            act()
    d.release("tab2")  # not the owner: changes nothing
    assert d.owner == "tab1" and src.lines == ["walk 80 0 0"]
    d.release("tab1")  # its tab closed or lost its connection, W still down
    assert src.lines == ["walk 80 0 0", "stop"]
    d.renew()
    assert src.lines[-1] == "stop" and d.owner is None
    # The gone tab's panel still refreshes until the server forgets it: it does not take the drive
    # back (a reloaded page is a new tab, which then would be view-only for RECONNECT_S).
    assert not d.claim("tab1", connected=False) and d.owner is None
    assert d.claim("tab2") and not d.claim("tab1")


def test_buttons_gait_and_wall_following():
    src = Recorder()
    d = Driver(src)
    d.claim("t")
    d.command("t", "stand")
    d.command("t", "gait ripple")
    d.wall("t", "right", 12.5)
    d.wall("t", None, None)
    for side, cm, why in (("up", 12, "side 'up': allowed left, right"), ("left", 3.9, "allowed 4..50")):
        with pytest.raises(ValueError, match=re.escape(why)):
            d.wall("t", side, cm)
    assert src.lines == ["stand", "gait ripple", "wall right 12.50", "wall off"]


def test_the_height_control_sends_the_consoles_height_within_the_robot_files_range():
    src = Recorder()
    d = Driver(src)
    d.claim("t")
    assert d.heights_mm == (60.0, 100.0)  # robots/default.py: BODY_HEIGHT_MIN 600, _MAX 1000 (0.1 mm)
    d.height("t", 60)
    d.height("t", 100.0)
    d.height("t", 72.25)  # the console takes tenths: rounded half to even by %.1f
    for bad in (59.9, 100.01, -80, None, "70", True, float("nan"), float("inf")):
        with pytest.raises(ValueError, match=re.escape("mm: allowed 60..100 (the robot file's range)")):
            d.height("t", bad)
    assert src.lines == ["height 60.0", "height 100.0", "height 72.2"]


def test_a_source_that_cannot_be_driven_refuses_every_tab():
    class Sim:
        drivable = False

    d = Driver(Sim())
    assert not d.claim("tab1")
    with pytest.raises(NotOwner, match="this source cannot be driven"):
        d.key("tab1", "w", True)
