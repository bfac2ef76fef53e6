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


# -- request tags (docs/console.md "Request tags"): issue 21 items 1, 2, 3, 5 -------------------


class Clock:
    """time.monotonic for the link: each read of the port takes `step` seconds (no wall clock)."""

    def __init__(self, step=0.1):
        self.now, self.step = 0.0, step

    def monotonic(self):
        return self.now


class TickingPort(FakePort):
    def __init__(self, lines, clock):
        super().__init__(lines)
        self.clock = clock

    def readline(self):
        self.clock.now += self.clock.step
        return super().readline()


def test_a_late_reply_under_another_tag_is_set_aside():
    # A 'gait wave' that timed out earlier answers now: the status request must get its own reply.
    junk = b"err unknown command 'sta' (help lists them)\r\n"
    port = FakePort([b"#17 ok gait wave\r\n", junk, b"#T ok frames 9\r\n"])
    lk = Link(port, timeout=0.5, name="/dev/fake", first_tag=18)
    assert lk.request("status") == "ok frames 9"
    assert port.written == [b"#18 status\n"]
    assert lk.late == ["#17 ok gait wave"]
    assert lk.other == ["err unknown command 'sta' (help lists them)"]  # a half-typed line's reply


def test_working_extends_the_wait_past_the_timeout(monkeypatch):
    clock = Clock(0.1)
    monkeypatch.setattr(link.time, "monotonic", clock.monotonic)
    # 'gait wave' on the emulated Pico: the working line within the timeout, the reply 25 s later.
    lines = [b"#T working\r\n"] + [b""] * 250 + [b"#T ok gait wave\r\n"]
    lk = Link(TickingPort(lines, clock), timeout=2.0, name="/dev/fake")
    assert lk.request("gait wave") == "ok gait wave" and lk.working == 1
    assert 25.0 <= clock.now <= 25.3
    # Without a working line the same silence is a timeout, named.
    clock.now = 0.0
    lk = Link(TickingPort([b""] * 250 + [b"#T ok gait wave\r\n"], clock), timeout=2.0, name="/dev/fake")
    with pytest.raises(LinkError, match="no answer to 'gait wave' from /dev/fake within 2.0 s"):
        lk.request("gait wave")
    # A working line does not wait for ever: WORKING_S (90 s) after it.
    clock.now = 0.0
    lk = Link(TickingPort([b"#T working\r\n"], clock), timeout=2.0, name="/dev/fake")
    with pytest.raises(LinkError, match="no answer"):
        lk.request("gait wave")
    assert 90.0 <= clock.now <= 90.3


@pytest.mark.parametrize(
    ("line", "why"),
    [
        ("", "an empty request: give a command (help lists them)"),
        ("   ", "an empty request: give a command (help lists them)"),
        ("\x03", "'\\x03' holds the non-text character 0x03: only printable ASCII is sent"),
        ("stand\x1b", "'stand\\x1b' holds the non-text character 0x1b: only printable ASCII is sent"),
        ("get 1\x01", "'get 1\\x01' holds the non-text character 0x01: only printable ASCII is sent"),
        ("get 1\nget 2", "one command per request: 'get 1\\nget 2' holds a line break"),
        ("walk 1 0 0 " + "0" * 80, "'walk 1 0 0 000000000...' is 91 characters: at most 84 (the board's line is 95"),
    ],
)
def test_lines_that_are_no_request_are_refused_and_nothing_is_written(line, why):
    port = FakePort([b"#T ok\r\n"])
    with pytest.raises(LinkError) as e:
        Link(port, timeout=0.2, name="/dev/fake").request(line)
    assert str(e.value).startswith(why) and port.written == []


def test_firmware_without_tags_is_named():
    port = FakePort([b"err unknown command '#T' (help lists them)\r\n"])
    with pytest.raises(LinkError, match="does not take request tags .older than this host's.: flash it"):
        Link(port, timeout=0.2, name="/dev/fake").request("status")


def test_each_link_starts_its_tags_at_random():
    # Two runs of `hexapod send` on one port: the second must not wait on the first's tag.
    firsts = set()
    for _ in range(5):
        port = FakePort([b"#T ok\r\n"])
        Link(port, timeout=0.2).request("stop")
        firsts.add(port.written[0].split()[0])
    assert len(firsts) == 5
