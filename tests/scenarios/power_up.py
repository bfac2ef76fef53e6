"""Power-up on the stub machine: main.main with its console, a calibration file or none, the
board file's "boot" setting; what the PCA9685 models put out before anyone types `stand`."""

import os

import _stub_clock as clock
import _stub_serial
import calstore
import main
import stub_board
from scenarios.calstore import cal_text


class Lines(_stub_serial.BufferReader):
    """Console input fed line by line, one after each `every` frames (a maker typing); it also
    watches the PCA9685 models once a frame (the console polls it once a frame)."""

    def __init__(self, lines, every, table, chips):
        _stub_serial.BufferReader.__init__(self, b"")
        self.lines = list(lines)
        self.every = every
        self.table = table
        self.chips = chips
        self.last_ms = -1
        self.frame = 0
        self.on = [False] * 18
        self.first = -1  # the frame (0-based) of the first pulse on any channel
        self.most = 0  # the most servos that went from no pulse to a pulse in one frame

    def read_byte(self):
        now = clock.ticks_ms()
        if now != self.last_ms:
            self.last_ms = now
            self.watch()
            self.frame += 1
            if self.lines and self.frame % self.every == 0:
                self.feed(self.lines.pop(0).encode() + b"\n")
        return _stub_serial.BufferReader.read_byte(self)

    def watch(self):
        started = 0
        for k in range(18):
            address, ch, _ = self.table[k]
            on = self.chips[address].pulse_us(ch) > 0
            if on and not self.on[k]:
                started += 1
            self.on[k] = on
        if started and self.first < 0:
            self.first = self.frame
        if started > self.most:
            self.most = started


def _board():
    """The pico stub board with its PCA9685 and HC-SR04 models: (board, chips, servo table). The
    VM's path starts with '' (the working folder: the repository), and main.py imports the robot
    file at its top, so `robots` comes from '' as a relative path: every robot module the boot
    needs is imported here, before a scenario's chdir would hide them."""
    board = stub_board.reset("pico")
    _, chips = stub_board.pca9685_models(board)
    stub_board.sonar_models(board, [3000 + 1000 * k for k in range(5)])
    table = stub_board.servo_table(board)
    __import__("robots.default_guard")
    return board, chips, table


def boot(folder, cal, setting, frames, typed=(), every=50, calibrated=None):
    """main.main for `frames` frames in folder (its calibration file: "none", "valid" or
    "corrupt"), the board file's boot setting (None: not given), `typed` console lines one per
    `every` frames. Returns (the boot word of `status`, the robot's mode, the frame of the first
    pulse any PCA9685 channel put out (-1: none), the most servos that went from no pulse to a
    pulse in one frame)."""
    board, chips, table = _board()
    here = os.getcwd()
    os.chdir(folder)
    try:
        for name in (calstore.FILE, calstore.TMP):
            if name in os.listdir():
                os.remove(name)
        if cal != "none":
            rows = [(0, s[2].direction, s[2].min_us, s[2].max_us) for s in table]
            text = cal_text(rows)
            if cal == "corrupt":
                text = text.replace("1 coxa 0", "1 coxa 9", 1)  # the checksum no longer matches
            with open(calstore.FILE, "w") as f:
                f.write(text)
        if setting is not None:
            board["boot"] = setting
        reader = Lines(typed, every, table, chips)
        r = main.main(frames, clock=clock, reader=reader, calibrated=calibrated)
        status = r.console.do("status")
    finally:
        os.chdir(here)
        board.pop("boot", None)
    word = status.split(" boot ")[1].split()[0]
    return word, r.robot.mode, reader.first, reader.most


def released(folder):
    """After main.main: whether each boot-only module is still imported (hexapod.board,
    hexapod.robotfile, hexapod.robotcal, hexapod.check, robots.default, robots.default_cal)."""
    import sys

    boot(folder, "none", None, 1)
    names = ("hexapod.board", "hexapod.robotfile", "hexapod.robotcal", "hexapod.check", "robots.default")
    return [name in sys.modules for name in names + ("robots.default_cal",)]


def _trimmed(folder, table):
    """A valid calibration file in folder whose rows move every servo's centre (trim 10 + k us,
    servo k) and narrow its range by 20 us a side; returns the servo maps it puts in force
    (centre_us, direction, min_us, max_us), servo order."""
    import consolecal

    from hexapod import release

    rows = [(10 + k, s[2].direction, s[2].min_us + 20, s[2].max_us - 20) for k, s in enumerate(table)]
    for name in (calstore.FILE, calstore.TMP):
        if name in os.listdir():
            os.remove(name)
    with open(calstore.FILE, "w") as f:
        f.write(consolecal.encode(rows))
    release("consolecal")
    return [(table[k][2].centre_us + rows[k][0],) + rows[k][1:] for k in range(18)]


def early(folder, typed, frames=200):
    """main.main with a calibration file that trims every servo (_trimmed) and `typed` waiting
    on the console before the first frame (a client that writes as soon as the port opens): the
    boot leaves the file's load to the first frames (console.start), and no command may run
    before the file's calibration is in force. Returns (the console's lines in order, the
    distinct servo maps in force whenever a frame with a pulse went to the PCA9685s, the file's
    maps, the robot's mode at the end)."""
    import console

    from drivers import pca9685

    table = _board()[2]
    said = []
    seen = []
    write = pca9685.ServoBank.write_frame
    start = console.start

    def write_frame(bank, pulses):
        if any(pulses):
            maps = [(s.centre_us, s.direction, s.min_us, s.max_us) for s in main.runner.robot.servos]
            if maps not in seen:
                seen.append(maps)
        return write(bank, pulses)

    def start_said(*args, **kw):
        kw["out"] = lambda *parts: said.append(" ".join(parts))
        return start(*args, **kw)

    here = os.getcwd()
    os.chdir(folder)
    try:
        want = _trimmed(folder, table)
        pca9685.ServoBank.write_frame = write_frame
        console.start = start_said
        lo = str(table[0][2].min_us + 10)  # LO in a line: inside the robot file's range of servo 0, not the file's
        reader = _stub_serial.BufferReader("".join(line.replace("LO", lo) + "\n" for line in typed).encode())
        r = main.main(frames, clock=clock, reader=reader)
    finally:
        pca9685.ServoBank.write_frame = write
        console.start = start
        os.chdir(here)
    return said, seen, want, r.robot.mode


def early_do(folder, line):
    """console.start with a boot's deferred load (board given) on a built runner, then at once
    console.do(line), as the REPL could after a Ctrl-C in the first frames: (the reply, the servo
    maps in force then, the file's maps, whether the load was still under way before do)."""
    import console

    table = _board()[2]
    here = os.getcwd()
    os.chdir(folder)
    try:
        want = _trimmed(folder, table)
        r = main.build(clock=clock)
        c = console.start(r, _stub_serial.BufferReader(), os, out=lambda *parts: None, board=r.board)
        pending = c._boot is not None
        reply = c.do(line)
    finally:
        os.chdir(here)
    return reply, [(s.centre_us, s.direction, s.min_us, s.max_us) for s in r.robot.servos], want, pending


def interrupted(folder):
    """console.start's deferred load on a built runner (as early_do) whose first open of the file
    raises KeyboardInterrupt (a Ctrl-C in that step); then console.do("status"): (what the step
    raised, whether a load was still under way after it, the reply, the servo maps in force then,
    the file's maps)."""
    import console

    table = _board()[2]
    opens = []

    def opener(name, mode="r"):
        opens.append(name)
        if len(opens) == 1:
            raise KeyboardInterrupt
        return open(name, mode)

    here = os.getcwd()
    os.chdir(folder)
    try:
        want = _trimmed(folder, table)
        r = main.build(clock=clock)
        c = console.start(r, _stub_serial.BufferReader(), os, opener, out=lambda *parts: None, board=r.board)
        c.poll()  # calstore's import and the Store
        raised = None
        try:
            c.poll()  # the file's read: interrupted
        except KeyboardInterrupt:
            raised = "KeyboardInterrupt"
        pending = c._boot is not None
        reply = c.do("status")
    finally:
        os.chdir(here)
    return raised, pending, reply, [(s.centre_us, s.direction, s.min_us, s.max_us) for s in r.robot.servos], want
