"""A refused command changes nothing of the console's state (tests/test_console_refusals.py): the
stub board (scenarios.console_rig) with a calibration file on a stub filesystem that can write
short while reporting success, and a telemetry stream whose output takes every line."""

import calstore
import console
from scenarios.calstore import StubFS, Writer, cal_text
from scenarios.console_rig import Board

from drivers import stream


class ShortWriter(Writer):
    """Drops the second half of each write yet reports every byte written (a full flash that says
    nothing): only save's read-back can notice."""

    def write(self, s):
        self.fs.files[self.name] += s[: len(s) // 2]
        return len(s)


class FlakyFS(StubFS):
    short = False  # writes come out short, reported whole

    def open(self, name, mode="r"):
        if mode in ("r", "rb") or not self.short:
            return StubFS.open(self, name, mode)
        self.files[name] = ""
        return ShortWriter(self, name)


class Sink:
    """The telemetry's output: every line taken (a refused `stream` must not start it)."""

    def write(self, buf, n):
        return n


def full_state(b, fs):
    """All the console's state: pulses, angles, mode, gait, the standing height, calibration rows, trims and source,
    PID gains, the follower, the walk command and its deadline, echo, the telemetry, the PCA9685
    outputs and the calibration file (a cut save may leave a broken temp file: load skips it)."""
    r = b.r
    con = b.con
    f = r.follower
    p = f.pid
    rb = r.robot
    t = con.telemetry
    return (
        list(rb.pulses),
        list(rb.angles),
        rb.mode,
        rb.gait,
        rb.walker.ground,
        [(s.centre_us, s.direction, s.min_us, s.max_us) for s in rb.servos],
        list(con.trims),
        con.cal_source,
        (p.kp, p.ki, p.kd),
        (f.mode, f.side, f.setpoint, f.speed),
        (rb.asked_vx, rb.asked_vy, rb.asked_yaw, con._walking, con._deadline),
        con.echo,
        (t.hz, t.every, t.due, t.sent, t.dropped),
        b.channels(),
        fs.files.get(calstore.FILE),
    )


def to(b, state):
    """Bring the board to state: relaxed, jogged, standing, walking or following (a wall); a walk
    renewed so it does not expire while the lines run (no frame runs between the snapshot before
    a line and the one after: con.do is the dispatcher itself)."""
    if state == "relaxed":
        return
    if state == "jogged":
        for leg in range(1, 7):
            b.say("foot %d 130 0 -80" % leg)
        b.say("pulse 2 femur 2350")  # near its top: a trim of +100 is refused by the pose
        return
    b.say("stand")
    b.frames(120)
    if state == "walking":
        b.say("walk 50 0 0")
        b.frames(5)
    elif state == "following":
        b.say("wall left 40")
        b.frames(5)


def refused(state, lines):
    """In state, each line run by the console's dispatcher ("<short>": save on a filesystem that
    writes short, "<readonly>": save on a read-only one): [mode, follower mode, [(line, reply,
    indexes of full_state that changed)]]."""
    b = Board()
    fs = FlakyFS()
    b.con = console.start(b.r, b.reader, fs, opener=fs.open, out=b.out)
    b.con.telemetry = stream.Stream(Sink())
    to(b, state)
    b.frames(2)  # the last reply's change reaches the chips (a line runs after its frame's tick)
    # A calibration file the pose refuses on its last row (leg 6 tibia's range excludes any tibia
    # angle but one far from the present one), the other 17 rows different from what is in force.
    fs.files[calstore.FILE] = cal_text([(7, 1, 610, 2390)] * 17 + [(0, 1, 2480, 2500)])
    out = []
    for typed in lines:
        line = typed
        if line == "<short>":
            fs.short = True
            line = "save"
        elif line == "<readonly>":
            fs.short = False
            fs.readonly = True
            line = "save"
        before = full_state(b, fs)
        reply = b.con.do(line)
        after = full_state(b, fs)
        out.append((typed, reply, [k for k in range(len(before)) if before[k] != after[k]]))
    return [b.robot.mode, b.r.follower.mode, out]
