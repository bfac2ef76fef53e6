"""The PC end of the serial console (docs/console.md): one request line, one reply line.

    with Link.open("/dev/ttyACM0") as link:
        reply = link.request("get 2")        # 'ok leg 2 angles ...' or 'err ...'
        lines = link.request_lines("selftest")   # a multi-line reply: every line, the end line last

A command in MULTI_LINE answers with several `ok`/`err` lines and then its end line, the one whose
second word is the command itself (`ok selftest 15 checks, 0 failed`, `err selftest: ...`);
request() returns that end line and keeps the lines before it in `link.body`.

Lines from the board that start with neither `ok` nor `err` (boot text, a calibration notice,
a traceback) are kept in `link.other` and skipped. Errors are LinkError with a sentence a
person can act on: no such port, a port that cannot be opened, no answer within the timeout
(firmware not running, or a REPL prompt), a disconnect mid-session.
"""

import contextlib
import time

import serial
from serial.tools import list_ports

# Commands whose reply is several lines, ended by the line `ok|err <command>...` (docs/console.md).
MULTI_LINE = ("selftest",)
# Each line of a multi-line reply may take this much longer than a one-line reply (a `selftest
# servos L` joint sweeps for 2 s before its line).
MULTI_LINE_EXTRA_S = 5.0
BAUD = 115200  # USB CDC ignores it; a USB-serial bridge (ESP32 DevKit) needs it
TIMEOUT_S = 2.0
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

    def __init__(self, port, timeout=TIMEOUT_S, name="?"):
        self.port = port
        self.timeout = timeout
        self.name = name
        self.other = []  # lines that were not replies
        self.body = []  # the lines before the end line of the last multi-line reply

    @classmethod
    def open(cls, device, timeout=TIMEOUT_S, baud=BAUD):
        """Open a serial port by path; LinkError when it does not exist or cannot be opened."""
        try:
            port = serial.Serial(device, baud, timeout=0.05, write_timeout=timeout)
        except serial.SerialException as e:
            text = str(e)
            if "No such file" in text or "FileNotFoundError" in text:
                raise LinkError("no such port %s (hexapod ports lists them)" % device) from None
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
        self._send(line)
        if word not in MULTI_LINE:
            return [self.read_reply(line)]
        lines = []
        while True:
            text = self.read_reply(line, self.timeout + MULTI_LINE_EXTRA_S)
            lines.append(text)
            w = text.split(None, 2)
            if len(w) > 1 and w[1].rstrip(":") == word:
                return lines

    def _send(self, line):
        if "\n" in line or "\r" in line:
            raise LinkError("one command per request: %r holds a line break" % line)
        try:
            self.port.write((line + "\n").encode("ascii", "replace"))
            self.port.flush()
        except PORT_ERRORS as e:
            raise LinkError("lost the board on %s while sending (%s): unplugged?" % (self.name, e)) from None

    def read_reply(self, line="", timeout=None):
        """The next line starting with `ok` or `err`, within timeout seconds (default self.timeout)."""
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
                if text == "ok" or text.startswith(("ok ", "err ")) or text == "err":
                    return text
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
