"""A robot build checked and ready for the core: six Legs, their mounts and the neutral stance.

`load(module)` reads a plain-data module from robots/ (see robots/default.py for the names
and units: lengths 0.1 mm, angles cdeg) and raises ValueError naming the robot, the field
and what is allowed when something is wrong, before anything moves. The checks are in
hexapod.robotfile, imported only then: boot-only code that main.main forgets once it has
built the robot (hexapod.release), so its heap goes back to the loop.
"""

from hexapod.fixmath import cos, sin
from hexapod.leg import Leg


def leg_from(data):
    """One Leg from a robot file's COXA, FEMUR, TIBIA, FEMUR_OFFSET and LIMITS (ValueError if bad)."""
    return Leg(
        coxa=data["COXA"],
        femur=data["FEMUR"],
        tibia=data["TIBIA"],
        femur_offset=data["FEMUR_OFFSET"],
        limits=data["LIMITS"],
    )


class Geometry:
    """A checked robot build; legs[i] is leg i + 1 (1 RF ... 6 LF)."""

    def __init__(self, name, data):
        self.name = name
        self.legs = [leg_from(data) for _ in range(6)]
        m = data["MOUNTS"]
        self.mount_x = [m[i][0] for i in range(6)]
        self.mount_y = [m[i][1] for i in range(6)]
        self.mount_angle = [m[i][2] for i in range(6)]
        self.mount_cos = [cos(a) for a in self.mount_angle]  # Q15
        self.mount_sin = [sin(a) for a in self.mount_angle]
        self.neutral_reach = data["NEUTRAL_REACH"]
        self.body_height = data["BODY_HEIGHT"]
        self.body_height_min = data["BODY_HEIGHT_MIN"]
        self.body_height_max = data["BODY_HEIGHT_MAX"]
        self.sit_height = data["SIT_HEIGHT"]
        self.foot_clearance = data["FOOT_CLEARANCE"]
        self.limits = tuple(data["LIMITS"])
        servo = data.get("SERVO")
        # The most the walk may turn a joint in one 20 ms tick, cdeg: the planner's share of
        # the no-load speed (0: no servo given, no limit).
        self.servo_step = 0
        if servo is not None and "planner_share_permille" in servo:
            self.servo_step = 6000 * 20 * servo["planner_share_permille"] // (servo["speed_ms_per_60deg"] * 1000)
        # How much farther from its coxa axis than neutral a stance foot on three feet (the
        # tripod) may be, 0.1 mm (0: no limit): the femur holds the body on that lever.
        self.stance_out_max = servo.get("stance_out_max", 0) if servo is not None else 0
        self.servo = servo
        # Each gait's cycle time until one is set (ms; tripod, tetrapod, ripple, wave).
        self.gait_cycle_ms = tuple(data.get("GAIT_CYCLE_MS") or (1000, 1000, 1000, 1000))

    def neutral_xy(self, i, out, j=0):
        """Body-frame (x, y) of leg i's neutral foot (0-based i), 0.1 mm, into out[j:j+2]."""
        r = self.neutral_reach
        out[j] = self.mount_x[i] + ((r * self.mount_cos[i] + 16384) >> 15)
        out[j + 1] = self.mount_y[i] + ((r * self.mount_sin[i] + 16384) >> 15)
        return out


def load(module, check=True):
    """A checked Geometry from a robots/ module (or any object with the same attributes); check
    False: unchecked, without importing the checks, for the file `hexapod flash` checked on the
    host (hexapod.wiring.load)."""
    if not check:
        return Geometry(getattr(module, "NAME", None) or module.__name__, module.__dict__)
    from hexapod import robotfile

    return robotfile.load(module)


def from_data(name, data):
    """A checked Geometry from a dict of the robots/ fields; ValueError names what is wrong."""
    from hexapod import robotfile

    return robotfile.from_data(name, data)
