"""The real board console (firmware/console.py) on the pico board's loop on the stub machine, as a
link the jog tool talks through: request(line) feeds the line to the console and runs 20 ms frames
until it answers. It starts standing (scenarios.rig.stand) with a calibration file store on a stub
filesystem. serve_pty puts any such link on a pseudo-terminal, so `hexapod jog --port` opens it
like a board. CPython only (the tests' own process)."""

import contextlib
import os
import threading

import _stub_clock as clock
import _stub_serial
import calstore
import console
from scenarios.calstore import StubFS, decode
from scenarios.rig import stand
from scenarios.runner import Loop


class ConsoleLink:
    def __init__(self):
        self.loop = Loop("pico")
        self.loop.plug(0x40, 0x41)
        self.runner = self.loop.build()
        self.robot = self.runner.robot
        clock.advance_to(stand(self.robot, clock.ticks_ms()) * 1000)
        self.reader = _stub_serial.BufferReader()
        self.replies = []
        self.fs = StubFS()
        self.console = console.start(self.runner, self.reader, self.fs, self.fs.open, out=self.say)
        self.replies.clear()  # the boot's 'cal: no hexapod_cal.txt ...' line
        self.lines = []  # every line requested, in order
        self.raw = b""  # every byte that came in over serve_pty

    def say(self, *parts):
        """The console's out: a line, or a tagged reply's tag and line (print's two arguments)."""
        self.replies.append(" ".join(parts))

    def frames(self, n):
        r = self.runner
        for _ in range(n):
            r.step()
            self.console.poll()
            r.wait()

    def request(self, line):
        """The console's reply to line, after the frames it took (one poll per frame, as Runner.run)."""
        self.lines.append(line.split(" ", 1)[1] if line.startswith("#") else line)  # the command, untagged
        before = len(self.replies)
        self.reader.feed(line.encode() + b"\n")
        for _ in range(20):
            self.frames(1)
            # a tagged slow command's '#N working' comes first (docs/console.md): its reply follows
            if len(self.replies) > before and not self.replies[-1].endswith(" working"):
                return self.replies[-1]
        raise AssertionError("no reply to %r in 20 frames" % line)

    def leg_line(self, n):
        """The console's leg line for leg n (1..6), read without a request."""
        return self.console.leg_line(n - 1)

    def limp(self, n, joint):
        """Leg n's servo `joint` (0..2) limp, the leg's other two driven where they were: the robot goes
        limp, then those two are jogged back (a jog of a limp leg drives only the servo it moves)."""
        r = self.robot
        k = 3 * (n - 1)
        angles = list(r.angles[k : k + 3])
        r.go_limp()
        for j in range(3):
            if j != joint:
                assert r.jog_joint(n - 1, j, angles[j]) == 0

    def saved_rows(self):
        """The calibration file's 18 (trim, direction, min_us, max_us) rows."""
        return decode(self.fs.files[calstore.FILE])


def serve_pty(link):
    """Answer console lines on a new pseudo-terminal; returns (slave path, stop()). Every byte that
    came in is kept in link.raw (a control byte sent by a client shows there)."""
    import tty

    master, slave = os.openpty()
    tty.setraw(slave)
    path = os.ttyname(slave)
    stopping = []

    def loop():
        buf = b""
        while not stopping:
            try:
                data = os.read(master, 256)
            except OSError:
                return
            buf += data
            link.raw += data
            while b"\n" in buf:
                raw, buf = buf.split(b"\n", 1)
                line = raw.decode(errors="replace").strip()
                if line and not stopping:
                    os.write(master, (link.request(line) + "\r\n").encode())

    t = threading.Thread(target=loop, daemon=True)
    t.start()

    def stop():
        stopping.append(1)
        for fd in (slave, master):
            with contextlib.suppress(OSError):
                os.close(fd)

    return path, stop
