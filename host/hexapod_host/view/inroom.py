"""A recording without a room (a board's: its body never leaves the origin) replayed in a wall
simulator world (`hexapod view --replay FILE --world W`): the body is put at the world's start
and moved by its recorded feet, the wall simulator's kinematic mover (hexapod_host.wall.room's
Body.move: the feet on the ground in two snapshots in a row stay put in the world, the body's
step is their least-squares rigid motion).

Start: as `hexapod sim wall` places its robot (wall.sim.place_at_start), facing along the start
wall, the followed side's sonar midpoint at the distance those two sonars first read together
(the recorded follow side, else the world's), or at START_MM when they never both read.
"""

import math

from hexapod_host.wall.room import Body
from hexapod_host.wall.sim import place_at_start

START_MM = 120.0  # `hexapod view --sim`'s default set point, 12 cm
SIDE_SONARS = {"left": (1, 2), "right": (3, 4)}  # hexapod.sensors order


class NotPlaceable(ValueError):
    """A recording that cannot be put in a world, with why."""


def check(described, world):
    """NotPlaceable unless the recording has no room of its own (a simulator's recording was
    made in one: its walls and its body's path are in the file)."""
    if described.get("walls"):
        raise NotPlaceable(
            "the recording was made in the simulator's world %s: its room and path are in the file; "
            "--world places a recording without a room (a board's: --virtual, --pico, --port)"
            % described.get("world", "?")
        )


def start(snaps, world):
    """(side, distance mm) the body starts at: see the module's docstring."""
    side = next((s["follow"]["side"] for s in snaps if s["follow"]["side"] in SIDE_SONARS), world.follow)
    for s in snaps:
        d = [s["distances"][k] for k in SIDE_SONARS[side]]
        if None not in d and all(v > 0 for v in d):
            return side, sum(d) / 2
    return side, START_MM


class Odometry:
    """The body's world pose from its feet, one snapshot after another (the module's mover): a
    Body (hexapod_host.wall.room) placed where it starts, stepped with each snapshot's legs."""

    def __init__(self, body):
        self.body = body
        self._old = None  # the feet of the snapshot before (None: start over from these)
        self._last = None  # the last step made with feet down in both, in the body's frame

    def lose(self):
        """The feet are not known for a while (a limp robot, a gap): the next snapshot starts over."""
        self._old = self._last = None

    def step(self, legs):
        """Move the body by these legs (four points a leg, body frame, mm); its (x, y, yaw)."""
        body = self.body
        body.set_legs(legs)
        x, y, theta = body.x, body.y, body.theta
        body.move(self._old)
        if len(body.stance) >= 2:
            c, si = math.cos(theta), math.sin(theta)
            dx, dy = body.x - x, body.y - y
            self._last = (body.theta - theta, c * dx + si * dy, -si * dx + c * dy)
        elif self._old is not None and self._last is not None:
            # No foot on the ground in both snapshots: a stance changed hands between them (a
            # recording of every other frame or fewer); the gait goes on as it went.
            body.advance(*self._last)
        self._old = body.feet
        return body.x, body.y, body.theta


def poses(snaps, world, board="pico"):
    """The body's (x, y mm, yaw rad) in the world for each snapshot (dicts, in order)."""
    body = Body(board)
    side, distance = start(snaps, world)
    place_at_start(body, world, side, distance)
    odometry = Odometry(body)
    return [odometry.step(s["legs"]) for s in snaps]
