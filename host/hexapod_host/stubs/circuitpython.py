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
import _stub_pins as pins
from machine import Pin

from hexapod_host.stubs import busio as fakes_busio

FEATHER_RP2040_PINS = (
    "A0", "A1", "A2", "A3", "D4", "D5", "D6", "D9", "D10", "D11", "D12", "D13", "D24", "D25",
    "SCL", "SDA", "SCK", "MOSI", "MISO", "TX", "RX", "LED", "NEOPIXEL", "BUTTON",
)  # fmt: skip
SUPERVISOR_PERIOD_MS = 1 << 29
SUPERVISOR_START_MS = SUPERVISOR_PERIOD_MS - 65000  # CircuitPython: first wrap about 65 s after boot
MAX_PULSE_US = 65535


class BoardPin:
    """A `board` pin: a name; its stub wire has the same id."""

    def __init__(self, name):
        self.name = name

    def __repr__(self):
        return "board.%s" % self.name


class Direction:
    INPUT = "input"
    OUTPUT = "output"


class Pull:
    UP = "up"
    DOWN = "down"


class CircuitPython:
    """One fake CircuitPython board: its modules, its pin claims, its I2C bus model."""

    def __init__(self, bus, pin_names=FEATHER_RP2040_PINS, ticks_start_ms=SUPERVISOR_START_MS):
        self.bus = bus
        self.claimed = {}
        self.ticks_start_ms = ticks_start_ms
        self.pulseins = []
        cp = self

        board = types.ModuleType("board")
        board.board_id = "adafruit_feather_rp2040"
        for name in pin_names:
            setattr(board, name, BoardPin(name))

        class I2C(fakes_busio.I2C):
            def __init__(self, scl, sda, *, frequency=100000, timeout=255):
                if scl is sda:
                    raise ValueError("scl and sda are both %r" % (scl,))
                cp.claim(scl, self)
                cp.claim(sda, self)
                self._pins = (scl, sda)
                fakes_busio.I2C.__init__(self, cp.bus, frequency)

            def deinit(self):
                fakes_busio.I2C.deinit(self)
                for p in self._pins:
                    cp.release(p)

        class SPI:  # adafruit_bus_device names busio.SPI in annotations; nothing here uses SPI
            def __init__(self, *args, **kw):
                raise NotImplementedError("fake busio: SPI is not modelled")

        busio = types.ModuleType("busio")
        busio.I2C = I2C
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
        return (clock.now_us() // 1000 + self.ticks_start_ms) % SUPERVISOR_PERIOD_MS

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

    def claim(self, pin, owner):
        if not isinstance(pin, BoardPin):
            raise TypeError("%r is not a board pin" % (pin,))
        if pin.name in self.claimed:
            raise ValueError("%s in use" % pin.name)
        self.claimed[pin.name] = owner

    def release(self, pin):
        self.claimed.pop(pin.name, None)


class DigitalInOut:
    """digitalio.DigitalInOut on a stub wire."""

    def __init__(self, cp, pin):
        cp.claim(pin, self)
        self._cp = cp
        self.pin = pin
        self._pin = Pin(pin.name, Pin.IN)

    def switch_to_output(self, value=False, drive_mode=None):
        self._pin.init(Pin.OUT, value=1 if value else 0)

    def switch_to_input(self, pull=None):
        self._pin.init(Pin.IN, pull=Pin.PULL_UP if pull == Pull.UP else Pin.PULL_DOWN if pull == Pull.DOWN else None)

    @property
    def direction(self):
        return Direction.OUTPUT if self._pin._w.mode == Pin.OUT else Direction.INPUT

    @direction.setter
    def direction(self, d):
        if d == Direction.OUTPUT:
            self.switch_to_output()
        else:
            self.switch_to_input()

    @property
    def value(self):
        return bool(self._pin.value())

    @value.setter
    def value(self, v):
        if self._pin._w.mode != Pin.OUT:
            raise AttributeError("Cannot set value when direction is input.")
        self._pin.value(1 if v else 0)

    def deinit(self):
        self._cp.release(self.pin)


class PulseIn:
    """pulseio.PulseIn as on the RP2040 port (see the module docstring)."""

    def __init__(self, cp, pin, maxlen, idle_state):
        if not isinstance(maxlen, int) or not 1 <= maxlen <= 65535:
            raise ValueError("maxlen must be 1-65535")
        cp.claim(pin, self)
        self._cp = cp
        self.pin = pin
        self.maxlen = maxlen
        self._idle = 1 if idle_state else 0
        Pin(pin.name, Pin.IN)
        self._buf = []
        self.resume()

    @property
    def paused(self):
        return self._paused

    def _record(self, width):
        self._buf.append(min(width, MAX_PULSE_US))
        if len(self._buf) > self.maxlen:
            del self._buf[0]

    def _change(self, t, level):
        if not self._active:
            if level != self._idle:
                self._active = True
                self._since = t
            self._level = level
            return
        width = t - self._since
        self._level = level
        self._since = t
        if width > 0:
            self._record(width)

    def _advance(self):
        now = clock.now_us()
        if not self._paused:
            edges = []
            t = self._t
            while len(edges) < 10000:
                e = pins.next_edge(self.pin.name, t)
                if e < 0 or e > now:
                    break
                edges.append(e)
                t = e
            # a level the wire had at the last ask that the edges since do not explain: a test changed a fault
            then = pins.level(self.pin.name) ^ (len(edges) & 1)
            if then != self._level:
                self._change(self._t, then)
            for e in edges:
                self._change(e, 1 - self._level)
        self._t = now

    def pause(self):
        self._advance()
        self._paused = True

    def resume(self, trigger_duration=0):
        if trigger_duration:
            raise NotImplementedError("fake PulseIn: trigger_duration is not modelled")
        now = clock.now_us()
        self._paused = False
        self._t = now
        self._level = pins.level(self.pin.name)
        self._active = self._level != self._idle  # the PIO's wait for the line to leave idle
        self._since = now

    def clear(self):
        self._advance()
        self._buf = []

    def popleft(self):
        self._advance()
        if not self._buf:
            raise IndexError("pop from empty PulseIn")
        return self._buf.pop(0)

    def __len__(self):
        self._advance()
        return len(self._buf)

    def __bool__(self):
        return len(self) > 0

    def __getitem__(self, i):
        self._advance()
        return self._buf[i]

    def deinit(self):
        self._paused = True
        self._cp.release(self.pin)


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
