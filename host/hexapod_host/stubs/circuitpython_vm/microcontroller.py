"""Fake CircuitPython `microcontroller` for the VM: delay_us on the virtual clock, the Pin type (see _cp_vm)."""

from _stub_clock import sleep_us as delay_us  # noqa: F401  (the module's names)
from _stub_cp import BoardPin as Pin  # noqa: F401
