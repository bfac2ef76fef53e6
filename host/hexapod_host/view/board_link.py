"""One serial line to a board carrying both the console's replies and its telemetry: a reader
thread sorts every line as it arrives (docs/view.md, "Driving"):

- `~T ...`: a telemetry line, parsed; the latest one is kept (`telemetry`), older ones dropped:
  the page draws only the newest;
- `#N ok ...`, `#N err ...`, `#N working`: the reply to the request sent under tag #N (`reply(tag)`);
  the page's commands go out tagged, so a reply pairs with its command even with telemetry
  lines between them;
- anything else (notices: `held:`, `battery:`, the boot line): kept in `notices`, the last 50.

Writes come from the page's event handlers and reads from the thread: the port's own write and
readline, a lock around the writes. hexapod_host.serial.link.Link stays the blocking
request/reply client of `send`, `jog` and `doctor`; this one never waits for a reply but in
request(), which the source calls once before the page is served.
"""

import contextlib
import random
import threading
import time
from collections import OrderedDict, deque

from hexapod_host.serial import telemetry
from hexapod_host.serial.link import PORT_ERRORS, TAG_MAX, check_line, send_tagged

REPLIES_KEPT = 200  # the page asks for a reply within seconds; older ones go


class BoardLink:
    """Replies and telemetry from one serial-like port (readline with a timeout, write)."""

    def __init__(self, port, name="?", parse=telemetry.parse, first_tag=None):
        self.port = port
        self.name = name
        self.parse = parse
        self.telemetry = None  # the newest telemetry dict
        self.telemetry_lines = 0
        self.malformed = 0  # telemetry lines the parser refused
        self.last_error = ""
        self.notices = deque(maxlen=50)
        self.on_telemetry = None  # called with each telemetry dict, in the reader's thread
        self.boots = 0  # the board's power-up lines seen (`boot: ...`, docs/console.md): it restarted
        self.replies = OrderedDict()  # '#N' -> 'ok ...' / 'err ...' / 'working'
        self.first = {}  # '#N' -> the first 'ok'/'err' line under it (a multi-line reply's first)
        self.lost = ""  # why the line went away ('' while it works)
        self._tag = random.randrange(1, TAG_MAX // 2) if first_tag is None else first_tag - 1
        self._write = threading.Lock()
        self._changed = threading.Condition()
        self._thread = None
        self._stop = False
        self._buf = b""

    def start(self):
        self._thread = threading.Thread(target=self._read_loop, name="board-link", daemon=True)
        self._thread.start()
        return self

    def send(self, line):
        """Write line as a tagged request now; its tag ('#N'). ValueError for a line the board
        would refuse to read (check_line's reason); nothing is written then."""
        why = check_line(line)
        if why:
            raise ValueError(why)
        with self._write:
            self._tag, tag, error = send_tagged(self.port, self._tag, line)
            if error is not None:
                self.lost = "lost the board on %s while sending (%s)" % (self.name, error)
        return tag

    def reply(self, tag):
        """The reply to the request under tag so far: None (nothing yet), 'working', 'ok ...', 'err ...'."""
        return self.replies.get(tag)

    def request(self, line, timeout=10.0, first=False):
        """Send line and wait for its reply (not 'working'); None when none came within timeout s.
        first: a multi-line reply's first line (selftest's `ok board ...`), not its latest."""
        tag = self.send(line)
        end = time.monotonic() + timeout
        with self._changed:
            while True:
                r = (self.first if first else self.replies).get(tag)
                if r is not None and r != "working":
                    return r
                left = end - time.monotonic()
                if left <= 0 or self.lost:
                    return None
                self._changed.wait(left)

    def feed(self, text):
        """Sort one line from the board (the reader thread's work; tests call it directly)."""
        text = text.strip()
        if not text:
            return
        if telemetry.is_telemetry(text):
            try:
                t = self.parse(text)
            except ValueError as e:
                self.malformed += 1
                self.last_error = str(e)
                return
            self.telemetry = t
            self.telemetry_lines += 1
            if self.on_telemetry is not None:
                try:
                    self.on_telemetry(t)
                except Exception as e:  # the reader must go on whatever a listener hits
                    self.last_error = "telemetry listener: %s: %s" % (type(e).__name__, e)
            return
        head, _, rest = text.partition(" ")
        is_reply = rest == "working" or rest.split(" ", 1)[0] in ("ok", "err")
        if head.startswith("#") and head[1:].isdigit() and is_reply:
            with self._changed:
                self.replies[head] = rest
                if rest != "working":
                    self.first.setdefault(head, rest)
                while len(self.replies) > REPLIES_KEPT:
                    self.first.pop(self.replies.popitem(last=False)[0], None)
                self._changed.notify_all()
            return
        if text.startswith("boot: "):
            self.boots += 1
        self.notices.append(text)

    def _read_loop(self):
        while not self._stop:
            try:
                chunk = self.port.readline()
            except PORT_ERRORS as e:
                self.lost = "lost the board on %s (%s)" % (self.name, e)
                with self._changed:
                    self._changed.notify_all()
                return
            if not chunk:
                continue
            self._buf += chunk
            if self._buf.endswith(b"\n"):
                line, self._buf = self._buf.decode("ascii", "replace"), b""
                self.feed(line)

    def close(self):
        self._stop = True
        if self._thread is not None:
            self._thread.join(2)
        with contextlib.suppress(*PORT_ERRORS):
            self.port.close()
