"""Fake CircuitPython `pulseio` for the VM (see _cp_vm)."""

from _cp_vm import CLAIMS
from _stub_cp import PulseIn as _PulseIn


def PulseIn(pin, maxlen=2, idle_state=False):
    return _PulseIn(CLAIMS, pin, maxlen, idle_state)
