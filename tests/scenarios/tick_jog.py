"""hexapod.tick.Robot's jog mode on a FrameBuffer, the default robot's calibration rows (robots/default_cal.py)."""

from scenarios.refusal import message
from scenarios.rig import TICK_MS

import robots.default as robot_file
from hexapod import geometry, robotcal, tick


def jog_session():
    """The replies and frames of a jog of leg 2, its refusals, a limp leg's one servo, then standing up
    and going limp: see the test for each row."""
    g = geometry.load(robot_file)
    fb = tick.FrameBuffer()
    robot = tick.Robot(g, robotcal.servo_maps(robotcal.load("default")), fb)
    t = [0]

    def run(n):
        for _ in range(n):
            robot.tick(t[0])
            t[0] += TICK_MS

    out = []
    out.append(robot.jog_foot(1, 1300, 0, -800))  # leg 2, 0.1 mm
    run(2)
    out.append((robot.mode, list(fb.pulses)))
    out.append((robot.jog_foot(1, 4000, 0, -800), robot.jog_code, robot.jog_excess))
    out.append((robot.jog_joint(1, 2, 500), robot.jog_code, robot.jog_excess))  # tibia +5 deg: past 0
    out.append((robot.jog_pulse(1, 1, 2450), robot.jog_servo, robot.jog_code, robot.jog_excess))
    out.append((robot.calibrate(4, 1500, 1, 1600, 2400), robot.jog_servo, robot.jog_code, robot.jog_excess))
    out.append(list(fb.pulses) == out[1][1])
    out.append(
        [
            message(robot.jog_foot, 6, 0, 0, 0),
            message(robot.jog_joint, 1, 3, 0),
            message(robot.jog_pulse, 1, 0, 1500.0),
            message(robot.calibrate, 4, 1500, 0, 600, 2400),
            message(robot.calibrate, 4, 1500, 1, 2400, 600),
        ]
    )
    out.append((robot.jog_joint(0, 0, 1000), list(robot.pulses[:6])))
    out.append(robot.stand_up())
    run(1)
    out.append(list(robot.angles[3:6]))
    run(200)
    out.append(robot.mode)
    robot.go_limp()
    out.append((robot.mode, fb.pulses == [0] * 18))
    out.append(robot.faults)
    return out
