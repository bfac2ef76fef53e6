"""The console's `selftest` on the stub board (the pico board file's loop on the stub machine: PCA9685
and HC-SR04 models, virtual clock) with a calibration file on scenarios.calstore's StubFS. Faults are
put into the models the way hardware goes wrong: a chip detached from the bus (unplugged or
unpowered: it no longer acknowledges), a chip reset (brownout), a sonar whose echo never rises, a
calibration file with a flipped byte. Runs on CPython and in the MicroPython VM."""

import _stub_clock as clock
import _stub_i2c
import _stub_pins
import _stub_serial
import calstore
import console
import main
import standing
import stub_board
from scenarios.calstore import StubFS, cal_text
from scenarios.rig import servo_state

from hexapod import tick


def rows(board):
    """The robot file's calibration as calibration-file rows (trim 0)."""
    return [(0, m.direction, m.min_us, m.max_us) for _, _, m in stub_board.servo_table(board)]


class Board:
    def __init__(self, cal="good", detach=None):
        _stub_i2c.reset()
        _stub_pins.reset()
        clock.reset(0)
        board = stub_board.reset("pico")
        self.bus, self.chips = stub_board.pca9685_models(board)
        if detach is not None:
            self.bus.detach(detach)
        self.sonars = stub_board.sonar_models(board, [3000 + 1000 * k for k in range(5)])
        self.fs = StubFS()
        if cal == "good":
            self.fs.files[calstore.FILE] = cal_text(rows(board))
        elif cal == "corrupt":  # one digit changed, the checksum line kept
            self.fs.files[calstore.FILE] = cal_text(rows(board)).replace("2 femur 0", "2 femur 7")
        self.r = main.build(clock=clock)
        self.robot = self.r.robot
        self.reader = _stub_serial.BufferReader()
        self.replies = []
        self.con = console.start(self.r, self.reader, self.fs, self.fs.open, out=self.replies.append)
        self.frames = 0

    def frame(self):
        self.r.step()
        self.con.poll()
        self.r.wait()
        self.frames += 1

    def say(self, line, end="ok selftest", limit=40):
        """Feed line; frames until a line starting with `end` (or 'err') comes, at most limit:
        [the lines, the frames it took]."""
        n = len(self.replies)
        self.reader.feed(line.encode() + b"\n")
        for k in range(limit):
            self.frame()
            new = self.replies[n:]
            for x in new:
                if x.startswith(end) or x.startswith("err " + end[3:]):
                    return [new, k + 1]
        return [self.replies[n:], -1]

    def registers(self):
        """Every register and latched output of each PCA9685 model, as lists (plain values)."""
        return [[a, list(m.regs), list(m.out)] for a, m in sorted(self.chips.items())]

    def state(self):
        return servo_state(self.robot, self.con) + [self.con.cal_source]


def stand(b):
    b.say("stand", "ok mode")
    standing.until_standing(b.robot, lambda n: b.frame())
    for _ in range(3):
        b.frame()


def checks(fault=None, standing=False):
    """`selftest` on a fresh board, with one fault (None, "detach_0x41", "unplug_0x41", "brownout_0x41",
    "no_echo_left_rear", "cal_corrupt", "cal_missing") and the robot relaxed or standing. Returns
    [lines, frames, registers before, registers after, sys.modules has selftest after, state same]."""
    b = Board(
        cal="corrupt" if fault == "cal_corrupt" else ("none" if fault == "cal_missing" else "good"),
        detach=0x41 if fault == "detach_0x41" else None,
    )
    if standing:
        stand(b)
    for _ in range(5):
        b.frame()
    if fault == "unplug_0x41":
        b.bus.detach(0x41)
    elif fault == "brownout_0x41":
        b.chips[0x41].reset()
    elif fault == "no_echo_left_rear":
        b.sonars[2].missing_echo = True
    before = b.registers()
    state = b.state()
    lines, frames = b.say("selftest")
    after = b.registers()
    import sys

    return [lines, frames, before, after, "selftest" in sys.modules, b.state() == state]


BAD = (
    "selftest foo",
    "selftest servos",
    "selftest servos 7",
    "selftest servos 0",
    "selftest servos x",
    "selftest servos 2 3",
    "selftest servos -1",
    "selftest servos 2.0",
    "selftest SERVOS 2",
    "selftest servo 2",
    "selftest 2",
)


def bad_lines(mode="relaxed"):
    """Each of BAD (and `selftest servos 2` unless sitting) on a board relaxed, standing or sitting:
    [[line, reply lines], ...], whether every state and register stayed the same, sys.modules."""
    b = Board()
    if mode == "standing":
        stand(b)
    elif mode == "sitting":
        b.say("sit", "ok mode")
        while b.robot.mode != tick.SITTING:
            b.frame()
    for _ in range(3):
        b.frame()
    out = []
    same = True
    lines = list(BAD)
    if mode != "sitting":
        lines.append("selftest servos 2")
    for line in lines:
        before = b.registers()
        state = b.state()
        got, frames = b.say(line, "err selftest", 3)
        b.frame()
        same = same and b.registers() == before and b.state() == state
        out.append([line, got])
    import sys

    return [out, same, "selftest" in sys.modules]


def sweep(leg=2):
    """`sit`, then `selftest servos leg`: [reply lines, frames, the leg's pulses each frame (robot
    and the PCA9685 models' outputs), the other 15 channels changed at any frame, mode after,
    the leg's pulses before and after]."""
    b = Board()
    b.say("sit", "ok mode")
    while b.robot.mode != tick.SITTING:
        b.frame()
    for _ in range(3):
        b.frame()
    table = stub_board.servo_table(b.r.board)
    k0 = 3 * (leg - 1)

    def outputs():
        return [b.chips[table[k][0]].pulse_us(table[k][1]) for k in range(18)]

    start = outputs()
    before = list(b.robot.pulses[k0 : k0 + 3])
    n = len(b.replies)
    b.reader.feed(("selftest servos %d\n" % leg).encode())
    seen = []
    others = False
    frames = 0
    while frames < 600:
        b.frame()
        frames += 1
        o = outputs()
        seen.append(o[k0 : k0 + 3])
        for k in range(18):
            if not k0 <= k < k0 + 3 and o[k] != start[k]:
                others = True
        if any(x.startswith("ok selftest") or x.startswith("err selftest") for x in b.replies[n:]):
            break
    for _ in range(5):
        b.frame()
    return [
        b.replies[n:],
        frames,
        seen,
        others,
        tick.MODE_NAMES[b.robot.mode],
        before,
        list(b.robot.pulses[k0 : k0 + 3]),
    ]


def sweep_cut_short():
    """`selftest servos 3` then `status` 10 frames in: the end line, then status's reply."""
    b = Board()
    b.say("sit", "ok mode")
    while b.robot.mode != tick.SITTING:
        b.frame()
    n = len(b.replies)
    b.reader.feed(b"selftest servos 3\n")
    for _ in range(10):
        b.frame()
    b.reader.feed(b"get 3\n")
    for _ in range(3):
        b.frame()
    return [b.replies[n:], tick.MODE_NAMES[b.robot.mode]]


def sweep_refused():
    """A servo whose calibrated range leaves no room above its present pulse (`range` at the pulse
    it holds): the jog path refuses the sweep's first step past it; the joint goes back."""
    b = Board()
    b.say("sit", "ok mode")
    while b.robot.mode != tick.SITTING:
        b.frame()
    p = b.robot.pulses[4]  # leg 2 femur
    # `range` waits for its modules (the package, caledit, calset: a frame each) before it runs
    r1 = b.say("range 2 femur 600 %d" % (p + 50), "ok leg", 5)[0]
    lines, frames = b.say("selftest servos 2", "ok selftest", 600)
    return [p, r1, lines, list(b.robot.pulses[3:6]), tick.MODE_NAMES[b.robot.mode]]
