"""CircuitPython's hardware modules faked on CPython, on the stub pins, bus model and virtual clock.

`CircuitPython(bus)` builds `board`, `busio`, `digitalio`, `pulseio`, `supervisor` and
`microcontroller` modules; `install(monkeypatch)` puts them in sys.modules (and points
adafruit_pca9685's `time` at the virtual clock, so its 5 ms start-up wait is virtual time the
chip models see). Pins are named like the Feather RP2040's `board` pins; each is a stub wire
(_stub_pins) with the same id as its name, so HC-SR04 models connect to "D4", "D5", ...

Fidelity notes:
- a pin is claimed by DigitalInOut, PulseIn or busio.I2C until deinit(); a second claim raises
  ValueError("... in use"), as CircuitPython does;
- PulseIn follows the RP2040 port: built running; resume() waits until the line leaves
  idle_state, then records the width (us) of every level when it ends, up to 65535, a
  zero width never; the oldest width is dropped when maxlen are held. Widths are worked out
  from the wires' edges when PulseIn is next asked (len, [], pause, clear), so a fault a test
  sets between two asks counts from the earlier ask. The RP2040 writes a width up to 32 us
  after its level ends (one FIFO word); not modelled (the ranger reads 60 ms later);
- supervisor.ticks_ms() wraps at 2**29 and starts 65 s before its first wrap;
- microcontroller.delay_us advances the virtual clock by exactly its argument.
"""

import importlib
import sys
import types

# Bare names: the very modules the firmware sees as `machine`, so one virtual clock and one set of wires.
import _stub_clock as clock
from _stub_cp import (  # noqa: F401  (re-exported: the tests' names for them)
    FEATHER_RP2040_PINS,
    MAX_PULSE_US,
    SUPERVISOR_PERIOD_MS,
    SUPERVISOR_START_MS,
    BoardPin,
    Claims,
    DigitalInOut,
    Direction,
    PinI2C,
    Pull,
    PulseIn,
    supervisor_ticks_ms,
)


class CircuitPython(Claims):
    """One fake CircuitPython board: its modules, its pin claims, its I2C bus model."""

    def __init__(self, bus, pin_names=FEATHER_RP2040_PINS, ticks_start_ms=SUPERVISOR_START_MS):
        Claims.__init__(self)
        self.bus = bus
        self.ticks_start_ms = ticks_start_ms
        self.pulseins = []
        cp = self

        board = types.ModuleType("board")
        board.board_id = "adafruit_feather_rp2040"
        for name in pin_names:
            setattr(board, name, BoardPin(name))

        class SPI:  # adafruit_bus_device names busio.SPI in annotations; nothing here uses SPI
            def __init__(self, *args, **kw):
                raise NotImplementedError("fake busio: SPI is not modelled")

        busio = types.ModuleType("busio")
        busio.I2C = lambda scl, sda, *, frequency=100000, timeout=255: PinI2C(cp, cp.bus, scl, sda, frequency)
        busio.SPI = SPI

        digitalio = types.ModuleType("digitalio")
        digitalio.DigitalInOut = lambda pin: DigitalInOut(cp, pin)
        digitalio.Direction = Direction
        digitalio.Pull = Pull

        def pulse_in(pin, maxlen=2, idle_state=False):
            p = PulseIn(cp, pin, maxlen, idle_state)
            cp.pulseins.append(p)
            return p

        pulseio = types.ModuleType("pulseio")
        pulseio.PulseIn = pulse_in

        supervisor = types.ModuleType("supervisor")
        supervisor.ticks_ms = self.ticks_ms

        microcontroller = types.ModuleType("microcontroller")
        microcontroller.delay_us = clock.sleep_us
        microcontroller.Pin = BoardPin

        self.modules = {
            "board": board,
            "busio": busio,
            "digitalio": digitalio,
            "pulseio": pulseio,
            "supervisor": supervisor,
            "microcontroller": microcontroller,
        }

    def ticks_ms(self):
        """supervisor.ticks_ms(): virtual ms, wrapping at 2**29."""
        return supervisor_ticks_ms(self.ticks_start_ms)

    def clock(self):
        """A cp_clock.Clock on these fakes and the virtual clock."""
        from drivers import cp_clock

        return cp_clock.Clock(
            ticks_ms=self.ticks_ms, sleep=clock.sleep, delay_us=clock.sleep_us, monotonic_ns=clock.monotonic_ns
        )

    def install(self, monkeypatch):
        """Put the modules in sys.modules for the test; adafruit_pca9685 sleeps on the virtual clock."""
        import adafruit_pca9685  # first, with Blinka's busio: its type hints import busio.SPI

        for name, module in self.modules.items():
            monkeypatch.setitem(sys.modules, name, module)

        monkeypatch.setattr(adafruit_pca9685, "time", clock)
        return self


def forget(name):
    """Drop a module imported on top of these fakes (sys.modules and its package's attribute)."""
    sys.modules.pop(name, None)
    parent, _, child = name.rpartition(".")
    if parent in sys.modules and child in vars(sys.modules[parent]):
        delattr(sys.modules[parent], child)


def reimport(name):
    """name imported afresh, so it binds the fake modules installed now."""
    forget(name)
    return importlib.import_module(name)
