"""The servo speed guard on robots/default.py, the same integers on both runtimes."""

from scenarios.rig import stand

import robots.default as d
from hexapod import geometry, tick


def guard():
    """[step, radii, peak, then wave at 1 s (refused), wave, its radii and peak, ripple at 1.56 s, its
    radii and peak], and standing: [tripod at 1.68 s, a full sideways walk, the command, scale]."""
    g = geometry.load(d)
    robot = tick.Robot(g, tick.default_servos(g), tick.FrameBuffer())
    w = robot.walker
    out = [g.servo_step, list(w.srho), w.servo_peak]
    out += [robot.set_gait(3, 1000), robot.set_gait(3), list(w.srho), w.servo_peak]
    out += [robot.set_gait(2, 1560), list(w.srho), w.servo_peak]
    stand(robot)
    return [out, [robot.set_gait(0, 1680), robot.walk(0, 3000, 0), list(w.cmd), w.scale_permille]]
