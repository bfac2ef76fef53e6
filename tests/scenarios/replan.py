"""A command change in the middle of a swing: the plain swing (CPython) and the viper one (the VM)."""

from scenarios.rig import Rig


def late_re_aims(ticks, changes, keep_from):
    """Walking at 400 0 0 from a stand, a yaw or speed change at each tick in changes: (angles, foot x,
    foot y, swing ticks) of every tick from keep_from on."""
    rig = Rig()
    rig.stand()
    robot = rig.robot
    w = rig.w
    out = []
    robot.walk(400, 0, 0)
    for n in range(ticks):
        if n in changes:
            robot.walk(400 - n, 0, 9000 if n % 2 else -6000)
        rig.run(1)
        if n >= keep_from:
            out.append((list(robot.angles), list(w.fx), list(w.fy), list(w.su)))
    return out
