"""Raspberry Pi Pico (RP2040) on MicroPython: two PCA9685 boards on I2C0, five HC-SR04.

Pins are GPIO numbers (GP4 is 4). The Pico"s pins are 3.3 V only: every echo line goes
through a 1k/2k divider (docs/wiring.md). Calibration rows are the seed 001 defaults
(600..2400 us, 10 us per degree): measure your own servos and replace them.
"""

BOARD = {
    "name": "pico",
    "runtime": "micropython",
    # 400 kHz works with the breakouts' own 10 kOhm pull-ups. The PCA9685 and the RP2040 both run
    # Fast-mode Plus: 1000000 halves the bursts' time, but only on a short bus (both boards within
    # ~30 cm) with 2.2 kOhm pull-ups added, so it is not the default (docs/pico.md).
    "i2c": {"id": 0, "sda": 4, "scl": 5, "freq": 400000},
    "pca9685": {
        "pwm_hz": 50,
        "chips": (  # osc_hz: each chip's measured oscillator (nominal 25 MHz, often a few % off)
            {"address": 0x40, "osc_hz": 25000000},  # right legs 1-3
            {"address": 0x41, "osc_hz": 25000000},  # left legs 4-6 (A0 jumper bridged)
        ),
    },
    # Femur and tibia servos of the left side are mounted mirrored, hence direction -1.
    "servos": (
        # leg, joint, chip, channel, centre_us, direction, min_us, max_us
        # centre_us is the pulse at joint angle 0. The tibia's 0 is the leg straight out, one end
        # of its -180..0 travel: 2400 us (600 us mirrored), so its -90 degree knee sits at 1500 us.
        (1, "coxa", 0x40, 0, 1500, 1, 600, 2400),
        (1, "femur", 0x40, 1, 1500, 1, 600, 2400),
        (1, "tibia", 0x40, 2, 2400, 1, 600, 2400),
        (2, "coxa", 0x40, 3, 1500, 1, 600, 2400),
        (2, "femur", 0x40, 4, 1500, 1, 600, 2400),
        (2, "tibia", 0x40, 5, 2400, 1, 600, 2400),
        (3, "coxa", 0x40, 6, 1500, 1, 600, 2400),
        (3, "femur", 0x40, 7, 1500, 1, 600, 2400),
        (3, "tibia", 0x40, 8, 2400, 1, 600, 2400),
        (4, "coxa", 0x41, 0, 1500, 1, 600, 2400),
        (4, "femur", 0x41, 1, 1500, -1, 600, 2400),
        (4, "tibia", 0x41, 2, 600, -1, 600, 2400),
        (5, "coxa", 0x41, 3, 1500, 1, 600, 2400),
        (5, "femur", 0x41, 4, 1500, -1, 600, 2400),
        (5, "tibia", 0x41, 5, 600, -1, 600, 2400),
        (6, "coxa", 0x41, 6, 1500, 1, 600, 2400),
        (6, "femur", 0x41, 7, 1500, -1, 600, 2400),
        (6, "tibia", 0x41, 8, 600, -1, 600, 2400),
    ),
    "sensors": (
        # name, trigger pin, echo pin, x, y (0.1 mm, body frame), heading (0.01 deg, 0 = forward, left +)
        # Side sonars on brackets at the stance's outer edge (210 mm out, above the legs), 200 mm
        # apart: an 8 cm reading keeps every foot and link clear of the wall (docs/wall.md).
        ("front", 6, 7, 1300, 0, 0),
        ("left_front", 8, 9, 1000, 2100, 9000),
        ("left_rear", 10, 11, -1000, 2100, 9000),
        ("right_front", 12, 13, 1000, -2100, -9000),
        ("right_rear", 14, 15, -1000, -2100, -9000),
    ),
    # Wall following at power-up (hexapod.follow): None, or e.g. {"side": "left", "setpoint": 800}
    # (set point 0.1 mm, the side sonar's reading; optional "speed" 0.1 mm/s, "form" "yaw"/"sweeps").
    "follow": None,
    # Battery monitor (hexapod.battery): None, or the pack through a divider on an ADC pin, e.g.
    # {"pin": 28, "divider_permille": 333} (2S LiPo through 20k over 10k, docs/wiring.md "Battery";
    # optional "cells" and per-cell "cell_warn_mv", "cell_cutoff_mv", "cell_resume_mv").
    "battery": None,
}
