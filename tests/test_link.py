"""hexapod_host.serial.link and `hexapod ports` on fake serial ports: board-looking ports first, other
lines skipped, a REPL prompt and a disconnect named."""

import termios
import types

import pytest
import serial

from hexapod_host.commands import cli
from hexapod_host.serial import link
from hexapod_host.serial.link import Link, LinkError


class FakePort:
    """Lines to read back; '#T' in one stands for the tag of the request written last."""

    def __init__(self, lines=(), fail_after=None):
        self.lines = list(lines)
        self.written = []
        self.fail_after = fail_after

    def write(self, data):
        self.written.append(data)

    def tag(self):
        return self.written[-1].split(b" ", 1)[0] if self.written else b"#?"

    def flush(self):
        pass

    def readline(self):
        if self.fail_after is not None:
            if self.fail_after == 0:
                raise serial.SerialException("device reports readiness to read but returned no data")
            self.fail_after -= 1
        return self.lines.pop(0).replace(b"#T", self.tag()) if self.lines else b""

    def close(self):
        pass


def test_request_skips_other_lines_and_returns_the_reply():
    port = FakePort([b"MicroPython v1.22\r\n", b"cal: no hexapod_cal.txt; ...\r\n", b"#T ok leg 2 angles 0.00\r\n"])
    lk = Link(port, timeout=0.2, name="/dev/fake", first_tag=41)
    assert lk.request("get 2") == "ok leg 2 angles 0.00"
    assert port.written == [b"#41 get 2\n"]
    assert lk.other == ["MicroPython v1.22", "cal: no hexapod_cal.txt; ..."]
    with pytest.raises(LinkError, match="one command per request"):
        lk.request("get 2\nget 3")


def test_a_repl_prompt_and_a_disconnect_are_named():
    lk = Link(FakePort([b"Traceback (most recent call last):\r\n", b">>> \r\n"]), timeout=0.2, name="/dev/fake")
    with pytest.raises(LinkError) as e:
        lk.request("status")
    assert str(e.value) == (
        "no answer to 'status' from /dev/fake within 0.2 s: is the hexapod firmware running?"
        " (the board is at the REPL: run main.py or reset it)"
    )
    lk = Link(FakePort([b"#T ok\r\n"], fail_after=1), timeout=1, name="/dev/fake")
    assert lk.request("stop") == "ok"
    with pytest.raises(LinkError) as e:
        lk.request("status")
    assert str(e.value).startswith("lost the board on /dev/fake (") and str(e.value).endswith("unplugged or reset?")


def test_ports_lists_boards_first(monkeypatch, capsys):
    def port(device, vid, description):
        return types.SimpleNamespace(device=device, vid=vid, description=description)

    fake = [
        port("/dev/ttyS0", None, "n/a"),
        port("/dev/ttyUSB0", 0x10C4, "CP2102 USB to UART"),
        port("/dev/ttyACM1", 0x2E8A, "Board in FS mode"),
        port("/dev/ttyACM0", 0x1234, "some modem"),
    ]
    monkeypatch.setattr(link.list_ports, "comports", lambda: fake)
    assert [r[0] for r in link.ports()] == ["/dev/ttyACM1", "/dev/ttyUSB0", "/dev/ttyACM0", "/dev/ttyS0"]
    assert cli.main(["ports"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].split()[:2] == ["/dev/ttyACM1", "Raspberry"] and lines[1].split()[:2] == ["/dev/ttyUSB0", "CP210x"]
    monkeypatch.setattr(link.list_ports, "comports", lambda: [])
    assert cli.main(["ports"]) == 0
    assert capsys.readouterr().out == "no serial ports found (is the board plugged in with a data cable?)\n"


# pyserial's tcdrain raises termios.error, not an OSError, when the device went away between
# write and flush: found by the jog test under load.
class VanishingPort:
    """A port whose device went away at `stage` (write, flush or readline)."""

    def __init__(self, stage, error):
        self.stage, self.error = stage, error

    def _maybe(self, stage):
        if stage == self.stage:
            raise self.error

    def write(self, data):
        self._maybe("write")

    def flush(self):
        self._maybe("flush")

    def readline(self):
        self._maybe("readline")
        return b""

    def close(self):
        raise self.error


ERRORS = (termios.error(5, "Input/output error"), OSError(5, "EIO"), serial.SerialException("device reports readiness"))


@pytest.mark.parametrize("stage", ["write", "flush", "readline"])
@pytest.mark.parametrize("error", ERRORS, ids=lambda e: type(e).__name__)
def test_unplugged_mid_request_is_one_link_error(stage, error):
    link = Link(VanishingPort(stage, error), timeout=0.2, name="/dev/ttyACM7")
    with pytest.raises(LinkError, match="lost the board on /dev/ttyACM7"):
        link.request("get 2")
    link.close()  # closing a vanished port raises nothing either
