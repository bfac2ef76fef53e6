"""End to end: the firmware loop in the MicroPython VM on a pseudo-terminal (hexapod
virtual-board), talked to through pyserial (hexapod_host.serial.link, `hexapod send`)."""

import os
import pty
import signal
import subprocess
import sys
import time
import tty

import pytest

from hexapod_host.commands import cli
from hexapod_host.serial.link import Link, LinkError
from hexapod_host.testing import reference
from hexapod_host.testing.runtimes import micropython_missing

LEG = dict(coxa=30.0, femur=85.0, tibia=125.0, femur_offset=32.0)
HALF_COUNT_US = 20000 / 4096 / 2  # the PCA9685 at 50 Hz: 4.88 us a count


@pytest.fixture
def board(tmp_path, virtual_board):
    """start(cal_dir=a temporary folder) -> (pty path, link): conftest's virtual_board."""
    return lambda cal_dir=str(tmp_path): virtual_board(cal_dir)


def model(link):
    words = link.request("model").split()
    assert words[:3] == ["ok", "model", "0x40"] and words[19] == "0x41"
    return [int(w) for w in words[3:19]] + [int(w) for w in words[20:36]]


def test_jogging_leg_2_moves_exactly_its_three_channels_by_what_ik_predicts(board):
    path, link = board()
    before = model(link)
    for line, point in (("foot 2 140 10 -70", (140, 10, -70)), ("nudge 2 -5 0 7.5", (135, 10, -62.5))):
        reply = link.request(line)
        assert reply.startswith("ok leg 2 angles "), reply
        time.sleep(0.1)  # a few frames
        after = model(link)
        changed = [k for k in range(32) if after[k] != before[k]]
        assert set(changed) <= {3, 4, 5} and changed  # pico.py: leg 2 is chip 0x40 channels 3, 4, 5
        t = reference.ik(*point, **LEG)
        want = (1500 + 10 * t[0], 1500 + 10 * t[1], 2400 + 10 * t[2])  # pico.py leg 2 rows, 10 us/deg
        for ch, w in zip((3, 4, 5), want, strict=True):
            # the model's whole us: half a count, the us rounding, 0.01 deg of the fixed-point IK
            assert abs(after[ch] - w) <= HALF_COUNT_US + 0.5 + 0.1, (line, ch, after[ch], w)
        before = after
    link.close()


def test_send_prints_replies_and_exits_1_on_err(board, capsys):
    path, link = board()
    link.close()
    assert cli.main(["send", "--port", path, "get 2", "foot 2 130 0 -80"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0] == "ok leg 2 angles 0.00 0.00 0.00 pulses 0 0 0 foot 240.0 0.0 32.0"
    assert out[1].startswith("ok leg 2 angles 0.00 8.11 -90.83 pulses 1500 1581 1492")
    assert cli.main(["send", "--port", path, "foot 2 400 0 0", "get 2"]) == 1
    out = capsys.readouterr().out.splitlines()
    assert out[0].startswith("err foot: too far: ") and out[1].startswith("ok leg 2 ")
    assert " pulses 1500 1581 1492 " in out[1]  # the refused foot moved nothing


def test_send_names_a_missing_port_and_a_silent_one(capsys, tmp_path):
    with pytest.raises(SystemExit) as stop:  # bad input, as for `hexapod jog`: exit 2
        cli.main(["send", "--port", str(tmp_path / "ttyNONE"), "status"])
    assert stop.value.code == 2
    assert capsys.readouterr().err == "hexapod: error: no such port '%s' (hexapod ports lists them)\n" % (
        tmp_path / "ttyNONE"
    )
    master, slave = pty.openpty()  # a line with nobody answering
    tty.setraw(slave)
    try:
        assert cli.main(["send", "--port", os.ttyname(slave), "--timeout", "0.3", "status"]) == 1
        err = capsys.readouterr().err
        assert "no answer to 'status' from " in err and "within 0.3 s: is the hexapod firmware running?" in err
    finally:
        os.close(master)
        os.close(slave)


def test_calibration_survives_a_restart_through_the_vms_filesystem(board, tmp_path):
    path, link = board()
    assert link.request("trim 2 femur -40").endswith("trim -40 dir 1 min_us 600 max_us 2400")
    assert link.request("range 2 tibia 700 2350").endswith("min_us 700 max_us 2350")
    assert link.request("save").startswith("ok saved hexapod_cal.txt crc ")
    assert sorted(os.listdir(tmp_path)) == ["hexapod_cal.txt"]
    link.close()
    path2, link2 = board()
    assert link2.request("cal 2 femur") == (
        "ok leg 2 joint femur centre_us 1500 ref_deg 0.00 trim -40 dir 1 min_us 600 max_us 2400"
    )
    assert link2.request("cal 2 tibia").endswith("min_us 700 max_us 2350")
    assert " cal file boot " in link2.request("status")
    (tmp_path / "hexapod_cal.txt").write_text("hexapod-cal 1\ngarbage\n")
    link2.close()
    _, link3 = board()
    assert link3.request("cal 2 femur").endswith("trim 0 dir 1 min_us 600 max_us 2400")
    assert "cal: hexapod_cal.txt truncated (no checksum line); the robot file's calibration is in use" in link3.other
    link3.close()


def test_virtual_board_command_prints_its_path_first_and_stops_on_sigterm(tmp_path):
    if micropython_missing():
        pytest.skip(micropython_missing())
    exe = os.path.join(os.path.dirname(sys.executable), "hexapod")
    proc = subprocess.Popen(
        [exe, "virtual-board", "--cal-dir", str(tmp_path)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    try:
        path = proc.stdout.readline().strip()
        assert path.startswith("/dev/pts/")
        with Link.open(path, timeout=10) as link:
            assert link.request("status").startswith("ok frames ")
            proc.send_signal(signal.SIGTERM)
            assert proc.wait(10) == 0
            # The board's side of the pty went with it: the open link hangs up. (Not a reopen of
            # the path: another test's new pty may take its number at once, and a CI run did.)
            with pytest.raises(LinkError, match="lost the board"):
                link.request("status")
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()


def status_of(link):
    words = link.request("status").split()
    return dict(zip(words[1::2], words[2::2], strict=False))


def test_a_walk_not_renewed_stops_in_real_time(board):
    # On the board's own clock, with no bound on the host's timing (the machine may be busy): the
    # deadlines below only stop a hang. The stub clock's tests pin the timeout to the frame.
    path, link = board()
    assert link.request("stand") == "ok mode moving"
    deadline = time.monotonic() + 15
    while status_of(link)["mode"] != "standing":
        assert time.monotonic() < deadline
        time.sleep(0.1)
    for _ in range(4):  # each renewal answers with the full timeout
        assert link.request("walk 60 0 0") == "ok walk 60.0 0.0 0.00 timeout_ms 1000"
    left = []
    deadline = time.monotonic() + 15
    while not left or left[-1] != 0:  # counts down on its own to 0, never past the timeout
        st = status_of(link)
        assert st["mode"] == "walking" or st["walk_ms"] == "0", st
        left.append(int(st["walk_ms"]))
        assert time.monotonic() < deadline
        time.sleep(0.02)
    assert left == sorted(left, reverse=True) and left[0] <= 1000, left
    deadline = time.monotonic() + 5
    while status_of(link)["mode"] != "standing":  # the steps under way finish, the feet land
        assert time.monotonic() < deadline
        time.sleep(0.05)


def test_echo_on_a_terminal(board):
    """A person in `screen`: after `echo on` the board sends back what is typed, a backspace
    as \\b \\b, the line end as \\r\\n, then the reply; the link still finds its replies."""
    path, link = board()
    assert link.request("echo on") == "ok echo on"
    link.port.write(b"get 1\x7f2\r")
    link.port.flush()
    deadline = time.monotonic() + 10
    raw = b""
    while raw.count(b"\n") < 2 and time.monotonic() < deadline:
        raw += link.port.read(256)
    echoed, reply = raw.split(b"\r\n", 1)
    assert echoed == b"get 1\b \b2"
    assert reply.strip().startswith(b"ok leg 2 angles ")
    assert link.request("get 3").startswith("ok leg 3 ")  # the echoed line goes to link.other
    assert link.other[-1].endswith(" get 3")  # '#N get 3': the echoed request, tag and all
    assert link.request("echo off") == "ok echo off"
    link.close()
