"""Robot build files: robots/default.py through hexapod.geometry."""

import robots.default as d
from hexapod import geometry


def default_robot():
    """[name, coxa, femur, tibia, femur offset, each leg's neutral foot (x, y), mount angles]."""
    g = geometry.load(d)
    xy = [0, 0]
    feet = [list(g.neutral_xy(i, xy)) for i in range(6)]
    leg = g.legs[0]
    return [g.name, leg.coxa, leg.femur, leg.tibia, leg.femur_offset, feet, g.mount_angle]


def refused(name, **changes):
    """The ValueError text of geometry.from_data(name, robots/default.py's fields with changes), or "accepted"."""
    fields = {}
    for k in dir(d):
        if k.isupper():
            fields[k] = getattr(d, k)
    fields.update(changes)
    try:
        geometry.from_data(name, fields)
        return "accepted"
    except ValueError as e:
        return str(e)
