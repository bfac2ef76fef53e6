"""The battery scenario's console reader and its run of main.main, with no stub in it but the
reader's byte buffer (_stub_serial, plain Python), so the same code watches the board on the stub
machine (scenarios.battery) and on the emulated Pico (tests/test_pico_battery.py ships this file
and _stub_serial to its flash)."""

import _stub_serial
import console
import main


class Script(_stub_serial.BufferReader):
    """The console's reader for main.main: types lines at given frames and, once a frame (the
    console polls it once a frame, after the step), logs every change of the robot's mode, the
    battery state and the walker's requested speed; the console's lines are kept with their frame.
    frame(): the frame in hand (the stub machine: its clock's ms // 20; a board: runner.frames - 1)."""

    def __init__(self, typed, frame):
        _stub_serial.BufferReader.__init__(self, b"")
        self.typed = typed  # {frame: line}
        self.frame = frame
        self.last = -1
        self.log = []  # (frame, what, value)
        self.said = []  # (frame, line) the console printed
        self.seen = {}

    def read_byte(self):
        now = self.frame()
        if now != self.last:
            self.last = now
            self.watch(now)
        return _stub_serial.BufferReader.read_byte(self)

    def watch(self, frame):
        r = main.runner
        for what, value in (
            ("mode", r.robot.mode),
            ("battery", r.battery.state),
            ("req_vx", r.robot.walker.req_vx),
        ):
            if self.seen.get(what) != value:
                self.seen[what] = value
                self.log.append((frame, what, value))
        line = self.typed.get(frame)
        if line is not None:
            self.feed(line.encode() + b"\n")

    def say(self, line):
        self.said.append((self.frame(), line))


def run(frames, typed, clock, frame, boot="stand"):
    """main.main(frames) with a Script typing `typed` and keeping the console's lines; (log, said)."""
    reader = Script(typed, frame)
    start = console.start

    def start_here(runner, reader, os=None, opener=open, out=print, **kw):
        c = start(runner, reader, os, opener, reader.say, **kw)  # the console's lines kept
        # The modules the typed lines' commands load on demand, loaded first: each line is answered
        # in the frame it is typed, as the scenario's frames were worked out (a line that waits for
        # its modules, a frame each, holds the lines after it too: console.Console._waiting).
        for name in ("consoleparts", "hexapod.jog", console.JOINT, console.WALL, console.MORE):
            console.load(name)
        return c

    console.start = start_here
    try:
        main.main(frames, clock=clock, reader=reader, boot=boot, calibrated=True)
    finally:
        console.start = start
    return reader.log, reader.said
