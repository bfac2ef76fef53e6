"""Raspberry Pi Pico (RP2040) on MicroPython: two PCA9685 boards on I2C0, five HC-SR04.

Pins are GPIO numbers (GP4 is 4). The Pico"s pins are 3.3 V only: every echo line goes
through a 1k/2k divider (docs/wiring.md).
The servo calibration and the sonar mounts are the robot's: robots/<robot>_cal.py.
"""

BOARD = {
    "name": "pico",
    "runtime": "micropython",
    "arch": "armv6m",  # mpy-cross -march: the code emitter of this board's .mpy files (viper)
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
    # (chip address, channel) of each leg's coxa, femur and tibia servo: which PCA9685 output drives it
    "channels": (
        ((0x40, 0), (0x40, 1), (0x40, 2)),  # leg 1 RF
        ((0x40, 3), (0x40, 4), (0x40, 5)),  # leg 2 RM
        ((0x40, 6), (0x40, 7), (0x40, 8)),  # leg 3 RR
        ((0x41, 0), (0x41, 1), (0x41, 2)),  # leg 4 LR
        ((0x41, 3), (0x41, 4), (0x41, 5)),  # leg 5 LM
        ((0x41, 6), (0x41, 7), (0x41, 8)),  # leg 6 LF
    ),
    "sonars": (
        # name, trigger pin, echo pin (where each sonar sits is the robot's: robots/<robot>_cal.py)
        ("front", 6, 7),
        ("left_front", 8, 9),
        ("left_rear", 10, 11),
        ("right_front", 12, 13),
        ("right_rear", 14, 15),
    ),
    # Wall following at power-up (hexapod.follow): None, or e.g. {"side": "left", "setpoint": 800}
    # (set point 0.1 mm, the side sonar's reading; optional "speed" 0.1 mm/s, "form" "crab" (default)/"yaw"/"sweeps").
    "follow": None,
    # Battery monitor (hexapod.battery): None, or the pack through a divider on an ADC pin, e.g.
    # {"pin": 28, "divider_permille": 333} (2S LiPo through 20k over 10k, docs/wiring.md "Battery";
    # optional "cells" and per-cell "cell_warn_mv", "cell_cutoff_mv", "cell_resume_mv").
    "battery": None,
}
