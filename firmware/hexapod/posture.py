"""Stand-up, sit-down, relax and body-height moves: feet travel in lockstep from wherever they are.

A move is up to three waypoint sets (each six body-frame feet, FINE units). All feet go
along straight lines and arrive together; the foot with the farthest to go moves at most
POSTURE_STEP (0.1 mm) per tick, so no servo jumps far in one frame.

- stand up: feet rise to just above the ground the body rests on (the body sits down
  first if it was up), slide over to the neutral stance, then push the body up.
- sit down: feet rise until the body rests on the ground and they lift FOOT_CLEARANCE off it;
  a foot that is not at its neutral place then (a jogged leg) slides there, just clear of the ground.
Both come in two variants (`straight`: a foot above the resting height comes down to it before
the slide, or stays up and comes down along the slide): hexapod.tick tries the path of one,
then the other, frame by frame before it queues a move.
- relax: sit down, then the servos go limp (the tick sends pulse 0).
"""

from micropython import const

from hexapod.body import FINE_SHIFT
from hexapod.fixmath import isqrt

POSTURE_STEP = const(20)  # most a foot moves per tick, 0.1 mm (100 mm/s at 50 Hz)


class Posture:
    """A queued lockstep move of the six feet of a Walker's fx/fy/fz arrays."""

    def __init__(self):
        self.way = [0] * 54  # up to three sets of (x, y, z) for legs 1..6, fine
        self.sets = 0
        self.index = 0
        self.start = [0] * 18
        self.n = 0  # ticks in the current segment
        self.k = 0  # ticks done in it

    def clear(self):
        self.sets = 0
        self.index = 0
        self.n = 0
        self.k = 0

    def stand_up(self, walker, rest_z, straight=False):
        """Queue: clear the ground at rest_z (fine), slide to neutral, lower to walker.ground.
        straight: a foot above rest_z comes down to it first too (else it stays up until the slide)."""
        self._to_rest(walker, rest_z, straight)
        w = self.way
        for i in range(6):
            b = 3 * i
            w[36 + b] = walker.nx[i]
            w[37 + b] = walker.ny[i]
            w[38 + b] = walker.ground
        self._begin(walker, 3)

    def sit_down(self, walker, rest_z, straight=True):
        """Queue: every foot straight up or down to rest_z (fine), then to the neutral stance at
        rest_z. straight False: a foot above rest_z stays up until the slide."""
        self._to_rest(walker, rest_z, straight)
        self._begin(walker, 2)

    def _to_rest(self, walker, rest_z, straight):
        w = self.way
        for i in range(6):
            b = 3 * i
            w[b] = walker.fx[i]
            w[b + 1] = walker.fy[i]
            w[b + 2] = walker.fz[i] if walker.fz[i] > rest_z and not straight else rest_z
            w[18 + b] = walker.nx[i]
            w[19 + b] = walker.ny[i]
            w[20 + b] = rest_z

    def to_height(self, walker, z):
        """Queue: every foot straight up or down to body-frame z (fine)."""
        for i in range(6):
            self.way[3 * i] = walker.fx[i]
            self.way[3 * i + 1] = walker.fy[i]
            self.way[3 * i + 2] = z
        self._begin(walker, 1)

    def _begin(self, walker, sets):
        self.sets = sets
        self.index = 0
        self._segment(walker)

    def _segment(self, walker):
        """Start the next waypoint set from the feet as they are; skip sets already reached."""
        while self.index < self.sets:
            base = 18 * self.index
            far = 0
            for i in range(6):
                self.start[3 * i] = walker.fx[i]
                self.start[3 * i + 1] = walker.fy[i]
                self.start[3 * i + 2] = walker.fz[i]
                dx = (self.way[base + 3 * i] - walker.fx[i]) >> FINE_SHIFT
                dy = (self.way[base + 3 * i + 1] - walker.fy[i]) >> FINE_SHIFT
                dz = (self.way[base + 3 * i + 2] - walker.fz[i]) >> FINE_SHIFT
                d = isqrt(dx * dx + dy * dy + dz * dz) + 1
                if d > far:
                    far = d
            same = True
            for k in range(18):
                if self.way[base + k] != self.start[k]:
                    same = False
            if not same:
                self.n = (far + POSTURE_STEP - 1) // POSTURE_STEP
                self.k = 0
                return
            self.index += 1

    def step(self, walker):
        """Advance one tick; True while a move is still running."""
        if self.index >= self.sets:
            return False
        self.k += 1
        base = 18 * self.index
        k = self.k
        n = self.n
        for i in range(6):
            b = 3 * i
            s = self.start
            w = self.way
            walker.fx[i] = s[b] + (w[base + b] - s[b]) * k // n
            walker.fy[i] = s[b + 1] + (w[base + b + 1] - s[b + 1]) * k // n
            walker.fz[i] = s[b + 2] + (w[base + b + 2] - s[b + 2]) * k // n
        if k >= n:
            self.index += 1
            self._segment(walker)
        return True
