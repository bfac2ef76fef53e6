"""Robot files (robots/<name>.py): read one and check it whole before anything moves; one
ValueError naming the robot, the field and what is allowed. Boot-only: hexapod.geometry.load
imports it, main.main forgets it once the robot is built (hexapod.release). Units as in
robots/default.py: lengths 0.1 mm, angles cdeg.
"""

from micropython import const

from hexapod.fixmath import sin
from hexapod.gait import CYCLE_MS_MAX, CYCLE_MS_MIN, NAMES
from hexapod.geometry import Geometry, leg_from
from hexapod.leg import OK, describe

LEG_NAMES = ("RF", "RM", "RR", "LR", "LM", "LF")
# Private constants (folded, no name kept on the board: a name is a qstr that outlives the release).
_MOUNT_MAX = const(5000)  # largest |x|, |y| of a coxa axis, 0.1 mm
_HEIGHT_MAX = const(3000)  # largest body height, 0.1 mm
# The optional SERVO dict of a robot file: key -> (smallest, largest allowed, unit).
SERVO_FIELDS = (
    ("stall_torque_mnm", 50, 100000, "mN m"),
    ("speed_ms_per_60deg", 20, 2000, "ms per 60 degrees, no load"),
    ("mass_g", 1, 1000, "g"),
    ("kp_mnm_per_rad", 100, 10000000, "mN m per rad"),
    ("armature_g_cm2", 0, 10000000, "g cm^2"),
    ("planner_share_permille", 50, 1000, "per mille of the no-load speed the walk may ask"),
    ("stance_out_max", 10, 2000, "0.1 mm a stance foot may be farther from its coxa than neutral"),
)
# Absent: the walk does not limit joint speeds, nor how far out a stance foot goes.
SERVO_OPTIONAL = ("planner_share_permille", "stance_out_max")
_FIELDS = const(
    (
        "COXA",
        "FEMUR",
        "TIBIA",
        "FEMUR_OFFSET",
        "LIMITS",
        "MOUNTS",
        "NEUTRAL_REACH",
        "BODY_HEIGHT",
        "BODY_HEIGHT_MIN",
        "BODY_HEIGHT_MAX",
        "SIT_HEIGHT",
        "FOOT_CLEARANCE",
    )
)


def load(module):
    """A Geometry from a robots/ module (or any object with the same attributes)."""
    name = getattr(module, "NAME", None) or getattr(module, "__name__", "robot")
    data = {}
    for field in _FIELDS:
        if not hasattr(module, field):
            raise ValueError("robot %r: %s is missing" % (name, field))
        data[field] = getattr(module, field)
    if hasattr(module, "SERVO"):
        data["SERVO"] = module.SERVO
    if hasattr(module, "GAIT_CYCLE_MS"):
        data["GAIT_CYCLE_MS"] = module.GAIT_CYCLE_MS
    return from_data(name, data)


def from_data(name, data):
    """A Geometry from a dict of the robots/ fields; ValueError names what is wrong."""
    pre = "robot %r: " % (name,)
    try:
        leg_from(data)
    except ValueError as err:
        raise ValueError(pre + str(err)) from None
    _check_mounts(pre, data["MOUNTS"])
    reach = data["COXA"] + data["FEMUR"] + data["TIBIA"]
    _int(pre, "NEUTRAL_REACH", data["NEUTRAL_REACH"], data["COXA"] + 1, reach - 1)
    _int(pre, "BODY_HEIGHT_MIN", data["BODY_HEIGHT_MIN"], 1, _HEIGHT_MAX)
    _int(pre, "BODY_HEIGHT_MAX", data["BODY_HEIGHT_MAX"], data["BODY_HEIGHT_MIN"], _HEIGHT_MAX)
    _int(pre, "BODY_HEIGHT", data["BODY_HEIGHT"], data["BODY_HEIGHT_MIN"], data["BODY_HEIGHT_MAX"])
    _int(pre, "SIT_HEIGHT", data["SIT_HEIGHT"], 0, data["BODY_HEIGHT_MIN"] - 1)
    _int(pre, "FOOT_CLEARANCE", data["FOOT_CLEARANCE"], 0, data["SIT_HEIGHT"])
    if data.get("SERVO") is not None:
        check_servo(pre, data["SERVO"])
    cycles = data.get("GAIT_CYCLE_MS")
    if cycles is not None:
        if not isinstance(cycles, (tuple, list)) or len(cycles) != len(NAMES):
            raise ValueError(pre + "GAIT_CYCLE_MS: need %d cycle times (ms): %s" % (len(NAMES), ", ".join(NAMES)))
        for k in range(len(NAMES)):
            _int(pre, "GAIT_CYCLE_MS %s (ms)" % NAMES[k], cycles[k], CYCLE_MS_MIN, CYCLE_MS_MAX)
    g = Geometry(name, data)
    # Every height the robot may stand or rest at must be a reachable neutral stance.
    leg = g.legs[0]
    out = [0, 0, 0]
    for label, h in (
        ("BODY_HEIGHT", g.body_height),
        ("BODY_HEIGHT_MIN", g.body_height_min),
        ("BODY_HEIGHT_MAX", g.body_height_max),
        ("SIT_HEIGHT", g.sit_height),
        ("SIT_HEIGHT - FOOT_CLEARANCE", g.sit_height - g.foot_clearance),
    ):
        code = leg.ik(g.neutral_reach, 0, -h, out)
        if code != OK:
            raise ValueError(
                pre
                + "the neutral foot (NEUTRAL_REACH %d, %s %d) is not reachable: %s"
                % (g.neutral_reach, label, h, describe(code, leg.excess))
            )
    return g


def check_servo(pre, servo):
    """ValueError (prefixed by pre) unless servo is a dict of the SERVO_FIELDS, each in range."""
    check_table(pre, "SERVO", servo, SERVO_FIELDS, SERVO_OPTIONAL)


def check_table(pre, label, table, fields, optional=()):
    """ValueError (pre + label ...) unless table is a dict of exactly `fields` ((key, lo, hi,
    unit), whole numbers in lo..hi), keys in `optional` may be left out."""
    names = [f[0] for f in fields]
    if not isinstance(table, dict):
        raise ValueError(pre + "%s: need a dict of %s, got %r" % (label, ", ".join(names), table))
    for key in table:
        if key not in names:
            raise ValueError(pre + "%s: unknown key %r, allowed: %s" % (label, key, ", ".join(names)))
    for name, lo, hi, unit in fields:
        if name not in table:
            if name in optional:
                continue
            raise ValueError(pre + "%s: %s is missing (%s, %d..%d)" % (label, name, unit, lo, hi))
        _int(pre, "%s %s (%s)" % (label, name, unit), table[name], lo, hi)


def _check_mounts(pre, mounts):
    if not isinstance(mounts, (tuple, list)) or len(mounts) != 6:
        raise ValueError(pre + "MOUNTS: need 6 (x, y, angle) entries, legs 1 RF .. 6 LF")
    for i in range(6):
        m = mounts[i]
        leg = "MOUNTS leg %d (%s)" % (i + 1, LEG_NAMES[i])
        if not isinstance(m, (tuple, list)) or len(m) != 3:
            raise ValueError(pre + leg + ": need (x, y, angle), got %r" % (m,))
        _int(pre, leg + " x", m[0], -_MOUNT_MAX, _MOUNT_MAX)
        _int(pre, leg + " y", m[1], -_MOUNT_MAX, _MOUNT_MAX)
        _int(pre, leg + " angle", m[2], -18000, 18000)
        # Legs 1-3 are on the right (y < 0), 4-6 on the left, and each points to its side.
        right = i < 3
        if (m[1] >= 0) if right else (m[1] <= 0):
            raise ValueError(
                pre + leg + ": y %d must be %s" % (m[1], "< 0 (right side)" if right else "> 0 (left side)")
            )
        if (sin(m[2]) >= 0) if right else (sin(m[2]) <= 0):
            raise ValueError(
                pre + leg + ": angle %d cdeg must point %s" % (m[2], "right (-180..0)" if right else "left (0..180)")
            )
    # Clockwise from above: front legs ahead of the middle ones, middle ahead of the rear.
    for a, b in ((0, 1), (1, 2), (5, 4), (4, 3)):
        if mounts[a][0] <= mounts[b][0]:
            raise ValueError(
                pre
                + "MOUNTS: leg %d (%s) x %d must be ahead of leg %d (%s) x %d"
                % (a + 1, LEG_NAMES[a], mounts[a][0], b + 1, LEG_NAMES[b], mounts[b][0])
            )


def _int(pre, name, value, lo, hi):
    if not isinstance(value, int) or isinstance(value, bool):
        raise ValueError(pre + "%s: need a whole number, got %r" % (name, value))
    if value < lo or value > hi:
        raise ValueError(pre + "%s: %d is outside the allowed %d..%d" % (name, value, lo, hi))
