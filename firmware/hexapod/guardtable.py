"""The servo guard's answers for a robot file's own settings, made on the host.

A configure's reach discs (reach.disc_steps) and servo radii (reach.servo_steps) cost thousands
of IK solves: 2.5 s on a Pico, for the same answers every time the robot is powered up or
changes to a gait at its robot file's settings. robots/NAME_guard.py keeps those answers
(`hexapod bench guard --table` writes it; tests/test_guard_table.py checks each entry against
the live guard, bit for bit). An entry is used only for a level body (no pose) at the exact
height, lift, gait, cycle, step and reach discs it was made for, and only when the robot file
is the one it was made from (ROBOT, compared whole): anything else runs the live guard.

The table's fields (lengths 0.1 mm, ms, cdeg a tick):
    ROBOT = robot_key(geometry) of the robot file it was made from
    DISCS = ((height, lift, (rho x6)), ...)
    SERVO = ((gait, cycle_ms, lift, step, height, (rho x6), peak, (srho x6)), ...)
"""

from hexapod.body import FINE_SHIFT


def robot_key(geometry):
    """Everything of a Geometry the guard's answers depend on, as one tuple of integers."""
    leg = geometry.legs[0]
    key = [leg.coxa, leg.femur, leg.tibia, leg.femur_offset, geometry.neutral_reach, geometry.servo_step]
    key.extend(geometry.limits)
    for i in range(6):
        key.append(geometry.mount_x[i])
        key.append(geometry.mount_y[i])
        key.append(geometry.mount_angle[i])
    return tuple(key)


def find_table(geometry):
    """robots/NAME_guard.py for this geometry when it was made from the same robot file, else None."""
    try:
        table = __import__("robots.%s_guard" % geometry.name, None, None, ("ROBOT",))
    except ImportError:
        return None
    if tuple(table.ROBOT) != robot_key(geometry):
        return None  # made from another robot file: the live guard answers
    return table


def table_discs(table, body, ground, lift, out):
    """The reach discs for a level body at ground (fine) and lift into out; False when the table has none."""
    if not body.level:
        return False
    height = -ground >> FINE_SHIFT
    for row in table.DISCS:
        if row[0] == height and row[1] == lift:
            rho = row[2]
            for i in range(6):
                out[i] = rho[i]
            return True
    return False


def table_servo(table, walker, gait, cycle_ms, lift, step, rho):
    """The servo radii and the no-step peak into walker._srho and _peak for the walker's level
    pose_body at its ground; False when the table has no entry for exactly these settings."""
    body = walker.pose_body
    if body is None or not body.level:
        return False
    height = -walker.ground >> FINE_SHIFT
    for row in table.SERVO:
        if row[0] == gait and row[1] == cycle_ms and row[2] == lift and row[3] == step and row[4] == height:
            r = row[5]
            same = True
            for i in range(6):
                if r[i] != rho[i]:
                    same = False
            if same:
                walker._peak[0] = row[6]
                for i in range(6):
                    walker._srho[i] = row[7][i]
                return True
    return False
