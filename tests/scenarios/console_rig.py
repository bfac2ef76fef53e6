"""The console's test bench: the pico board file's loop on the stub machine (PCA9685 and HC-SR04
models, virtual clock) with a console reading from a BufferReader, lines run by its poll()
between frames as Runner.run does. Runs on CPython and in the MicroPython VM.

A Board starts from reset stubs (bus, pins, clock at 0), so a second Board in one call, or in
one CPython process, starts where the VM's fresh process does. The sonars stand 300, 400, 500,
600 and 700 mm from their walls (seed 000's ring order)."""

import _stub_clock as clock
import _stub_i2c
import _stub_pins
import _stub_serial
import console
import main
import standing
import stub_board
from scenarios.rig import servo_state

from hexapod import board as boards
from hexapod import robotcal

SONAR_MM10 = [3000 + 1000 * k for k in range(5)]  # each sonar's wall, tenths of a mm


class Board:
    """A fresh stub board and its console; every reply line collected in `replies`.

    r: the Runner (main.build), robot: its tick.Robot, con: the Console, reader: its BufferReader,
    table: the board's servo table [(chip address, channel, _)] in leg/joint order, chips: the
    PCA9685 models by address, bus: their I2C bus, sonar: the HC-SR04 models in ring order."""

    SAY_FRAMES = 20  # frames say() waits for a reply

    def __init__(self):
        _stub_i2c.reset()
        _stub_pins.reset()
        clock.reset(0)
        board = stub_board.reset("pico")
        self.table = boards.servo_table(board, robotcal.servo_maps(robotcal.load("default")))
        self.bus, self.chips = stub_board.pca9685_models(board)
        self.sonar = stub_board.sonar_models(board, SONAR_MM10)
        self.r = main.build(clock=clock)
        self.robot = self.r.robot
        self.reader = _stub_serial.BufferReader()
        self.replies = []
        self.con = console.start(self.r, self.reader, None, out=self.out)

    def out(self, line, more=None):
        """As print: a tagged reply comes as (tag, line), kept as one line."""
        self.replies.append(line if more is None else line + " " + more)

    def frame(self):
        self.r.step()
        self.con.poll()
        self.r.wait()

    def frames(self, n):
        r = self.r  # locals: the VM's fastest lookups, for the long runs
        con = self.con
        for _ in range(n):
            r.step()
            con.poll()
            r.wait()

    def say(self, line):
        """Feed line, run frames until its reply (at most SAY_FRAMES): the reply, or None."""
        n = len(self.replies)
        self.reader.feed(line.encode() + b"\n")
        for _ in range(self.SAY_FRAMES):
            self.frame()
            if len(self.replies) > n:
                return self.replies[-1]
        return None

    def says(self, lines):
        """say() each line: the replies."""
        return [self.say(line) for line in lines]

    def lines(self, data, n=3):
        """Feed raw bytes, run n frames: the reply lines they brought."""
        before = len(self.replies)
        self.reader.feed(data)
        self.frames(n)
        return self.replies[before:]

    def channels(self):
        """The PCA9685 models' 18 servo pulse widths (us), leg/joint order."""
        return [self.chips[a].pulse_us(ch) for a, ch, _ in self.table]

    def unsafe(self):
        """[servo, ns] of each servo whose output is neither off nor inside its calibrated
        min..max (give or take half a PCA9685 count)."""
        bad = []
        servos = self.robot.servos
        for k in range(18):
            a, ch, _ = self.table[k]
            s = servos[k]
            m = self.chips[a]
            ns = m.pulse_ns(ch)
            half = (m.prescale() + 1) * 500000000 // m.clock_hz() + 1
            if ns and not s.min_us * 1000 - half <= ns <= s.max_us * 1000 + half:
                bad.append((k, ns))
        return bad

    def state(self):
        """What a refused command must leave as it was (scenarios.rig.servo_state)."""
        return servo_state(self.robot, self.con)

    def stand(self):
        """say('stand') and run frames until the robot is STANDING (standing.until_standing's bound)."""
        self.say("stand")
        standing.until_standing(self.robot, lambda n: self.frame())


def steps(todo):
    """On a fresh board, each step: ("lines", bytes, frames) -> the reply lines the bytes brought,
    ("do", line) -> the console's reply to line run directly, ("mode",) -> the robot's mode."""
    b = Board()
    out = []
    for step in todo:
        if step[0] == "lines":
            out.append(b.lines(step[1], step[2]))
        elif step[0] == "do":
            out.append(b.con.do(step[1]))
        else:
            out.append(b.robot.mode)
    return out


def frame_heap(datas):
    """VM heap bytes of one console poll with each whole line waiting in the reader (as the
    bench's console rows), the replies going nowhere (as print: nothing kept)."""
    from scenarios.heap import heap_bytes

    b = Board()
    con = b.con
    reader = b.reader
    con.out = _nowhere

    def frame(data):
        reader.data = data
        reader.pos = 0
        con.poll()

    return [heap_bytes(frame, bytearray(d)) for d in datas]


def _nowhere(line, tag_line=None):
    pass
