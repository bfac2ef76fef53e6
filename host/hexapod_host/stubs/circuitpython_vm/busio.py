"""Fake CircuitPython `busio` for the VM: I2C on _stub_i2c.shared_bus(None) (see _cp_vm)."""

from _cp_vm import CLAIMS
from _stub_cp import PinI2C
from _stub_i2c import shared_bus


def I2C(scl, sda, *, frequency=100000, timeout=255):
    return PinI2C(CLAIMS, shared_bus(None), scl, sda, frequency)
