"""What a command may ask, checked before anything moves: the walk's velocity bounds and the wall
follower's request, and is_whole. Pure, imports nothing of the core: it sits below everything
that obeys it (the walker, the turns, the follower) and everything that checks a request ahead of
them (a board file's "follow" setting, the console), so a check never pulls in the walker.

Units: speeds 0.1 mm/s, yaw rates cdeg/s, the set point 0.1 mm (the side sonar's reading, as in
seed 000).
"""

from micropython import const


def is_whole(v):
    """True for an int that is not a bool: the integer test every value check in the core uses."""
    return isinstance(v, int) and not isinstance(v, bool)


SPEED_MAX = const(3000)  # largest |vx|, |vy| a walk accepts, 0.1 mm/s
YAW_RATE_MAX = const(9000)  # largest |yaw rate| a walk accepts, cdeg/s

SIDES = ("left", "right")  # the wall followed
# The PID output as a yaw rate (Robot.walk), as seed 000's coxa sweeps, or as a sideways speed (crab: the
# robot turns only to keep the sonars in their beam; hexapod.follow, docs/wall.md).
FORMS = ("yaw", "sweeps", "crab")
SETPOINT_MIN = const(400)  # the follower's set point (the side sonar's reading), 0.1 mm
SETPOINT_MAX = const(5000)
SPEED_MIN = const(100)  # the follower's forward speed: SPEED_MIN..SPEED_MAX, 0.1 mm/s


def check_request(side, setpoint, speed=None, form="crab"):
    """ValueError naming the first bad value of a wall-follow request among side, setpoint
    (0.1 mm), speed (0.1 mm/s, None: the follower's default) and form."""
    if side not in SIDES:
        raise ValueError("side: %r, allowed 'left' or 'right'" % (side,))
    if not is_whole(setpoint) or setpoint < SETPOINT_MIN or setpoint > SETPOINT_MAX:
        raise ValueError(
            "setpoint: %r is outside %d..%d (0.1 mm, the side sonar's reading)" % (setpoint, SETPOINT_MIN, SETPOINT_MAX)
        )
    if speed is not None and (not is_whole(speed) or speed < SPEED_MIN or speed > SPEED_MAX):
        raise ValueError("speed: %r is outside %d..%d (0.1 mm/s)" % (speed, SPEED_MIN, SPEED_MAX))
    if form not in FORMS:
        raise ValueError("form: %r, allowed 'yaw', 'sweeps' or 'crab'" % (form,))
