"""hexapod.robotcal on robots/default_cal.py: the shipped calibration, mutations of it, its maps."""

from scenarios.boards import thaw

import robots.default as geo
import robots.default_cal as cal
from hexapod import robotcal

DELETE = "<delete>"
GOOD = {"REFERENCE": cal.REFERENCE, "SERVOS": cal.SERVOS, "SONARS": cal.SONARS}


def mutated(path, value):
    """A deep copy of GOOD with the item at path replaced by value (or deleted: DELETE)."""
    d = thaw(GOOD)
    o = d
    for k in path[:-1]:
        o = o[k]
    if value == DELETE:
        del o[path[-1]]
    else:
        o[path[-1]] = value
    return d


def why(fn, *args):
    """fn(*args)'s ValueError message, or "accepted"."""
    try:
        fn(*args)
        return "accepted"
    except ValueError as e:
        return str(e)


def check(d, limits=geo.LIMITS):
    return why(robotcal.validate, "default", d, limits)


def mutations(changes):
    """The message of each (path, value) mutation's validation."""
    return [check(mutated(p, v)) for p, v in changes]


def shipped():
    """GOOD, a copy of it and GOOD without limits checked; load() gives something; 18 servo maps."""
    return [
        check(GOOD),
        check(thaw(GOOD)),
        check(GOOD, None),
        robotcal.load("default", geo.LIMITS) is not None,
        len(robotcal.servo_maps(robotcal.load("default"))),
    ]


def failing_changes_nothing():
    """(the refused data unchanged, its message names centre_us, the shipped rows unchanged)."""
    d = mutated(("SERVOS", 3, 2), 2450)
    before = repr(d)
    r = check(d)
    return (repr(d) == before, "centre_us" in r, repr(GOOD["SERVOS"]) == repr(cal.SERVOS))


def load_error(name):
    return why(robotcal.load, name)


def maps_and_mounts():
    """Each servo map's pulse at every 0.5 degree inside its joint's limits, the first leg's
    reference angles, the sonar mounts, and whether servo_maps makes fresh maps each call."""
    c = robotcal.load("default", geo.LIMITS)
    maps = robotcal.servo_maps(c)
    lim = geo.LIMITS
    pulses = [[maps[k].raw(a) for a in range(lim[2 * (k % 3)], lim[2 * (k % 3) + 1] + 1, 50)] for k in range(18)]
    fresh = maps[0] is not robotcal.servo_maps(c)[0]
    return (pulses, [m.ref_cdeg for m in maps[:3]], robotcal.sensor_mounts(c), fresh)
