"""`selftest servos L` (selftest.py's start() imports this for that job only, and the console drops
it with selftest when the job ends): leg L's coxa, femur and tibia swept one after the other, each
+-10 degrees around the angle it holds and back, at SWEEP_CDEG_PER_S, every step through
Robot.jog_joint (the robot file's joint limits and each servo's calibrated range apply).
"""

from hexapod.units import format_fixed

FRAME_MS = 20
SWEEP_CDEG = 1000  # +-10 degrees around the present angle
SWEEP_CDEG_PER_S = 2000  # 20 deg/s: 0.4 degree a frame
STEP_CDEG = SWEEP_CDEG_PER_S * FRAME_MS // 1000
JOINTS = ("coxa", "femur", "tibia")


class Sweep:
    """`selftest servos L` as a console job: leg L's joints one after the other, +-SWEEP_CDEG around
    the present angle and back, STEP_CDEG a frame, through Robot.jog_joint; then `sit` again."""

    def __init__(self, console, leg):
        self.con = console
        self.robot = console.robot
        self.leg = leg
        self.joint = 0
        self.count = 0
        self.failed = 0
        self.done = False
        self._begin()

    def _begin(self):
        k = 3 * self.leg + self.joint
        self.a0 = self.robot.angles[k]
        self.offset = 0
        self.turns = 0  # 0: going up, 1: going down, 2: coming back
        self.lo = self.hi = self.robot.pulses[k]

    def step(self):
        out = []
        r = self.robot
        j = self.joint
        if self.turns == 0:
            self.offset += STEP_CDEG
            if self.offset >= SWEEP_CDEG:
                self.offset = SWEEP_CDEG
                self.turns = 1
        elif self.turns == 1:
            self.offset -= STEP_CDEG
            if self.offset <= -SWEEP_CDEG:
                self.offset = -SWEEP_CDEG
                self.turns = 2
        else:
            self.offset += STEP_CDEG
            if self.offset >= 0:
                self.offset = 0
                self.turns = 3
        code = r.jog_joint(self.leg, j, self.a0 + self.offset)
        k = 3 * self.leg + j
        if code:
            why = self.con._refused(code)[4:]
            back = r.jog_joint(self.leg, j, self.a0)
            self.count += 1
            self.failed += 1
            out.append(
                "err servo %d %s: refused at %s deg (%s); %s"
                % (
                    self.leg + 1,
                    JOINTS[j],
                    format_fixed(self.a0 + self.offset, 2),
                    why,
                    "it went back to %s deg" % format_fixed(self.a0, 2) if not back else "it stays where it was",
                )
            )
            self._next(out)
            return out
        p = r.pulses[k]
        self.lo = p if p < self.lo else self.lo
        self.hi = p if p > self.hi else self.hi
        if self.turns == 3:
            self.count += 1
            out.append(
                "ok servo %d %s swept %s..%s deg at %d deg/s, pulses %d..%d us"
                % (
                    self.leg + 1,
                    JOINTS[j],
                    format_fixed(self.a0 - SWEEP_CDEG, 2),
                    format_fixed(self.a0 + SWEEP_CDEG, 2),
                    SWEEP_CDEG_PER_S // 100,
                    self.lo,
                    self.hi,
                )
            )
            self._next(out)
        return out

    def _next(self, out):
        if self.joint < 2:
            self.joint += 1
            self._begin()
            return
        code = self.robot.sit_down()  # every pulse is back where it was: the leg's jog ends at once
        if code:
            self.failed += 1
            why = self.con._refused(code)[4:]
            out.append("err selftest servos %d: 'sit' afterwards refused: %s" % (self.leg + 1, why))
        else:
            out.append(self.end())
        self.done = True

    def abort(self):
        self.done = True
        return (
            "err selftest servos %d: cut short by a new line during the %s; the leg stays where it is ('sit' "
            % (
                self.leg + 1,
                JOINTS[self.joint],
            )
            + "brings it home)"
        )

    def end(self):
        return "%s selftest servos %d: %d joints swept, %d failed" % (
            "err" if self.failed else "ok",
            self.leg + 1,
            self.count,
            self.failed,
        )
