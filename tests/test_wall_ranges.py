"""Every intermediate of the PID and the wall follower stays a MicroPython small int (|v| < 2**30).

The core is imported through tests/test_tick_ranges.py's AST rewrite (every arithmetic result
goes through a checker); then the PID runs at the largest gains and clamps with errors,
measurement steps and intervals at and past their limits, and the follower runs both walls at
the extreme set points and speeds through readings from 2 cm to 4 m, faults, corners and a
long search (the robot is a stand-in: tests/test_tick_ranges.py checks the tick itself)."""

import os
import sys

from tests.test_leg_ranges import SMALL, Checker
from tests.test_tick_ranges import instrumented_core

SCRIPT = """
from hexapod import follow, limits, pid, tick

for gains in ((pid.GAIN_MAX,) * 3, (1, pid.GAIN_MAX, 0), (pid.GAIN_MAX, 0, pid.GAIN_MAX)):
    p = pid.PID(*gains, out_max=pid.OUT_LIMIT, i_max=pid.OUT_LIMIT)
    t = 0
    top = 0
    for k in range(400):
        m = (-60000, 60000, 0, 40000, -40000, 5000)[k % 6]
        sp = (400, 5000, 60000, -60000)[k % 4]
        t += (1, 2, 999, 1000, 1001, 100, 40)[k % 7]
        top = max(top, abs(p.update(sp, m, t & 0x3FFFFFFF)), abs(p.i))
    out(top)

class FakeWalker:
    # What the follower reads of a walker: heading (fixmath.ANGLE_UNIT), state, the ramped velocity
    # (0.1 mm/s; the distance estimate's forward travel) and the held-tick count.

    def __init__(self):
        self.psi = 0
        self.state = 0
        self.vel = [0, 0, 0]
        self.held = 0


class FakeRobot:
    # Stands in for tick.Robot where only the follower's arithmetic is under test: the real tick
    # under this instrumentation costs ~5 ms a frame (tests/test_tick_ranges.py covers it).

    def __init__(self):
        self.walker = FakeWalker()
        self.body = self
        self.mode = tick.STANDING
        self.yaw = 0

    def settled(self):
        return True

    def walk(self, vx, vy, yaw):
        self.walker.state = 2
        self.walker.vel[0] = vx
        self.yaw = yaw
        return 0

    def stop(self):
        self.yaw = 0
        self.walker.vel[0] = 0
        return 0

    def tick(self, now):
        p = self.walker.psi + 2 * self.yaw
        self.walker.psi = p - 3600000 if p >= 3600000 else (p + 3600000 if p < 0 else p)
        return 0


def drive(robot, side, setpoint, speed, frames, t, form="yaw"):
    f = follow.Follower(robot)
    f.set_gains(pid.GAIN_MAX, pid.GAIN_MAX, pid.GAIN_MAX)
    f.follow(side, setpoint, speed, form)
    dist = [-1] * 5
    status = [5] * 5
    near = (1, 2) if side == "left" else (3, 4)
    total = 0
    for n in range(frames):
        k = (0, 4, 1, 3, 2)[n % 5]
        c = n // 5
        # Phases of 40 cycles: follow with wobble, extremes, corner, faults, anything, lost, blocked.
        phase = (c // 40) % 7
        d = -1
        st = 1
        if k == 0:
            d = (-1, 40000, 2100 + c % 50 * 100, -1, 30000, 6000, 200)[phase]
        elif k in near:
            wobble = setpoint + c * 53 % 400 - 200 + (k - near[0]) * 30
            d = (wobble, (200, setpoint + follow.WALL_GAP)[c % 2], setpoint, -1, 200 + c * 53 % 9000, 40000, setpoint)[
                phase
            ]
            if phase == 3:
                st = 2 if k == near[0] else 3
        if d >= 0 and st == 1:
            st = 0
        if d >= 0 and d <= 200 and k in near and c % 3:
            st = 4
        status[k] = st
        dist[k] = d if st == 0 else -1
        f.update(t & 0x3FFFFFFF, k, dist, status)
        robot.tick(t & 0x3FFFFFFF)
        t += 20
        if f.mode == follow.STOPPED:
            total += f.updates
            f.follow(side, setpoint, speed, form)
    return f, total + f.updates


for side in ("left", "right"):
    for setpoint, speed in ((limits.SETPOINT_MIN, 3000), (limits.SETPOINT_MAX, 3000), (800, limits.SPEED_MIN)):
        f, total = drive(FakeRobot(), side, setpoint, speed, 1400, (1 << 30) - 14000)
        out((f.mode, total, f.turned))



def full_turn(walker, left, right, out):
    # seed 000's turn at the walk's extremes (the real one needs a walker: tests/test_follow.py)
    out[0] = 3000
    out[1] = -9000
    return out


follow.sweep_command = full_turn
f, total = drive(FakeRobot(), "right", limits.SETPOINT_MAX, 3000, 1400, 0, "sweeps")
out((f.mode, total, f.turned))
"""


class PerFile(Checker):
    """The checker, also keeping the largest value per core file."""

    def __init__(self):
        super().__init__()
        self.by_file = {}

    def __call__(self, value):
        super().__call__(value)
        if isinstance(value, int):
            name = os.path.basename(sys._getframe(1).f_code.co_filename)
            if abs(value) > self.by_file.get(name, -1):
                self.by_file[name] = abs(value)
        return value


def test_every_intermediate_of_pid_and_follower_fits_a_small_int():
    checker = PerFile()
    rows = []
    with instrumented_core(checker):
        exec(compile(SCRIPT, "<wall ranges>", "exec"), {"out": rows.append})
        assert sys.modules["hexapod.follow"].__dict__.get("_chk_") is checker  # the rewritten core ran
        assert sys.modules["hexapod.pid"].__dict__.get("_chk_") is checker
    assert len(rows) == 10, rows
    assert all(abs(u) == 9000 for u in rows[:3])  # the PID was driven to its clamps
    assert all(r[1] > 80 for r in rows[3:9]), rows  # the follower steered through the phases
    assert rows[9][1] > 80  # and in seed 000's form
    for name in ("pid.py", "follow.py"):
        big = checker.by_file[name]
        print("largest intermediate in %s: %d (%.1f%% of 2**30)" % (name, big, 100 * big / SMALL))
    assert checker.biggest < SMALL
