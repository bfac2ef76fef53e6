"""The host's stand-up helper (stubs/micropython/standing.py) on a default robot and on a stand-in
that stands after a set number of frames. Runs on CPython and in the MicroPython VM."""

import standing

import robots.default as d
from hexapod import geometry, tick


def _robot():
    g = geometry.load(d)
    return tick.Robot(g, tick.default_servos(g), tick.FrameBuffer())


class Slow:
    """Stands up `after` frames after stand_up() (never if None); stand_up answers `answer`."""

    def __init__(self, after, answer=tick.OK):
        self.geometry = geometry.load(d)
        self.mode = tick.RELAXED
        self.reason = tick.OK
        self.after = after
        self.answer = answer

    def stand_up(self):
        if self.answer == tick.OK:
            self.mode = tick.MOVING
        return self.answer

    def frame(self, n):
        if self.after is not None and n + 1 >= self.after:
            self.mode = tick.STANDING


def default_robot():
    """[bound, frames stand() took, the n each frame got were 0.., mode after, ticks run, a second
    stand's frames]: a default robot standing from relaxed, ticked every 20 ms."""
    robot = _robot()
    seen = []

    def frame(n):
        seen.append(n)
        robot.tick(20 * n)

    n = standing.stand(robot, frame)
    again = standing.until_standing(robot, frame)
    return [standing.posture_frames(robot.geometry), n, seen == list(range(n)), robot.mode, robot.ticks, again]


def open_coded():
    """The frames the loop every caller wrote before standing.stand took on a default robot."""
    robot = _robot()
    robot.stand_up()
    n = 0
    while robot.mode != tick.STANDING:
        robot.tick(20 * n)
        n += 1
    return n


def bounded(after, most):
    """until_standing on a stand-in that stands after `after` frames, bound most: the frames, or
    [the error's text, frames run]."""
    r = Slow(after)
    r.stand_up()
    ran = []

    def frame(n):
        ran.append(n)
        r.frame(n)

    try:
        return standing.until_standing(r, frame, most)
    except RuntimeError as e:
        return [str(e), len(ran)]


def refused():
    """stand() on a stand-in whose stand_up refuses (BUSY), bound 3: [the error's text]."""
    r = Slow(None, tick.BUSY)
    try:
        standing.stand(r, r.frame, 3)
    except RuntimeError as e:
        return [str(e)]
    return ["no error"]


def frozen():
    """A real robot asked to stand whose frames never tick it: the error after the default bound."""
    robot = _robot()
    try:
        standing.stand(robot, lambda n: None)
    except RuntimeError as e:
        return [str(e), robot.ticks]
    return ["no error"]
