"""Fake CircuitPython `supervisor` for the VM: ticks_ms on the virtual clock, the serial line (see _cp_vm)."""

from _cp_vm import SERIAL, START_MS
from _stub_cp import supervisor_ticks_ms

runtime = SERIAL


def ticks_ms():
    return supervisor_ticks_ms(START_MS[0])
