"""Fake CircuitPython `digitalio` for the VM (see _cp_vm)."""

from _cp_vm import CLAIMS
from _stub_cp import DigitalInOut as _DigitalInOut
from _stub_cp import Direction, Pull  # noqa: F401  (the module's names)


def DigitalInOut(pin):
    return _DigitalInOut(CLAIMS, pin)
