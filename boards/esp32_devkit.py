"""ESP32 DevKit (ESP32-WROOM-32) on MicroPython: two PCA9685 boards on I2C0, five HC-SR04.

Pins are GPIO numbers. Triggers on output-capable pins away from the boot straps (0, 2, 5,
12, 15) and the flash (6..11); echoes on input-only 34, 35, 36 (VP), 39 (VN) and on 32.
The ESP32 is 3.3 V only: every echo line goes through a 1k/2k divider (docs/wiring.md).
The servo calibration and the sonar mounts are the robot's: robots/<robot>_cal.py.
"""

BOARD = {
    "name": "esp32_devkit",
    "runtime": "micropython",
    "arch": "xtensawin",  # mpy-cross -march: the code emitter of this board's .mpy files (viper)
    "i2c": {"id": 0, "sda": 21, "scl": 22, "freq": 400000},
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
        ("front", 25, 34),
        ("left_front", 26, 35),
        ("left_rear", 27, 36),
        ("right_front", 14, 39),
        ("right_rear", 33, 32),
    ),
    # Wall following at power-up (hexapod.follow): None, or e.g. {"side": "left", "setpoint": 800}
    # (set point 0.1 mm, the side sonar's reading; optional "speed" 0.1 mm/s, "form" "crab" (default)/"yaw"/"sweeps").
    "follow": None,
}
