"""Adafruit Feather RP2040 on MicroPython (the rp2 port's ADAFRUIT_FEATHER_RP2040 firmware): the
same wiring as boards/feather_rp2040.py, two PCA9685 boards on the STEMMA QT I2C, five HC-SR04.

Why a second Feather file: on CircuitPython the deploy does not fit the Feather's heap yet (it
compiles every .py at import, docs/flashing.md); MicroPython runs the .mpy files that `hexapod
flash` compiles, with the Pico's heap (the same RP2040). Pins are GPIO numbers: the Feather's
silkscreen names map as STEMMA QT SDA = GPIO2, SCL = GPIO3 (I2C1), D4-D6 = GPIO6-8, D9-D13 =
GPIO9-13, A0 = GPIO26, A1 = GPIO27 (Adafruit's Feather RP2040 pinout). Every echo line goes
through a 1k/2k divider (docs/wiring.md); GPIO13 also lights the red LED: a trigger, never an echo.
The servo calibration and the sonar mounts are the robot's: robots/<robot>_cal.py.
"""

BOARD = {
    "name": "feather_rp2040_micropython",
    "runtime": "micropython",
    "arch": "armv6m",  # mpy-cross -march: the code emitter of this board's .mpy files (viper)
    "i2c": {"id": 1, "sda": 2, "scl": 3, "freq": 400000},
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
        # name, trigger pin, echo pin: the CircuitPython file's D4/D5, D6/D9, D10/D11, D13/D12, A0/A1
        ("front", 6, 7),
        ("left_front", 8, 9),
        ("left_rear", 10, 11),
        ("right_front", 13, 12),
        ("right_rear", 26, 27),
    ),
    # Wall following at power-up (hexapod.follow): None, or e.g. {"side": "left", "setpoint": 800}
    # (set point 0.1 mm, the side sonar's reading; optional "speed" 0.1 mm/s, "form" "crab" (default)/"yaw"/"sweeps").
    "follow": None,
    # Battery monitor (hexapod.battery): None, or the pack through a divider on an ADC pin, e.g.
    # {"pin": 28, "divider_permille": 333} (A2 = GPIO28; 2S LiPo through 20k over 10k, docs/wiring.md
    # "Battery"; optional "cells" and per-cell "cell_warn_mv", "cell_cutoff_mv", "cell_resume_mv").
    "battery": None,
}
