"""hexapod.tick.Robot's jog mode on a FrameBuffer, the default robot's calibration rows (robots/default_cal.py)."""

from scenarios.refusal import message
from scenarios.rig import TICK_MS, stand

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


def calibrate_reaches_the_chip_at_once():
    """Issue 24: a range or trim change must never leave the frame sink (the PCA9685s) driving a
    pulse outside the new range. Leg 3 femur (servo 7; robots/default_cal.py: centre 1500, dir 1,
    600..2400) jogged to 2118 us, then, with no tick between, a trim to centre 1200 and a range of
    590..1858; then the same on a standing robot whose frames are held. Rows: each step's (code, sink's pulse)."""
    g = geometry.load(robot_file)
    fb = tick.FrameBuffer()
    robot = tick.Robot(g, robotcal.servo_maps(robotcal.load("default")), fb)
    out = [robot.jog_pulse(2, 1, 2118)]
    robot.tick(0)
    out.append(fb.pulses[7])
    out.append((robot.calibrate(7, 1200, 1, 600, 2400), fb.pulses[7]))
    out.append((robot.calibrate(7, 1200, 1, 590, 1858), fb.pulses[7]))
    # Standing, frames held (leg 2 femur's map swapped for one its standing angle misses): the
    # sink keeps the last frame sent, so a calibration that waits for a frame never arrives.
    fb = tick.FrameBuffer()
    robot = tick.Robot(g, robotcal.servo_maps(robotcal.load("default")), fb)
    if robot.stand_up() != 0:
        return out
    t = stand(robot, 0)
    before = fb.pulses[10]  # leg 4 femur
    robot.servos[4].min_us = robot.servos[4].max_us - 1  # as clamped_frame: the next frame is held
    robot.tick(t)
    out.append((robot.reason, fb.pulses[10] == before))
    # pico leg 4 femur: centre 1500, dir -1; 40 us down keeps its standing angle inside 600..2400
    s = robot.servos[10]
    out.append((robot.calibrate(10, 1460, -1, 600, before - 1), fb.pulses[10] - before, s.max_us))
    return out
