"""Issue 21 items 1-4 on the emulated Pico (MicroPython's own RPI_PICO image under rp2040js, the
firmware flashed, its PCA9685s and sonars attached), through the pty `hexapod pico serial` gives:
`hexapod send 'gait wave'` (1.5-1.8 emulated s, 20-30 s of wall time) answered, not timed out, and
the next request gets its own reply; half-typed input dropped; the port held exclusively; the jog
prompt's Ctrl-C never sent, and what a 0x03 does to a real MicroPython (KeyboardInterrupt: the loop
leaves, servos relaxed, the REPL). tests/test_link_board.py does the same on the virtual board."""

import os
import time

import pytest

from hexapod_host.commands import cli
from hexapod_host.pico import emulator as pico
from hexapod_host.serial import jog
from hexapod_host.serial.link import Link, LinkError

REASON = pico.missing()
pytestmark = pytest.mark.skipif(REASON is not None, reason=REASON or "")


def send(capsys, *lines):
    status = cli.main(["send", "--port", PATH[0], *lines])  # the default 2 s timeout
    return status, capsys.readouterr().out.splitlines()


PATH = [None]


def test_the_link_on_the_emulated_pico(capsys):
    with pico.flashed() as fs, pico.serial(fs, devices=pico.devices()) as path:
        PATH[0] = path
        with Link.open(path, timeout=600) as link:  # main.py boots: ~4 emulated s of imports
            assert link.request("help").startswith("ok help ")
        # Item 2: the gait's servo check takes 1.5-1.8 emulated s; `working` keeps the client waiting.
        status, out = send(capsys, "gait wave")
        assert (status, out) == (0, ["ok gait wave"])
        status, out = send(capsys, "status", "gait")
        assert status == 0 and out[0].startswith("ok frames ") and out[1] == "ok gait wave", out
        # Item 3: half-typed text on the line before a request.
        fd = os.open(path, os.O_WRONLY | os.O_NOCTTY)
        os.write(fd, b"sit")
        os.close(fd)
        status, out = send(capsys, "gait")
        assert (status, out) == (0, ["ok gait wave"])
        # Item 4 and item 1: a program holds the port; the jog line with Ctrl-C is not sent.
        with Link.open(path, timeout=10) as link:
            with pytest.raises(SystemExit) as stop:
                cli.main(["send", "--port", path, "status"])
            assert stop.value.code == 2 and "in use by another program" in capsys.readouterr().err
            assert link.request("stand") == "ok mode moving"
            tool = jog.Jog(link, LinkError)
            tool.line("status\x03")
            assert tool.view.error and tool.view.message.startswith("not sent: the line holds the control character")
            words = link.request("status").split()
            assert words[words.index("mode") + 1] in ("moving", "standing")  # the loop runs on
            # What 0x03 does to MicroPython: KeyboardInterrupt, main.py's loop leaves relaxed, REPL.
            link.port.write(b"\x03")
            raw = b""
            end = time.monotonic() + 120
            while b">>> " not in raw and time.monotonic() < end:
                raw += link.port.read(256)
            assert b"stopped: servos relaxed; runner.run() resumes" in raw and b">>> " in raw, raw
