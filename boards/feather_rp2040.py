"""Adafruit Feather RP2040 on CircuitPython: two PCA9685 boards on the STEMMA QT I2C, five HC-SR04.

Pins are names in CircuitPython's `board` module (main.py looks them up); busio.I2C has no
bus id. The RP2040 is 3.3 V only: every echo line goes through a 1k/2k divider
(docs/wiring.md). D13 also lights the red LED: it serves as a trigger (the LED flickers),
never as an echo (the LED would load the divider).
The servo calibration and the sonar mounts are the robot's: robots/<robot>_cal.py.
"""

BOARD = {
    "name": "feather_rp2040",
    "runtime": "circuitpython",
    "arch": None,  # CircuitPython loads .py sources: no mpy-cross
    "i2c": {"id": None, "sda": "SDA", "scl": "SCL", "freq": 400000},
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
        ("front", "D4", "D5"),
        ("left_front", "D6", "D9"),
        ("left_rear", "D10", "D11"),
        ("right_front", "D13", "D12"),
        ("right_rear", "A0", "A1"),
    ),
    # Wall following at power-up (hexapod.follow): None, or e.g. {"side": "left", "setpoint": 800}
    # (set point 0.1 mm, the side sonar's reading; optional "speed" 0.1 mm/s, "form" "crab" (default)/"yaw"/"sweeps").
    "follow": None,
}
