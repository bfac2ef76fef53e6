"""Stub of MicroPython's `machine` module for CPython and the MicroPython unix VM.

Placed first on sys.path, it overrides the VM's built-in module. The pieces live in
sibling modules so that each hardware edge can grow on its own:
  _stub_clock.py  virtual clock (ticks_us, ticks_ms, ticks_diff, sleep)
  _stub_pins.py   Pin, time_pulse_us, WDT, freq, reset_cause, unique_id
  _stub_i2c.py    I2C, SoftI2C on a bus model to which chip models attach
  _stub_adc.py    ADC (the rp2 port's read_u16) on voltages a test sets over virtual time
"""

from _stub_adc import ADC  # noqa: F401
from _stub_i2c import I2C, SoftI2C  # noqa: F401
from _stub_pins import (  # noqa: F401  (re-exported: this module is the board's `machine`)
    DEEPSLEEP_RESET,
    HARD_RESET,
    PWRON_RESET,
    SOFT_RESET,
    WDT,
    WDT_RESET,
    Pin,
    disable_irq,
    enable_irq,
    freq,
    idle,
    lightsleep,
    reset_cause,
    time_pulse_us,
    unique_id,
)
