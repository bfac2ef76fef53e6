"""The stub machine as main.build finds it for a board file: a fresh virtual clock, pins and I2C
buses, the board's PCA9685 models on its bus and HC-SR04 models on its sonar pins. Shared by the
host's rigs (hexapod_host.wall.rig, hexapod_host.pico.loop) and the tests' source-text rigs; runs on CPython and in the
MicroPython VM."""

import _stub_adc
import _stub_clock as clock
import _stub_i2c
import _stub_pins
import hcsr04_model
from _stub_i2c import shared_bus
from pca9685_model import PCA9685Model

from hexapod import board as boards
from hexapod import robotcal


def reset(board_name="pico"):
    """Clock at 0 us, pins and buses as at power-up; returns the board file (validated)."""
    clock.reset(0)
    _stub_pins.reset()
    _stub_i2c.reset()
    _stub_adc.reset()
    return boards.load(board_name)


def servo_table(board, robot="default"):
    """The 18 (address, channel, ServoMap) main.build drives: the board's channel map joined with
    robots/<robot>_cal.py's servo rows (hexapod.board.servo_table)."""
    return boards.servo_table(board, robotcal.servo_maps(robotcal.load(robot)))


def pca9685_models(board, attach=True):
    """(the board's I2C bus on the virtual clock, {address: PCA9685Model}); the models are on the
    bus unless attach is False (a test plugs them in itself)."""
    bus = shared_bus(board["i2c"]["id"])
    bus.clock_us = clock.now_us
    chips = {}
    for c in board["pca9685"]["chips"]:
        chips[c["address"]] = PCA9685Model(c["address"], osc_hz=c["osc_hz"])
        if attach:
            bus.attach(chips[c["address"]])
    return bus, chips


def sonar_models(board, distances):
    """HC-SR04 models on the board's trigger/echo pins (hexapod.sensors order), each answering its
    distance (0.1 mm)."""
    pins = boards.sonar_pins(board)
    return [hcsr04_model.HCSR04(pins[k][0], pins[k][1], distance=distances[k]) for k in range(len(pins))]
