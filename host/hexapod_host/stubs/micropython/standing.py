"""Standing a robot up off the board: ask, then run frames until the robot is STANDING, at most a
bound of frames, and a clear error if it never gets there (a loop for ever is no test result).

The callers differ in what a frame is: a bare robot.tick(t) on a clock of their own, a Runner's
step, a console bench's frame. So a frame is the caller's: frame(n) runs frame n (0 = the first
after the ask), and the frames run come back, for the caller's clock (t + 20 ms * frames).

It lives beside the MicroPython stubs (host/hexapod_host/stubs/micropython) because that is the
one folder on every path that needs it: CPython's sys.path (hexapod_host puts it there), the
VM's MICROPYPATH (hexapod_host.mpvm.search_path: the tests' scenarios and the scripts in
host/hexapod_host/vm) and the emulated Pico's bench flash (hexapod_host.commands.pico adds it),
yet never on a board (hexapod_host.serial.flash stages firmware/, boards/ and robots/ only).
It is not a Robot method: that would add its bytes to every board's resident heap, for a loop
no board runs.
"""

from hexapod import tick
from hexapod.posture import POSTURE_STEP


def posture_frames(geometry):
    """The most frames a posture move (stand, sit, relax, height) can take on geometry.

    The soft start holds the first pose tick.WAKE_FRAMES frames; then up to three waypoint sets
    (hexapod.posture), in each the farthest foot moving POSTURE_STEP (0.1 mm) a frame. No foot
    goes farther than the diameter 2R of its leg's workspace: every reachable foot lies within
    R = coxa + femur + tibia + |femur_offset| (0.1 mm) of its coxa origin, and the body's pose is
    fixed during a move. A set is so at most ceil((2R + 1) / POSTURE_STEP) frames (posture's +1
    rounding); one more frame ends the move. robots/default.py: R = 2720, 24 + 3 * 273 + 1 = 844.
    """
    leg = geometry.legs[0]
    reach = leg.coxa + leg.femur + leg.tibia + (leg.femur_offset if leg.femur_offset > 0 else -leg.femur_offset)
    return tick.WAKE_FRAMES + 3 * ((2 * reach + 1 + POSTURE_STEP - 1) // POSTURE_STEP) + 1


def until_standing(robot, frame, most=None, asked=None):
    """Run frame(n) for n = 0, 1, ... until robot.mode is STANDING; return the frames run (0 if
    it already stood). most: the bound (None: posture_frames(robot.geometry)); past it,
    RuntimeError naming the mode and the robot's last reason. asked: what the ask answered,
    named in that error when it was a refusal (a tick reason code)."""
    if most is None:
        most = posture_frames(robot.geometry)
    n = 0
    while robot.mode != tick.STANDING:
        if n >= most:
            why = "" if not asked else "; the ask answered: " + tick.describe(asked)
            raise RuntimeError(
                "not standing after %d frames: mode %s, last reason: %s%s"
                % (most, tick.MODE_NAMES[robot.mode], tick.describe(robot.reason), why)
            )
        frame(n)
        n += 1
    return n


def stand(robot, frame, most=None):
    """robot.stand_up(), then until_standing(robot, frame, most): the frames it took."""
    return until_standing(robot, frame, most, robot.stand_up())
