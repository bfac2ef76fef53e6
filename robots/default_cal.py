"""Calibration of the default robot: each servo's pulse at its joint's reference angle, its
direction and range, and where the five sonars sit. Plain data, read by hexapod.robotcal.load.

This is the robot's, whichever board drives it: the board file (boards/) says which PCA9685
channel drives each servo and which pins each sonar has. The rows are seed 001's defaults
(10 us per degree, 600..2400 us): measure your servos and replace them, or trim them at the
console (`trim`, `dir`, `range`, `save`: hexapod_cal.txt on the board overrides these rows).

Units: pulses us, angles centidegrees, lengths 0.1 mm. Body frame: x forward, y left, z up.
"""

# The joint angle each servo is calibrated at, cdeg (coxa, femur, tibia): centre_us below is
# the pulse there. Coxa and femur at 0; the tibia mid-travel, its -90 degree knee (the middle
# of its -180..0 limits), so a trim has room both ways.
REFERENCE = (0, 0, -9000)

# Femur and tibia servos of the left side are mounted mirrored, hence direction -1.
SERVOS = (
    # leg, joint, centre_us (the pulse at the reference angle), direction, min_us, max_us
    (1, "coxa", 1500, 1, 600, 2400),
    (1, "femur", 1500, 1, 600, 2400),
    (1, "tibia", 1500, 1, 600, 2400),
    (2, "coxa", 1500, 1, 600, 2400),
    (2, "femur", 1500, 1, 600, 2400),
    (2, "tibia", 1500, 1, 600, 2400),
    (3, "coxa", 1500, 1, 600, 2400),
    (3, "femur", 1500, 1, 600, 2400),
    (3, "tibia", 1500, 1, 600, 2400),
    (4, "coxa", 1500, 1, 600, 2400),
    (4, "femur", 1500, -1, 600, 2400),
    (4, "tibia", 1500, -1, 600, 2400),
    (5, "coxa", 1500, 1, 600, 2400),
    (5, "femur", 1500, -1, 600, 2400),
    (5, "tibia", 1500, -1, 600, 2400),
    (6, "coxa", 1500, 1, 600, 2400),
    (6, "femur", 1500, -1, 600, 2400),
    (6, "tibia", 1500, -1, 600, 2400),
)

SONARS = (
    # name, x, y (0.1 mm, body frame), heading (0.01 deg, 0 = forward, left +)
    # Side sonars on brackets at the stance's outer edge (210 mm out, above the legs), 200 mm
    # apart: an 8 cm reading keeps every foot and link clear of the wall (docs/wall.md).
    ("front", 1300, 0, 0),
    ("left_front", 1000, 2100, 9000),
    ("left_rear", -1000, 2100, 9000),
    ("right_front", 1000, -2100, -9000),
    ("right_rear", -1000, -2100, -9000),
)
