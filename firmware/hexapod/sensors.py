"""The sensor contract: what the loop, the drivers, the wall follower, the data checks and the
console agree on, in one place. Pure: no I/O, no clock; never allocates in a frame.

Sonars (five HC-SR04, seed 000 Fig. 2). Their order is the index into every per-sonar buffer:
FRONT, LEFT_FRONT, LEFT_REAR, RIGHT_FRONT, RIGHT_REAR (SENSOR_NAMES). A ping reports a status
code (OK .. PENDING, STATUS_NAMES are the console's words for them) and, only with OK, a
distance in 0.1 mm; any other status leaves NO_DISTANCE in its place. A mount is (x, y,
heading): 0.1 mm in the body frame and cdeg counter-clockwise from forward; check_mounts says
whether five of them suit the wall follower (front facing forward, each side pair facing its
side, front sensor ahead of rear). DEFAULT_MOUNTS are the shipped robot's (robots/default_cal.py).

A frame sensor is what the loop (runner.Runner) asks of any sensor, once per 50 Hz frame:

    frame(now_ms) -> int   this frame's share of the work (a ping fired, an echo collected, an
                           ADC read): no waiting beyond what fits a frame, no allocation; the
                           index of the reading that came in this frame, -1 when none did
    faults                 readings that came back faulty so far (the status line counts them)

Its readings stay in its own buffers for whoever reads them. Sonars below is the sonar ring as
one; a battery monitor or an IMU would be another, handed to the Runner beside it.
"""

from micropython import const

from hexapod.limits import is_whole

FRONT = const(0)
LEFT_FRONT = const(1)
LEFT_REAR = const(2)
RIGHT_FRONT = const(3)
RIGHT_REAR = const(4)
SENSOR_NAMES = ("front", "left_front", "left_rear", "right_front", "right_rear")

OK = const(0)
OUT_OF_RANGE = const(1)  # nothing in range (the module's 38 ms no-echo hold; also what under 2 cm looks like)
NO_ECHO = const(2)  # the echo never rose (missing echo, unplugged module)
STUCK = const(3)  # the echo was already high before the trigger: nothing fired
TOO_CLOSE = const(4)  # an echo shorter than MIN_RANGE
WAIT = const(5)  # asked again too soon (or no result yet): nothing fired, buffers untouched
PENDING = const(6)  # fired, its echo not in yet (a driver's inside word; never in a buffer)
STATUS_NAMES = ("ok", "out_of_range", "no_echo", "stuck", "too_close", "wait", "pending")
NO_DISTANCE = const(-1)  # dist[i] whenever status[i] is not OK
MIN_RANGE = const(200)  # the HC-SR04's 2 cm, 0.1 mm: a TOO_CLOSE reading is nearer than this

# The shipped robot's mounts (robots/default_cal.py SONARS), SENSOR_NAMES order: side sonars on
# brackets 210 mm out, 200 mm apart.
DEFAULT_MOUNTS = (
    (1300, 0, 0),
    (1000, 2100, 9000),
    (-1000, 2100, 9000),
    (1000, -2100, -9000),
    (-1000, -2100, -9000),
)
# Each sonar's intended heading is 0 (front), 90 degrees (left pair) or -90 (right pair). Private
# constants here and below: folded into the code, no name kept on the board (a name costs heap).
_SIDE_HEADING = const(9000)  # cdeg
_HEADING_SLACK = const(1000)  # how far a mount may turn from it, cdeg (the beam is ~15 deg either side)
_BASELINE_MIN = const(500)  # a side pair's front sonar at least this far ahead of its rear one, 0.1 mm


def check_mounts(mounts):
    """ValueError unless mounts are 5 (x, y, heading) in SENSOR_NAMES order that the wall follower
    can use: front facing forward, side sonars facing their side (+-10 deg) on that side, each
    side's front sonar at least 50 mm ahead of its rear one."""
    if not isinstance(mounts, (tuple, list)) or len(mounts) != 5:
        raise ValueError("sensor mounts: need 5 (x, y, heading) in the order %s" % (", ".join(SENSOR_NAMES),))
    for k in range(5):
        m = mounts[k]
        if (
            not isinstance(m, (tuple, list))
            or len(m) != 3
            or not (is_whole(m[0]) and is_whole(m[1]) and is_whole(m[2]))
        ):
            raise ValueError("sensor mounts: %s: %r, allowed (x, y, heading) integers" % (SENSOR_NAMES[k], m))
        want = 0 if k == FRONT else (_SIDE_HEADING if k <= LEFT_REAR else -_SIDE_HEADING)
        if m[2] < want - _HEADING_SLACK or m[2] > want + _HEADING_SLACK:
            raise ValueError(
                "sensor mounts: %s heading %d cdeg, allowed %d..%d"
                % (SENSOR_NAMES[k], m[2], want - _HEADING_SLACK, want + _HEADING_SLACK)
            )
        if k and (m[1] <= 0 if k < 3 else m[1] >= 0):
            raise ValueError(
                "sensor mounts: %s y %d must be %s" % (SENSOR_NAMES[k], m[1], "> 0 (left)" if k < 3 else "< 0 (right)")
            )
    for f, r in ((LEFT_FRONT, LEFT_REAR), (RIGHT_FRONT, RIGHT_REAR)):
        if mounts[f][0] - mounts[r][0] < _BASELINE_MIN:
            raise ValueError(
                "sensor mounts: %s x %d must be at least 500 (50 mm) ahead of %s x %d"
                % (SENSOR_NAMES[f], mounts[f][0], SENSOR_NAMES[r], mounts[r][0])
            )


class Sonars:
    """The sonar ring as a frame sensor: a round robin (drivers.hcsr04.RoundRobin, or anything with
    tick(dist, status) -> the index whose result came in, -1 none) and the buffers it fills."""

    def __init__(self, ring, count=5):
        self.ring = ring
        self.distances = [NO_DISTANCE] * count  # 0.1 mm, NO_DISTANCE when not OK
        self.status = [WAIT] * count  # WAIT until a sonar has a first result
        self.faults = 0  # pings that came back OUT_OF_RANGE, NO_ECHO, STUCK or TOO_CLOSE

    def frame(self, now_ms):
        """One slot of the round robin; returns the sonar whose reading came in (-1: none)."""
        i = self.ring.tick(self.distances, self.status)
        if i >= 0:
            st = self.status[i]
            if st != OK and st != WAIT:
                self.faults += 1
        return i
