"""Issue 21 items 1-6 on the virtual board (`hexapod virtual-board`, the firmware loop in the
MicroPython VM on a pty), end to end through pyserial and the CLI: Ctrl-C stops the loop as on
MicroPython and the jog prompt never sends it; replies paired with requests; a clean line before
each request; the port held exclusively; an empty request refused; nothing left behind when the
virtual board is killed or hung up on. tests/test_pico_link.py does the same on the emulated Pico."""

import os
import pty
import signal
import subprocess
import sys
import time
import tty

import pytest

from hexapod_host.commands import cli
from hexapod_host.commands import console as console_cmd
from hexapod_host.serial import jog
from hexapod_host.serial.link import Link, LinkError, PortBusy
from hexapod_host.testing.runtimes import micropython_missing


@pytest.fixture
def board(virtual_board):
    """start() -> (pty path, link): a virtual board with no calibration filesystem (conftest's)."""
    return lambda: virtual_board("")


def status_of(link):
    words = link.request("status").split()
    return dict(zip(words[1::2], words[2::2], strict=False))


def model(link):
    words = link.request("model").split()
    return [int(w) for w in words[3:19] + words[20:36]]


def standing(link):
    assert link.request("stand") == "ok mode moving"
    end = time.monotonic() + 20
    while status_of(link)["mode"] != "standing":
        assert time.monotonic() < end
        time.sleep(0.1)


def read_until(port, text, timeout=10.0):
    end = time.monotonic() + timeout
    raw = b""
    while text not in raw and time.monotonic() < end:
        raw += port.read(256)
    return raw


def test_ctrl_c_stops_the_loop_as_on_micropython_and_the_jog_prompt_never_sends_it(board):
    path, link = board()
    standing(link)
    # The jog tool's ':' line with Ctrl-C or Esc in it: refused, nothing sent, the robot stands.
    tool = jog.Jog(link, LinkError)
    for typed in ("\x03", "status\x03", "stand\x1b"):
        tool.line(typed)
        assert tool.view.error and tool.view.message.startswith("not sent: the line holds the control character")
    with pytest.raises(LinkError, match="non-text character 0x03"):
        link.request("\x03")
    assert status_of(link)["mode"] == "standing" and all(model(link)[k] for k in range(3))
    # What that byte would have done (MicroPython's KeyboardInterrupt): the loop leaves, every servo
    # goes limp, the board sits at its REPL.
    link.port.write(b"\x03")
    raw = read_until(link.port, b">>> ")
    assert b"stopped: servos relaxed; runner.run() resumes" in raw and raw.endswith(b">>> "), raw
    with pytest.raises(LinkError, match="the board is at the REPL"):
        Link(link.port, timeout=0.5, name=path).request("status")
    link.port.write(b"runner.run()\r")
    read_until(link.port, b"\n")
    assert model(link) == [0] * 32  # every PCA9685 channel off: the robot dropped
    assert status_of(link)["mode"] == "relaxed"


def test_a_late_reply_is_not_the_next_requests(board, capsys):
    path, link = board()
    # A request whose client gave up (a timed-out `send 'gait wave'`): its reply comes late.
    link.port.write(b"#5 gait wave\n")
    link.close()
    time.sleep(0.2)  # a few frames: the late reply waits in the pty
    assert cli.main(["send", "--port", path, "status", "gait"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0].startswith("ok frames ") and out[1] == "ok gait wave", out


def test_half_typed_input_does_not_corrupt_the_next_request(board, capsys):
    path, link = board()
    link.close()
    fd = os.open(path, os.O_WRONLY | os.O_NOCTTY)
    os.write(fd, b"walk 100 0 0")  # typed in another terminal, no Enter
    os.close(fd)
    assert cli.main(["send", "--port", path, "status"]) == 0
    words = capsys.readouterr().out.split()
    assert words[:2] == ["ok", "frames"] and words[words.index("mode") + 1] == "relaxed"
    fd = os.open(path, os.O_WRONLY | os.O_NOCTTY)
    os.write(fd, b"\x01\x01import os\x04")  # a raw-REPL tool's bytes (hexapod flash pointed here)
    os.close(fd)
    assert cli.main(["send", "--port", path, "get 2"]) == 0
    assert capsys.readouterr().out == "ok leg 2 angles 0.00 0.00 0.00 pulses 0 0 0 foot 240.0 0.0 32.0\n"


def test_the_port_is_held_exclusively(board, capsys):
    path, link = board()  # one program has the port open
    with pytest.raises(SystemExit) as stop:
        cli.main(["send", "--port", path, "status"])
    assert stop.value.code == 2
    assert capsys.readouterr().err == (
        "hexapod: error: port %s in use by another program (a terminal, mpremote, another hexapod command):"
        " close it first\n" % path
    )
    with pytest.raises(PortBusy):
        Link.open(path)
    with pytest.raises(SystemExit) as stop:
        cli.main(["doctor", "--port", path])
    assert stop.value.code == 2
    assert link.request("get 1").startswith("ok leg 1 ")  # the holder's replies are still its own
    link.close()
    assert cli.main(["send", "--port", path, "get 1"]) == 0


def test_an_empty_request_is_refused_before_anything_is_sent(capsys):
    master, slave = pty.openpty()  # a line with nothing behind it: any byte sent would wait here
    tty.setraw(slave)
    try:
        for lines, why in (
            ([""], "LINE 1: an empty request: give a command (help lists them)"),
            (["status", "  "], "LINE 2: an empty request: give a command (help lists them)"),
            (["stop\x03"], "LINE 1: 'stop\\x03' holds the non-text character 0x03: only printable ASCII is sent"),
        ):
            with pytest.raises(SystemExit) as stop:
                cli.main(["send", "--port", os.ttyname(slave), *lines])
            assert stop.value.code == 2 and capsys.readouterr().err == "hexapod: error: %s\n" % why
        os.set_blocking(master, False)
        with pytest.raises(BlockingIOError):
            os.read(master, 100)  # nothing was written
    finally:
        os.close(master)
        os.close(slave)


def _virtual_board(*options):
    """`hexapod virtual-board` as a user starts it: (process, pty path, calibration directory)."""
    if micropython_missing():
        pytest.skip(micropython_missing())
    exe = os.path.join(os.path.dirname(sys.executable), "hexapod")
    cmd = [exe, "virtual-board", *options]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    path = proc.stdout.readline().strip()
    note = proc.stderr.readline()
    cal_dir = note.split("(calibration file in ")[1].split(")")[0]
    assert path.startswith("/dev/pts/") and os.path.isdir(cal_dir), note
    return proc, path, cal_dir


def children(pid):
    """Processes whose parent is pid (from /proc)."""
    found = []
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open("/proc/%s/stat" % entry) as f:
                    stat = f.read()
            except OSError:
                continue
            if int(stat.rsplit(")", 1)[1].split()[1]) == pid:
                found.append(int(entry))
    return found


def gone(pid, timeout=10.0):
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        try:
            with open("/proc/%d/stat" % pid) as f:
                if f.read().rsplit(")", 1)[1].split()[0] == "Z":
                    return True  # a zombie: dead, waiting for its (new) parent to reap it
        except OSError:
            return True
        time.sleep(0.05)
    return False


def test_kill_9_leaves_no_vm_serving_the_pty(tmp_path):
    # --cal-dir: a killed command cannot remove its temporary directory (nothing runs on SIGKILL).
    proc, path, cal_dir = _virtual_board("--cal-dir", str(tmp_path))
    try:
        # A client keeps the pty open (a terminal, jog): without it the VM would die of EIO anyway.
        with Link.open(path, timeout=1) as link:
            assert link.request("get 1").startswith("ok leg 1 ")
            (vm,) = children(proc.pid)
            proc.kill()  # kill -9: no handler runs
            proc.wait(10)
            assert gone(vm), "the MicroPython VM %d still serves %s after its parent was killed" % (vm, path)
            with pytest.raises(LinkError):  # the master side closed: lost, or no answer
                link.request("get 1")
    finally:
        for pid in children(proc.pid):
            os.kill(pid, signal.SIGKILL)
        if proc.poll() is None:
            proc.kill()
            proc.wait()


def test_the_next_virtual_board_removes_what_a_kill_9_left(tmp_path):
    dead = subprocess.Popen(["true"])
    dead.wait()  # a pid that no process has now
    names = [
        "hexapod-cal-%d-abc" % dead.pid,  # its owner is gone: removed
        "hexapod-cal-%d-def" % os.getpid(),  # owner running: kept
        "hexapod-cal-x-ghi",  # not a pid: kept
        "hexapod-calm-%d-jkl" % dead.pid,  # another prefix: kept
    ]
    for name in names:
        (tmp_path / name).mkdir()
    (tmp_path / names[0] / "hexapod_cal.txt").write_text("hexapod-cal 2\n")
    (tmp_path / ("hexapod-cal-%d-file" % dead.pid)).write_text("")  # a file, not a directory: kept
    removed = console_cmd.remove_stale_cal_dirs(str(tmp_path))
    assert removed == [str(tmp_path / names[0])]
    assert sorted(os.listdir(tmp_path)) == sorted(names[1:] + ["hexapod-cal-%d-file" % dead.pid])


def test_kill_9_without_cal_dir_leaves_a_directory_the_next_board_removes():
    proc, path, cal_dir = _virtual_board()
    try:
        (vm,) = children(proc.pid)
        proc.kill()  # kill -9: no handler runs
        proc.wait(10)
        assert gone(vm) and os.path.isdir(cal_dir)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    proc, path, second = _virtual_board()
    try:
        assert not os.path.exists(cal_dir) and os.path.isdir(second)
    finally:
        proc.send_signal(signal.SIGTERM)
        proc.wait(10)
    assert not os.path.exists(second)


@pytest.mark.parametrize("sig", [signal.SIGHUP, signal.SIGTERM])
def test_hangup_or_terminate_removes_the_temporary_calibration_directory(sig):
    proc, path, cal_dir = _virtual_board()
    try:
        with Link.open(path, timeout=10) as link:
            assert link.request("get 1").startswith("ok leg 1 ")
        (vm,) = children(proc.pid)
        proc.send_signal(sig)
        assert proc.wait(10) == 0
        assert not os.path.exists(cal_dir)
        assert gone(vm)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
