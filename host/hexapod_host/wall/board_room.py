"""The virtual board's room (`hexapod virtual-board --world`): the wall simulator's room, in real time.

The room is the wall simulator's, not a copy: the beams cast into the world's walls
(hexapod_host.wall.sim.answers, room.beam_distance) and the body moved by its stance feet
(hexapod_host.wall.physics.FeetMover, room.Body.move). It runs here, on the host, because that
code is CPython-only (math.hypot, zip(strict=True), the float FK of hexapod_host.testing) and it
is what the simulator's figures were measured with; the VM script takes five distances before
each frame and gives back the 18 pulses the core sent after it, one line each way over two
pipes (hexapod_host.vm.virtual_board), so the board and the room step together, frame by frame.
No noise, dropouts, slip or speed error: the room answers exactly. The walls are not solid: a
robot steered into one walks through it (the simulator ends a trial there instead).

Units: mm and radians (the room's); the distances on the pipe are 0.1 mm, 0 = nothing heard.
"""

import contextlib
import threading

from hexapod_host.wall.physics import FeetMover
from hexapod_host.wall.room import Body
from hexapod_host.wall.sim import answers, place_at_start
from hexapod_host.wall.world import WorldError

# The side sonars' midpoint starts 15 cm from the start wall: 3 cm off a 12 cm set point, inside
# the simulator's start offsets (1-4 cm, hexapod_host.wall.sim.OFFSET_CM), so `wall left 12` has
# something to correct and every set point of seed 000 (8-16 cm) is a short walk away.
START_CM = 15


class Room:
    """A world with the robot at its start; serve() feeds a virtual board until it stops."""

    def __init__(self, world, start_cm=START_CM):
        self.world = world
        self.walls = world.walls
        self.body = body = Body()
        place_at_start(body, world, world.follow, start_cm * 10.0)
        standing = body.neutral_legs()  # the feet the first frame's are compared with
        touched = body.touches(self.walls)
        if touched >= 0:
            raise WorldError(
                "world %s: start: %g cm from wall %d the robot stands on wall %d (move start.along)"
                % (world.source, start_cm, world.start_wall, touched)
            )
        self.mover = FeetMover(body, standing)
        self.frames = 0  # frames the board has run in the room
        self.distances = self.pings()

    def pings(self):
        """What the five sonars hear from where the body is (0.1 mm, 0: nothing)."""
        return answers(self.body, self.walls)

    def frame(self, pulses):
        """The board ran a frame that sent these 18 pulses (us): move the body, cast the beams again."""
        self.mover.step(pulses, 1.0, 0.0)
        self.frames += 1
        self.distances = self.pings()

    def serve(self, to_vm, from_vm):
        """Feed the board's sonars over the pipes (file objects, text) until the board stops."""
        try:
            to_vm.write(line_of(self.distances))
            to_vm.flush()
            for line in from_vm:
                self.frame([int(v) for v in line.split()])
                to_vm.write(line_of(self.distances))
                to_vm.flush()
        except (BrokenPipeError, ValueError):  # the VM is gone (or its fds closed under us)
            pass
        finally:
            for f in (to_vm, from_vm):
                with contextlib.suppress(OSError):  # a write still buffered to a VM that is gone
                    f.close()

    def start(self, to_vm, from_vm):
        """serve() on a daemon thread; returns the thread."""
        t = threading.Thread(target=self.serve, args=(to_vm, from_vm), name="virtual-board-room", daemon=True)
        t.start()
        return t


def line_of(values):
    return " ".join(str(v) for v in values) + "\n"
