"""A robot's calibration file, robots/<robot>_cal.py: what belongs to the robot, not the board.

Plain data (see robots/default_cal.py): REFERENCE, the joint angle each joint's servos are
calibrated at (cdeg: coxa, femur, tibia); SERVOS, 18 rows (leg, joint, centre_us, direction,
min_us, max_us) with centre_us the pulse at that reference angle; SONARS, where each sonar
sits: (name, x, y, heading), 0.1 mm and cdeg in the body frame. load() checks it whole before
anything moves: one ValueError naming the robot, the place, what is wrong and what is allowed.
The board file says which chip channel drives each servo and which pins each sonar has
(hexapod.board); the console's calibration file (calstore, written by `save`) overrides trim,
direction and range at run time. Pure: no hardware imports.
"""

from micropython import const

from hexapod.check import Check, is_identifier
from hexapod.sensors import SENSOR_NAMES, check_mounts
from hexapod.servo import ServoMap
from hexapod.wiring import JOINTS, sensor_mounts, servo_maps  # noqa: F401 (this module's names too)

# The file's fields (REFERENCE, SERVOS, SONARS) and its rows' shapes are written out where they
# are used: a module-level name is a qstr that stays in the board's heap after the release.
_XY_MAX = const(10000)  # largest |x|, |y| of a sonar, 0.1 mm


def validate(name, data, limits=None):
    """Check a calibration (a dict of REFERENCE, SERVOS, SONARS); limits: the robot's six joint limits (cdeg: coxa
    min, max, femur min, max, tibia min, max), each reference must lie inside them. Returns
    data unchanged, or raises ValueError naming the first mistake."""
    ck = Check("robot", name)
    ck.dict_of("calibration", data, ("REFERENCE", "SERVOS", "SONARS"))
    ref = ck.seq("REFERENCE", data["REFERENCE"], 3, "(coxa, femur, tibia) in cdeg")
    for j in range(3):
        where = "REFERENCE %s" % JOINTS[j]
        a = ck.int_in(where, ref[j], -18000, 18000, " (0.01 deg)")
        if a % 100:
            ck.fail(where, "%d, allowed whole degrees (a multiple of 100 cdeg)" % a)
        if limits is not None and (a < limits[2 * j] or a > limits[2 * j + 1]):
            lo, hi = limits[2 * j], limits[2 * j + 1]
            ck.fail(where, "%d is outside the robot's %s limits %d..%d cdeg" % (a, JOINTS[j], lo, hi))
    rows = _servos(ck, data["SERVOS"])
    for k in range(18):
        where, s = rows[k]
        for i, field in ((2, "centre_us"), (3, "direction"), (4, "min_us"), (5, "max_us")):
            if not isinstance(s[i], int) or isinstance(s[i], bool):
                ck.fail(where + " " + field, "%r, allowed an integer" % (s[i],))
        try:
            ServoMap(centre_us=s[2], direction=s[3], min_us=s[4], max_us=s[5], ref_cdeg=ref[k % 3])
        except ValueError as e:
            ck.fail(where, str(e))
    sonars = ck.named("SONARS", data["SONARS"], 4, "(name, x, y, heading)", SENSOR_NAMES, "sonar")
    for n in SENSOR_NAMES:  # the headings are check_mounts' to judge
        for i in (1, 2):
            ck.int_in("sonar %s %s" % (n, "x" if i == 1 else "y"), sonars[n][i], -_XY_MAX, _XY_MAX, " (0.1 mm)")
    try:
        check_mounts(sensor_mounts(data))
    except ValueError as e:
        ck.fail("SONARS", str(e))
    return data


def _servos(ck, v):
    """18 rows (leg, joint, ...), one per servo: {k: (where, row)}, k = (leg - 1) * 3 + joint and
    where "SERVOS[i] (leg L joint)" for the row's own messages."""
    shape = "(leg, joint, centre_us, direction, min_us, max_us)"
    ck.seq("SERVOS", v, -1, "of rows (leg, joint, centre_us, direction, min_us, max_us)")
    by = {}
    for i in range(len(v)):
        at = "%s[%d]" % ("SERVOS", i)
        s = ck.seq(at, v[i], 6, shape)
        leg = ck.int_in(at + " leg", s[0], 1, 6)
        k = (leg - 1) * 3 + JOINTS.index(ck.one_of(at + " joint", s[1], JOINTS))
        at = "%s (leg %d %s)" % (at, leg, s[1])
        if k in by:
            ck.fail(at, "listed twice (first at %s)" % (by[k][0].split(" ")[0],))
        by[k] = (at, s)
    for k in range(18):
        if k not in by:
            ck.fail("SERVOS", "missing servo leg %d %s" % (k // 3 + 1, JOINTS[k % 3]))
    return by


def load(robot, limits=None):
    """Import robots/<robot>_cal.py and return its validated calibration (a dict of REFERENCE,
    SERVOS, SONARS)."""
    if not is_identifier(robot):
        raise ValueError("robot name %r: allowed a file name in robots/ without .py" % (robot,))
    try:
        module = __import__("robots.%s_cal" % robot, None, None, ("SERVOS",))
    except ImportError:
        raise ValueError(
            "robot %r: no robots/%s_cal.py (the robot's servo calibration and sonar mounts)" % (robot, robot)
        ) from None
    data = {}
    for field in ("REFERENCE", "SERVOS", "SONARS"):
        if not hasattr(module, field):
            raise ValueError("robot %r: robots/%s_cal.py defines no %s" % (robot, robot, field))
        data[field] = getattr(module, field)
    return validate(robot, data, limits)
