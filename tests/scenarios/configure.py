"""Configures spread over frames (Robot.set_* with wait=False), the same integers on both runtimes."""

import gc
import sys

from scenarios.rig import TICK_MS, stand

import robots.default as d
from hexapod import geometry, tick
from hexapod.gait import RIPPLE


class Solves:
    """Counts the IK solves of a robot's legs made outside its frames (the configure's own)."""

    def __init__(self, robot):
        self.n = 0
        self.on = True
        for leg in robot.geometry.legs:
            leg.ik = self._counted(leg.ik)
        frame = robot._output_plain

        def quiet():
            # The frame's own six solves (the plain output calls leg.ik; the viper one solves apart)
            # are not the configure's.
            self.on = False
            code = frame()
            self.on = True
            return code

        robot._output_plain = quiet

    def _counted(self, inner):
        def ik(x, y, z, out, i=0):
            if self.on:
                self.n += 1
            return inner(x, y, z, out, i)

        return ik


def _robot():
    g = geometry.load(d)
    return tick.Robot(g, tick.default_servos(g), tick.FrameBuffer())


def _ask(robot, kind, wait):
    if kind == "gait":
        return robot.set_gait(RIPPLE, 2400, wait=wait)  # not the robot file's 2.28 s: not in its table
    if kind == "pose":
        return robot.set_pose(roll=500, pitch=-300, wait=wait)
    if kind == "height":
        return robot.set_height(700, wait=wait)
    return robot.set_params(lift_height=250, wait=wait)


def _state(robot):
    w = robot.walker
    return [
        list(w.rho),
        list(w.next_rho),
        list(w.srho),
        list(w.next_srho),
        w.servo_peak,
        w.step,
        w.next_lift,
        w.next_gait,
        w.next_cycle_ms,
        w.ground,
        robot.gait,
        robot.cycle_ms,
        list(robot.body.target),
        robot.mode,
        robot.after,
    ]


def spread(kind):
    """[code at once, solves in the command, most solves in one tick, ticks until done, job code,
    the state after, the same command's state with wait=True, the body's travel while it ran (0.1 mm)]
    for kind "gait" (asked walking), "pose", "height" or "params" (asked standing)."""
    robot = _robot()
    now = stand(robot)
    if kind == "gait":
        robot.walk(400, 0, 0)
    count = Solves(robot)
    code = robot.set_gait(0) if kind == "none" else _ask(robot, kind, False)
    asked = count.n
    worst = 0
    ticks = 0
    x0 = robot.walker.bx
    while robot.configuring():
        count.n = 0
        robot.tick(now)
        now += TICK_MS
        ticks += 1
        if count.n > worst:
            worst = count.n
    travel = (robot.walker.bx - x0) >> 4
    after = _state(robot)
    sync = _robot()
    stand(sync)
    if kind == "gait":
        sync.walk(400, 0, 0)
    sync_code = _ask(sync, kind, True)
    return [code, asked, worst, ticks, robot.job_code, after, _state(sync), sync_code, travel]


def refusals():
    """What is refused while a pose is being checked, and what a second configure gets."""
    robot = _robot()
    now = stand(robot)
    out = [robot.set_pose(roll=500, wait=False), robot.configuring()]
    robot.tick(now)
    out += [robot.walk(400, 0, 0), robot.set_gait(RIPPLE, 2400, wait=False), robot.sit_down(), robot.set_height(700)]
    out.append(tick.describe(tick.CONFIGURING))
    return out


def job_heap():
    """MicroPython only: heap bytes left by each tick of a pose change in the frames' slack, ticks
    that allocated, and how many ticks it took (its generators are made when asked, not in a tick)."""
    if sys.implementation.name != "micropython":
        return None
    robot = _robot()
    now = stand(robot)
    robot.set_pose(roll=500, wait=False)
    allocated = []
    ticks = 0
    gc.collect()
    gc.disable()
    while robot.configuring():
        before = gc.mem_alloc()
        robot.tick(now)
        after = gc.mem_alloc()
        now += TICK_MS
        ticks += 1
        if after != before:
            allocated.append(after - before)
    gc.enable()
    return [allocated, ticks]


def deferred(pattern):
    """A gait asked walking (as spread's), under Runner.run's deferral (robot.defer): each frame one
    tick, then a walk command when pattern says so (its characters in turn: "c" a command, "."
    none), then pay() as Runner.run pays after its console. Returns [the most job steps in a tick (the
    walking step owed instead), the frames whose paid steps were not what the rule says (at most
    5: frame, paid), the first 40 frames' paid steps, ticks until done, the state after, the state
    of the same change made without the deferral]."""
    robot = _robot()
    now = stand(robot)
    robot.walk(400, 0, 0)
    robot.set_gait(RIPPLE, 2400, wait=False)
    robot.defer = True
    in_tick = 0
    wrong = []
    first = []
    ticks = 0
    last = 1
    while robot.configuring():
        n = robot.job_steps
        robot.tick(now)
        in_tick = max(in_tick, robot.job_steps - n)
        now += TICK_MS
        made = pattern[ticks % len(pattern)] == "c"
        if made:
            robot.walk(400, 0, 0)  # the same command again: the walk itself unchanged
        n = robot.job_steps
        if robot.owed:
            robot.pay(made)
        n = robot.job_steps - n
        want = 0 if made and last else 1
        if n != want and len(wrong) < 5:
            wrong.append((ticks, n))
        last = n
        if ticks < 40:
            first.append(n)
        ticks += 1
    robot.defer = False
    sync = _robot()
    stand(sync)
    sync.walk(400, 0, 0)
    sync.set_gait(RIPPLE, 2400, wait=True)
    return [in_tick, wrong, first, ticks, _state(robot), _state(sync)]
