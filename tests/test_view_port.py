"""`hexapod view --port PORT` and `--pico` without a browser: the CLI's refusals (a missing port, a
port another program holds: exit 2, nothing sent on the line) and a pretend board on a real
pseudo-terminal (what the host sees of a board on USB): the port is held exclusively while the
page serves, `stream on 25` is asked, its telemetry drawn; a board that answers nothing or `err`
to `stream` (older firmware) is still served, drawn resting, with what it said. The page on a
virtual board's pty and on the emulated Pico: tests/test_view_sources_browser.py."""

import os
import select
import socket
import threading
import tty

import pytest

from hexapod_host.commands import cli, view
from hexapod_host.pico import emulator
from hexapod_host.serial.link import Link, PortBusy

# tests/test_view_virtual.py's hand-written line: frame 1234, walking, the hand-worked pulses
# (legs 1 and 5 at femur +30, tibia -120 degrees: the tibia straight down).
PULSES = [1500, 1800, 1200] + [1500, 1500, 2400] * 2 + [1500, 1500, 600] + [1500, 1200, 1800] + [1500, 1500, 600]
LINE = "~T 1234 4 1 7 1 1 800 0 500 %s - 1234 1200 - - 2 0 0 1 5 -35 1250 - 0 2 1 3" % " ".join(map(str, PULSES))


def free_listen():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return "127.0.0.1:%d" % s.getsockname()[1]


class PtyBoard:
    """A pretend board on the master side of a new pty: answers each tagged line with
    answer(command) (None: stays silent), then sends `after` lines; keeps what it read."""

    def __init__(self, answer, after=()):
        self.master, self.slave = os.openpty()
        tty.setraw(self.slave)  # a USB serial line's bytes: no echo
        self.path = os.ttyname(self.slave)
        self.answer = answer
        self.after = list(after)
        self.read = b""
        self._stop = False
        self._thread = threading.Thread(target=self._serve, daemon=True)
        self._thread.start()

    def _serve(self):
        buf = b""
        while not self._stop:
            if not select.select([self.master], [], [], 0.02)[0]:
                continue
            try:
                data = os.read(self.master, 4096)
            except OSError:
                return
            self.read += data
            buf += data
            while b"\n" in buf:
                line, buf = buf.split(b"\n", 1)
                tag, _, command = line.decode().partition(" ")
                reply = self.answer(command)
                out = ([] if reply is None else ["%s %s" % (tag, reply)]) + self.after
                os.write(self.master, "".join(s + "\n" for s in out).encode())

    def stop(self):
        self._stop = True
        self._thread.join(2)
        os.close(self.master)
        os.close(self.slave)


@pytest.fixture
def board_factory():
    made = []

    def make(answer, after=()):
        made.append(PtyBoard(answer, after))
        return made[-1]

    yield make
    for b in made:
        b.stop()


def parse(*argv):
    """hexapod view's own parser and checks, as `hexapod view ARGV` runs them (before serving)."""
    return view.parse(cli.build_parser().parse_args(["view", *argv, "--listen", free_listen()]))


def test_a_missing_port_is_refused(capsys):
    with pytest.raises(SystemExit) as exc:
        cli.main(["view", "--port", "/dev/no-such-tty", "--no-browser", "--listen", free_listen()])
    assert exc.value.code == 2
    assert "--port: no such port /dev/no-such-tty (hexapod ports lists them)" in capsys.readouterr().err


def test_a_port_another_program_holds_is_refused_and_nothing_is_sent(board_factory, capsys):
    board = board_factory(lambda command: "ok")
    with Link.open(board.path), pytest.raises(SystemExit) as exc:  # a terminal holds the robot's line
        cli.main(["view", "--port", board.path, "--no-browser", "--listen", free_listen()])
    assert exc.value.code == 2
    assert "--port: port %s in use by another program" % board.path in capsys.readouterr().err
    assert board.read == b""  # no `stream on`, no `help`: the other program's line untouched


def test_the_port_is_held_while_served_and_its_telemetry_drawn(board_factory):
    board = board_factory(lambda command: "ok stream 25" if command == "stream on 25" else "ok", after=[LINE])
    source, speed, _, _, record = parse("--port", board.path)
    try:
        assert (source.name, source.stream_reply, speed, record) == ("port", "ok stream 25", 1.0, None)
        # `stream on 25`, `selftest` (what the board is), then `cal 1 coxa` (the board's servo
        # maps, view/boardcal.py), which this pretend board answers with a bare ok: no board line,
        # no cal line, so nothing more is asked
        sent = [line.split(" ", 1)[1] for line in board.read.decode().splitlines()]
        assert sent == ["stream on 25", "selftest", "cal 1 coxa"]
        assert source.cal.source == "robot file ('cal 1 coxa' answered 'ok')"
        assert source.board_text() == "board unknown ('selftest' answered 'ok')"
        with pytest.raises(PortBusy):
            Link.open(board.path)  # nobody else types on the robot's line while the page drives
        for _ in range(500):
            if source.link.telemetry_lines:
                break
            threading.Event().wait(0.01)
        s = source.snapshot()
        assert (s["frame"], s["mode"], s["pulses"]) == (1234, "walking", PULSES)
        # tests/test_view.py's hand-worked leg 1: femur +30, tibia -120 degrees
        assert s["angles"][:3] == pytest.approx([0, 3000, -12000], abs=1)
        assert s["distances"] == [None, 123.4, 120.0, None, None]
    finally:
        source.close()
    Link.open(board.path).close()  # let go when the server stops


def test_old_firmware_without_stream_is_served_resting_with_its_err(board_factory):
    err = "err unknown command 'stream' (help lists them)"
    board = board_factory(lambda command: err if command.startswith("stream") else "ok")
    source = parse("--port", board.path)[0]
    try:
        s = source.snapshot()
        assert s["extra"]["stream"] == err  # the drive panel shows it
        assert (s["frame"], s["mode"], s["pulses"]) == (0, "-", [0] * 18)
        assert s["angles"] == [0, 0, -9000] * 6  # limp joints at their reference angles
        # and it is still driven: the stand button's line goes out
        tag = source.command("stand")
        for _ in range(500):
            if source.reply(tag):
                break
            threading.Event().wait(0.01)
        assert source.reply(tag) == "ok"
    finally:
        source.close()


def test_a_board_that_answers_nothing_is_served_resting(board_factory):
    board = board_factory(lambda command: None)
    source = view.open_board(board.path, "--port", "port", reply_s=0.5)  # the CLI's guard is 10 s
    try:
        s = source.snapshot()
        assert s["extra"]["stream"] == "no reply to 'stream on 25'"
        assert (s["frame"], s["pulses"]) == (0, [0] * 18)
        assert b"stream on 25\n" in board.read
    finally:
        source.close()


@pytest.mark.parametrize(
    "argv, message",
    [
        (["--sim", "--sonar-cm", "30"], "--sonar-cm: only with --pico (what the emulated HC-SR04s see)"),
        (["--port", "/dev/x", "--sonar-cm", "30"], "--sonar-cm: only with --pico"),
        (["--pico", "--virtual-port", "/dev/x"], "--virtual-port: only with --virtual"),
    ],
)
def test_options_of_another_source_are_refused(argv, message, capsys):
    with pytest.raises(SystemExit) as exc:
        cli.main(["view", *argv, "--no-browser"])
    assert exc.value.code == 2
    assert message in capsys.readouterr().err


@pytest.mark.skipif(emulator.missing() is not None, reason=emulator.missing() or "")
def test_pico_sonar_distances_are_checked_before_anything_starts(capsys):
    with pytest.raises(SystemExit) as exc:
        cli.main(["view", "--pico", "--sonar-cm", "1", "--no-browser"])
    assert exc.value.code == 2
    assert "--sonar-cm: 1 is outside 2..400 cm (the HC-SR04's range)" in capsys.readouterr().err


def test_pico_without_the_emulator_says_what_is_missing(monkeypatch, capsys):
    monkeypatch.setattr(emulator, "missing", lambda: "the Pico emulator needs Node.js >= 18: install it")
    with pytest.raises(SystemExit) as exc:
        cli.main(["view", "--pico", "--no-browser"])
    assert exc.value.code == 2
    assert "--pico: the Pico emulator needs Node.js >= 18" in capsys.readouterr().err
