"""The PC end of the serial console (docs/console.md): one request line, one reply line.

    with Link.open("/dev/ttyACM0") as link:
        reply = link.request("get 2")        # 'ok leg 2 angles ...' or 'err ...'
        lines = link.request_lines("selftest")   # a multi-line reply: every line, the end line last

Each request goes out tagged (`#N get 2`, docs/console.md "Request tags"): the board answers
`#N ok ...`, so a reply is paired with its request, and a late reply to an earlier request (one
that timed out, in this process or an earlier one: tags start at a random number) is set aside in
`link.late`, never taken for this one's. The tag's `#` also starts the request on a clean line:
half-typed text or a stray byte before it is dropped by the board, and no control byte is ever sent
(a line holding one is refused here). A `#N working` line (a command that takes longer than a frame:
a gait's servo check) extends the wait to WORKING_S.

A command in MULTI_LINE answers with several `ok`/`err` lines and then its end line, the one whose
second word is the command itself (`ok selftest 15 checks, 0 failed`, `err selftest: ...`);
request() returns that end line and keeps the lines before it in `link.body`.

Lines from the board that are no reply to this request (boot text, a calibration notice, a
traceback, the reply to a half-typed line) are kept in `link.other` and skipped; telemetry lines
(`~`, a board under `stream on`: docs/console.md) are skipped and not kept. The port is opened
exclusively (an advisory lock, as miniterm and picocom take): a second program gets PortBusy.
Errors are LinkError with a sentence a person can act on: no such port, a port in use or that
cannot be opened, no answer within the timeout (firmware not running, or a REPL prompt), a
disconnect mid-session.
"""

import contextlib
import random
import time

import serial
from serial.tools import list_ports

from hexapod_host.serial.telemetry import PREFIX as TELEMETRY

# Commands whose reply is several lines, ended by the line `ok|err <command>...` (docs/console.md).
MULTI_LINE = ("selftest",)
# Each line of a multi-line reply may take this much longer than a one-line reply (a `selftest
# servos L` joint sweeps for 2 s before its line).
MULTI_LINE_EXTRA_S = 5.0
BAUD = 115200  # USB CDC ignores it; a USB-serial bridge (ESP32 DevKit) needs it
TIMEOUT_S = 2.0
# After `#N working` the reply may take this long: a gait's servo check takes 1.5-1.8 s on a Pico,
# 20-30 s of wall time on the emulated one (hexapod pico serial) on a loaded 2-core machine.
WORKING_S = 90.0
LINE_MAX = 95  # characters the board takes in a line (firmware/console.py), the tag included
TAG_MAX = 999999999  # '#' and at most 9 digits
# USB vendor ids of the boards this project runs on: Raspberry Pi (Pico), Adafruit (Feather),
# Espressif (native USB), and the USB-serial bridges on ESP32 DevKits (CP210x, CH340, FTDI).
BOARD_VIDS = {0x2E8A: "Raspberry Pi", 0x239A: "Adafruit", 0x303A: "Espressif", 0x10C4: "CP210x", 0x1A86: "CH340"}
BOARD_VIDS[0x0403] = "FTDI"

try:  # POSIX: tcdrain on a port whose device went away raises termios.error, not an OSError
    from termios import error as _TermiosError
except ImportError:
    _TermiosError = OSError
# What a port raises when the board is unplugged or reset mid-session.
PORT_ERRORS = (OSError, serial.SerialException, _TermiosError)


class LinkError(Exception):
    """The board cannot be reached or stopped answering; the message says what to check."""


class PortBusy(LinkError):
    """Another program holds the port (a terminal, mpremote, another hexapod command)."""


def send_tagged(port, last, line):
    """Write line (checked by the caller: check_line) to port as the request after number last,
    wrapping at TAG_MAX: (its number, its tag '#N', None), or with the port's error (PORT_ERRORS)
    in place of None when it could not be written."""
    n = last + 1 if last < TAG_MAX else 1
    tag = "#%d" % n
    try:
        port.write(("%s %s\n" % (tag, line)).encode("ascii"))
        port.flush()
    except PORT_ERRORS as e:
        return n, tag, e
    return n, tag, None


def check_line(line):
    """Why line cannot be sent as one request ('' when it can): empty, a line break, a control or
    non-ASCII character (Ctrl-C would stop the board's loop), too long for the board's line."""
    if not line.strip():
        return "an empty request: give a command (help lists them)"
    for ch in line:
        if ch in "\r\n":
            return "one command per request: %r holds a line break" % line
        if not (" " <= ch <= "~" or ch == "\t"):
            return "%r holds the non-text character 0x%02x: only printable ASCII is sent" % (line, ord(ch))
    if len(line) > LINE_MAX - 11:
        return "%r is %d characters: at most %d (the board's line is %d with the request tag)" % (
            line[:20] + "...",
            len(line),
            LINE_MAX - 11,
            LINE_MAX,
        )
    return ""


def ports():
    """Serial ports as (device, description, vendor or ''), board-looking ones first."""
    rows = []
    for p in list_ports.comports():
        vendor = BOARD_VIDS.get(p.vid, "") if p.vid is not None else ""
        rows.append((p.device, p.description or "", vendor))
    rows.sort(key=lambda r: (r[2] == "", r[0]))
    return rows


class Link:
    """A request/reply client on an open serial-like object (has write, readline, close)."""

    def __init__(self, port, timeout=TIMEOUT_S, name="?", first_tag=None):
        self.port = port
        self.timeout = timeout
        self.name = name
        self.other = []  # lines that were not replies
        self.late = []  # replies to other tags: an earlier request's, after it gave up
        self.body = []  # the lines before the end line of the last multi-line reply
        self.working = 0  # `working` lines seen (commands that took longer than a frame)
        # Random start: a late reply to another process's request (same port, earlier run) must
        # not carry the tag this one waits for.
        self._tag = random.randrange(1, TAG_MAX // 2) if first_tag is None else first_tag - 1

    @classmethod
    def open(cls, device, timeout=TIMEOUT_S, baud=BAUD):
        """Open a serial port by path, exclusively; LinkError when it does not exist or cannot be
        opened, PortBusy when another program holds it."""
        try:
            port = serial.Serial(device, baud, timeout=0.05, write_timeout=timeout, exclusive=True)
        except serial.SerialException as e:
            text = str(e)
            if "No such file" in text or "FileNotFoundError" in text:
                raise LinkError("no such port %s (hexapod ports lists them)" % device) from None
            if "exclusively lock" in text or "Errno 16" in text or "busy" in text:
                raise PortBusy(
                    "port %s in use by another program (a terminal, mpremote, another hexapod command): close it first"
                    % device
                ) from None
            raise LinkError("cannot open %s: %s" % (device, text)) from None
        return cls(port, timeout, device)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        with contextlib.suppress(*PORT_ERRORS):
            self.port.close()

    def request(self, line):
        """Send one command line; return its reply line ('ok ...' or 'err ...'), stripped (for a
        multi-line reply its end line; the lines before it in self.body)."""
        lines = self.request_lines(line)
        self.body = lines[:-1]
        return lines[-1]

    def request_lines(self, line):
        """Send one command line; return every line of its reply, the end line last (one line
        unless the command is in MULTI_LINE)."""
        words = line.split()
        word = words[0] if words else ""
        tag = self._send(line)
        if word not in MULTI_LINE:
            return [self.read_reply(line, tag=tag)]
        lines = []
        while True:
            text = self.read_reply(line, self.timeout + MULTI_LINE_EXTRA_S, tag)
            lines.append(text)
            w = text.split(None, 2)
            if len(w) > 1 and w[1].rstrip(":") == word:
                return lines

    def _send(self, line):
        """Write line as a tagged request; returns its tag ('#N')."""
        why = check_line(line)
        if why:
            raise LinkError(why)
        self._tag, tag, error = send_tagged(self.port, self._tag, line)
        if error is not None:
            raise LinkError("lost the board on %s while sending (%s): unplugged?" % (self.name, error))
        return tag

    def read_reply(self, line="", timeout=None, tag=None):
        """The next reply line (`ok ...`/`err ...`) within timeout seconds (default self.timeout),
        its tag taken off; with tag, only the reply carrying it (others go to self.late; `working`
        under it extends the wait to WORKING_S); without, the next untagged one."""
        timeout = self.timeout if timeout is None else timeout
        deadline = time.monotonic() + timeout
        buf = b""
        while True:
            try:
                chunk = self.port.readline()
            except PORT_ERRORS as e:
                raise LinkError("lost the board on %s (%s): unplugged or reset?" % (self.name, e)) from None
            buf += chunk
            if buf.endswith(b"\n"):
                text = buf.decode("ascii", "replace").strip()
                buf = b""
                if text.startswith(TELEMETRY):
                    continue  # a streaming board's telemetry (`stream on`): never a reply, never kept
                head, _, rest = text.partition(" ")
                if head.startswith("#") and head[1:].isdigit():
                    if head != tag:
                        if _is_reply(rest) or rest == "working":
                            self.late.append(text)
                        else:
                            self.other.append(text)  # an echoed request (echo on)
                        continue
                    if rest == "working":
                        self.working += 1
                        deadline = time.monotonic() + max(timeout, WORKING_S)
                        continue
                    if _is_reply(rest):
                        return rest
                elif _is_reply(text):
                    if tag is None:
                        return text
                    if text.startswith("err unknown command %r" % tag):
                        raise LinkError(
                            "the firmware on %s does not take request tags (older than this host's): "
                            "flash it (hexapod flash)" % self.name
                        )
                if text:
                    self.other.append(text)
                continue
            if time.monotonic() > deadline:
                hint = ""
                if any(t.startswith(">>>") for t in self.other) or buf.startswith(b">>>"):
                    hint = " (the board is at the REPL: run main.py or reset it)"
                raise LinkError(
                    "no answer to %r from %s within %.1f s: is the hexapod firmware running?%s"
                    % (line, self.name, timeout, hint)
                )


def _is_reply(text):
    return text == "ok" or text == "err" or text.startswith(("ok ", "err "))
