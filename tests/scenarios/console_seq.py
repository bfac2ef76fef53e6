"""Console command sequences on the stub board (the pico board file's loop on the stub machine:
PCA9685 and HC-SR04 models, virtual clock), lines fed through the console's own reader and run
by its poll() between frames, as Runner.run does. Runs on CPython and in the MicroPython VM.

Frame bounds, from the robot file (robots/default.py) and the core's speeds:
- POSTURE_FRAMES: a posture move (stand, sit, relax) is at most three waypoint sets
  (hexapod.posture); in each the farthest foot moves POSTURE_STEP (2 mm) a frame, and no foot
  travels farther than the diameter of its leg's workspace: every reachable foot lies within
  R = coxa + femur + tibia + |femur_offset| of its coxa origin (the body pose is fixed during a
  move, so body-frame distances are leg-frame distances), so a set takes at most
  ceil((2R + 1) / POSTURE_STEP) frames (posture's +1 rounding). Default robot: R = 272 mm,
  273 frames a set, 819 for the move, plus 2 (the frame that ends the move, and the reply
  coming in the frame after the line). 16 s: loose, but a frozen move never gets there.
- WALK_FRAMES: `stop` (or a console walk expiring, or `wall off`) lets the steps under way
  finish (at most one gait cycle) and then sets every foot down at neutral (at most one more
  cycle): two of the slowest gait's cycles (robot file GAIT_CYCLE_MS, wave 4.32 s) = 432
  frames, plus the walk's timeout (1000 ms = 50 frames) and 2 for the expiry check.
- HELD_FRAMES: no frame may be held (faults rising) for longer than the longest of the two.
"""

import console
import standing
from scenarios import console_rig
from scenarios.rig import servo_state

import robots.default as d
from hexapod import tick
from hexapod.gait import TICK_MS
from hexapod.posture import POSTURE_STEP

_REACH = d.COXA + d.FEMUR + d.TIBIA + (d.FEMUR_OFFSET if d.FEMUR_OFFSET > 0 else -d.FEMUR_OFFSET)
POSTURE_FRAMES = 3 * ((2 * _REACH + 1 + POSTURE_STEP - 1) // POSTURE_STEP) + 2
WALK_FRAMES = 2 * max(d.GAIT_CYCLE_MS) // TICK_MS + console.WALK_TIMEOUT_MS // TICK_MS + 2
HELD_FRAMES = POSTURE_FRAMES if POSTURE_FRAMES > WALK_FRAMES else WALK_FRAMES
MODES = tick.MODE_NAMES


def _waits(name):
    """The imports a line of module `name`'s commands may wait for: the consoleparts package, then
    console.BEFORE's chain down from it (console.Console._waiting: one a frame)."""
    n = 1
    while name is not None:
        n += 1
        name = console.BEFORE.get(name)
    return n


# A reply comes in its line's frame, or in the frame after its modules' imports (the line's frame,
# one a module, then the command's): 3 frames allowed before the imports waited (2026-11-28).
REPLY_FRAMES = 2 + max(_waits(m) for m in (console.JOINT, console.CALSET, console.CAL, console.MORE))


class Board(console_rig.Board):
    """The console bench (scenarios.console_rig.Board); a reply waited for at most REPLY_FRAMES."""

    SAY_FRAMES = REPLY_FRAMES


def sit_after_tibia_zero(frames=200):
    """Issue 20, point 3: stand, `joint 2 tibia 0`, `sit`, then `frames` frames. Returns
    [replies, frames to standing, frames the sit took (-1: never sitting), mode, held, faults,
    leg 2's pulses, the console's other lines]."""
    b = Board()
    replies = [b.say("stand")]
    n = standing.until_standing(b.robot, lambda n: b.frame(), POSTURE_FRAMES)
    replies.append(b.say("joint 2 tibia 0"))
    replies.append(b.say("sit"))
    took = -1
    for k in range(frames):
        b.frame()
        if took < 0 and b.robot.mode == tick.SITTING:
            took = k + 1
    notices = [x for x in b.replies if not x.startswith("ok") and not x.startswith("err")]
    return [
        replies,
        n,
        took,
        MODES[b.robot.mode],
        b.r.held,
        b.robot.faults,
        list(b.robot.pulses[3:6]),
        notices,
    ]


def held_notice():
    """A frame made unreachable behind the console's back (a servo map narrowed directly, as a
    stray REPL edit would): the console says so once, not every frame. Returns [notices, held
    frames, notices after the map is put back and the frame is held again]."""
    b = Board()
    b.stand()
    s = b.robot.servos[4]  # leg 2 femur
    lo = s.min_us
    s.min_us = b.robot.pulses[4] + 50
    for _ in range(100):
        b.frame()
    first = [x for x in b.replies if x.startswith("held")]
    held = b.r.held
    s.min_us = lo
    b.frame()
    s.min_us = b.robot.pulses[4] + 50
    for _ in range(10):
        b.frame()
    return [first, held, [x for x in b.replies if x.startswith("held")]]


# -- random sequences -------------------------------------------------------------------------


class Lcg:
    """The same numbers on CPython and MicroPython (random differs between them)."""

    def __init__(self, seed):
        self.x = seed & 0x7FFFFFFF

    def below(self, n):
        self.x = (self.x * 1103515245 + 12345) & 0x7FFFFFFF
        return (self.x >> 16) % n

    def pick(self, items):
        return items[self.below(len(items))]


JOINTS = ("coxa", "femur", "tibia")
GAITS = ("tripod", "tetrapod", "ripple", "wave")
# Malformed or out-of-range lines: each must be refused (`err`) and change nothing.
INVALID = (
    "joint 7 tibia 0",
    "joint 2 knee 0",
    "joint 2 tibia 5",
    "joint 2 tibia -200",
    "walk 999 0 0",
    "walk 10 0",
    "foot 2 a b c",
    "foot 2 400 0 0",
    "nudge 0 1 1 1",
    "stand now",
    "sit 1",
    "relax please",
    "trim 2 femur 999",
    "range 2 tibia 2400 600",
    "dir 2 femur 2",
    "gait run",
    "pulse 2 tibia 3000",
    "pulse 2 tibia 12.5",
    "wall up 10",
    "wall left 1",
    "stop now",
    "jump",
    "get 9",
)
QUERIES = ("status", "get 2", "cal 2 tibia", "sonar", "pid", "help", "gait", "echo")
GAPS = (0, 0, 0, 1, 1, 2, 3, 8)  # frames between commands


def _num(g, lo, hi):
    """A decimal between lo and hi (whole units), sometimes with a fraction."""
    v = lo + g.below(hi - lo + 1)
    if g.below(4) == 0:
        return "%d.%d" % (v, g.below(10)) if v >= 0 else "-%d.%d" % (-v, g.below(10))
    return str(v)


def command(g):
    """One console line drawn from g."""
    k = g.below(200)
    leg = str(1 + g.below(6))
    if k < 6:
        return "stand"
    if k < 12:
        return "sit"
    if k < 14:
        return "relax"
    if k < 24:
        return g.pick(QUERIES)
    if k < 52:
        return "joint %s %s %s" % (leg, g.pick(JOINTS), g.pick(("0", "0", _num(g, -90, 90), _num(g, -180, 0))))
    if k < 68:
        return "foot %s %s %s %s" % (leg, _num(g, 40, 260), _num(g, -150, 150), _num(g, -180, 60))
    if k < 80:
        return "nudge %s %s %s %s" % (leg, _num(g, -30, 30), _num(g, -30, 30), _num(g, -30, 30))
    if k < 92:
        return "pulse %s %s %d" % (leg, g.pick(JOINTS), 600 + g.below(1801))
    if k < 101:
        return "trim %s %s %d" % (leg, g.pick(JOINTS), g.below(201) - 100)
    if k < 106:
        return "dir %s %s %s" % (leg, g.pick(JOINTS), g.pick(("1", "-1")))
    if k < 113:
        lo = 600 + g.below(900)
        return "range %s %s %d %d" % (leg, g.pick(JOINTS), lo, lo + 100 + g.below(2400 - lo - 99))
    if k < 131:
        return "walk %s %s %s" % (_num(g, -300, 300), _num(g, -300, 300), _num(g, -90, 90))
    if k < 141:
        return "stop"
    if k < 142:
        return "gait " + g.pick(GAITS)
    if k < 150:
        return g.pick(("wall left 30", "wall right 45", "wall off", "wall off"))
    if k < 158:
        return "defaults"
    if k < 170:
        return g.pick(QUERIES)
    return g.pick(INVALID)


def _snap(b):
    r = b.robot
    return servo_state(r, b.con) + [
        r.gait,
        b.r.follower.mode,
        list(r.walker.fx),
        list(r.walker.fy),
        list(r.walker.fz),
    ]


class Run:
    """Sequences back to back on one board, each starting where the last one settled (every
    target reached: jogged, sitting, standing, relaxed, recalibrated, another gait), a fresh
    board every `fresh` sequences; every frame checked."""

    def __init__(self, seed, fresh):
        self.g = Lcg(seed)
        self.fresh = fresh
        self.b = None
        self.bad = []  # [sequence, lines so far, what went wrong]
        self.commands = 0
        self.frames = 0
        self.oks = {}
        self.errs = 0
        self.worst = {}  # target -> most frames an accepted command took to get there
        self.held = 0
        self.held_run = 0
        self.worst_held_run = 0

    def fail(self, what):
        if len(self.bad) < 5:
            self.bad.append([self.seq, list(self.lines), what])

    def frame(self):
        b = self.b
        held = b.r.held
        b.frame()
        self.frames += 1
        if b.r.held != held:
            self.held += 1
            self.held_run += 1
            if self.held_run > self.worst_held_run:
                self.worst_held_run = self.held_run
            if self.held_run == HELD_FRAMES + 1:
                self.fail("frames held for more than %d frames: %s" % (HELD_FRAMES, tick.describe(b.robot.reason)))
        else:
            self.held_run = 0
        self.check_target()

    def check_target(self):
        if self.target is None:
            return
        name, modes, deadline, since = self.target
        mode = self.b.robot.mode
        # There: in the mode, following no wall, and the frame sent (a held frame is not a pose reached).
        if mode in modes and self.b.robot.reason == 0 and not (mode == tick.STANDING and not self.settled()):
            took = self.frames - since
            if took > self.worst.get(name, 0):
                self.worst[name] = took
            self.target = None
        elif self.frames > deadline:
            self.fail(
                "%s answered ok, still %s (%s) after %d frames"
                % (name, MODES[mode], tick.describe(self.b.robot.reason), self.frames - since)
            )
            self.target = None

    def settled(self):
        return not self.b.r.follower.mode

    def expect(self, name, modes, bound):
        self.target = [name, modes, self.frames + bound, self.frames]
        self.check_target()

    def send(self, line):
        b = self.b
        self.lines.append(line)
        self.commands += 1
        n = len(b.replies)
        b.reader.feed(line.encode() + b"\n")
        before = None
        reply = None
        for _ in range(REPLY_FRAMES):
            b.r.step()
            before = _snap(b)
            was = b.robot.mode
            b.con.poll()
            b.r.wait()
            self.frames += 1
            if len(b.replies) > n:
                reply = b.replies[-1]
                break
        self.lines[-1] = "%s -> %s" % (line, reply)
        word = line.split()[0]
        if reply is None or not (reply == "ok" or reply.startswith("ok ") or reply.startswith("err ")):
            self.fail("no ok/err reply to %r: %r" % (line, reply))
            return
        if reply.startswith("err"):
            self.errs += 1
            if _snap(b) != before:
                self.fail("%r refused but changed the state" % line)
            self.check_target()
            return
        if "internal" in reply:
            self.fail(reply)
        self.oks[word] = self.oks.get(word, 0) + 1
        self.accepted(line, word, was)

    def accepted(self, line, word, was):
        b = self.b
        mode = b.robot.mode
        if word == "stand":
            self.expect("stand", (tick.STANDING,), POSTURE_FRAMES)
        elif word == "sit":
            self.expect("sit", (tick.SITTING,), POSTURE_FRAMES)
        elif word == "relax":
            self.expect("relax", (tick.RELAXED,), POSTURE_FRAMES)
        elif word in ("joint", "foot", "nudge", "pulse"):
            if mode != tick.JOG:
                self.fail("%r answered ok, mode %s" % (line, MODES[mode]))
            self.target = None
        elif word == "walk" or word == "stop" or (word == "wall" and line == "wall off"):
            if mode == tick.WALKING or b.r.follower.mode:
                self.expect(word, (tick.STANDING,), WALK_FRAMES)
        elif word == "wall":
            self.target = None  # following: walks until `wall off` or `stop`
        elif word in ("trim", "dir", "range", "gait", "defaults") and mode != was:
            self.fail("%r answered ok and changed the mode from %s to %s" % (line, MODES[was], MODES[mode]))

    def start(self):
        if self.b is None or self.seq % self.fresh == 0:
            self.b = Board()
        self.lines = []
        self.target = None

    def sequence(self, length):
        g = self.g
        self.start()
        for _ in range(length):
            self.send(command(g))
            for _ in range(g.pick(GAPS)):
                self.frame()
        # The end: a walk or wall following is stopped; every accepted command must get where it said.
        if self.b.robot.mode == tick.WALKING or self.b.r.follower.mode:
            self.send("stop")
        while self.target is not None:
            self.frame()


def sequences(seed, n, length=3, fresh=100):
    """n sequences of `length` random lines (seeded LCG). Returns [sequences, commands, frames,
    accepted per command word, refusals, worst frames to the target per command word, held
    frames, longest held run, failures (first 5), bounds]."""
    run = Run(seed, fresh)
    for k in range(n):
        run.seq = k
        run.sequence(length)
    return [
        n,
        run.commands,
        run.frames,
        run.oks,
        run.errs,
        run.worst,
        run.held,
        run.worst_held_run,
        run.bad,
        [POSTURE_FRAMES, WALK_FRAMES, HELD_FRAMES],
    ]
