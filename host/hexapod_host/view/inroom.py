"""A recording without a room (a board's: its body never leaves the origin) replayed in a wall
simulator world (`hexapod view --replay FILE --world W`): the body is put at the world's start
and moved by its recorded feet, the wall simulator's kinematic mover (hexapod_host.wall.room's
Body.move: the feet on the ground in two snapshots in a row stay put in the world, the body's
step is their least-squares rigid motion). Where a stance changes hands between two snapshots
two frames apart (a board streams every other frame) the frame between is the hand-over: see
through_hand_over.

Start: as `hexapod sim wall` places its robot (wall.sim.place_at_start), facing along the start
wall, the followed side's sonar midpoint at the distance those two sonars first read together
(the recorded follow side, else the world's), or at START_MM when they never both read.
"""

import math

from hexapod_host.wall.room import Body, grounded, rigid_2d
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


def through_hand_over(body, old_feet):
    """Move the body over the one frame missing between old_feet and its feet (body frame, mm),
    where the stance changed hands: the feet on the ground in the first snapshot carry it to the
    missing frame, those on the ground in the second carry it on (as the wall simulator's mover
    does frame by frame: in its hand-over frame all six are down). The missing frame's feet are
    taken halfway between the two snapshots': the feet move smoothly in the body frame, and a
    foot lifting (or landing) in the next frame still moves much as it did on the ground.
    False (body not moved) unless each snapshot has two feet on the ground."""
    first = [k for k, on in enumerate(grounded(old_feet)) if on]
    second = [k for k, on in enumerate(grounded(body.feet)) if on]
    if len(first) < 2 or len(second) < 2:
        return False
    mid = [((a[0] + b[0]) / 2, (a[1] + b[1]) / 2) for a, b in zip(old_feet, body.feet, strict=True)]
    body.advance(*rigid_2d([mid[k] for k in first], [old_feet[k][:2] for k in first]))
    body.advance(*rigid_2d([body.feet[k][:2] for k in second], [mid[k] for k in second]))
    return True


class Odometry:
    """The body's world pose from its feet, one snapshot after another (the module's mover): a
    Body (hexapod_host.wall.room) placed where it starts, stepped with each snapshot's legs."""

    def __init__(self, body):
        self.body = body
        self._old = None  # the feet of the snapshot before (None: start over from these)
        self._frame = None  # its frame
        self._last = None  # the last step made with feet down in both, in the body's frame

    def lose(self):
        """The feet are not known for a while (a limp robot, a gap): the next snapshot starts over."""
        self._old = self._last = None

    def step(self, legs, frame):
        """Move the body by these legs (four points a leg, body frame, mm) of this frame; its
        (x, y, yaw)."""
        body = self.body
        old = self._old
        body.set_legs(legs)
        x, y, theta = body.x, body.y, body.theta
        body.move(old)
        if len(body.stance) >= 2:
            c, si = math.cos(theta), math.sin(theta)
            dx, dy = body.x - x, body.y - y
            self._last = (body.theta - theta, c * dx + si * dy, -si * dx + c * dy)
        elif old is not None and frame - self._frame == 2 and through_hand_over(body, old):
            # No foot on the ground in both snapshots two frames apart: the stance changed hands
            # in the frame between, rebuilt from its neighbours. The step before does not stand in
            # for it: the mover's step turns the same way at the same point of every stride (the
            # pulses' 1 us steps), and a follower holding one command for strides piled that up.
            pass
        elif old is not None and self._last is not None:
            # Further apart, the frame of the hand-over is not known: the gait goes on as it went.
            body.advance(*self._last)
        self._old, self._frame = body.feet, frame
        return body.x, body.y, body.theta


def poses(snaps, world, board="pico"):
    """The body's (x, y mm, yaw rad) in the world for each snapshot (dicts, in order)."""
    body = Body(board)
    side, distance = start(snaps, world)
    place_at_start(body, world, side, distance)
    odometry = Odometry(body)
    return [odometry.step(s["legs"], s["frame"]) for s in snaps]
