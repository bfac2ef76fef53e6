"""CircuitPython's pins, digitalio, pulseio and busio.I2C on the stub wires, bus model and virtual clock.

The pieces both fakes of CircuitPython share: hexapod_host.stubs.circuitpython builds CPython
modules from them, stubs/circuitpython_vm/ serves them to the MicroPython VM as real modules
(`board`, `busio`, ...). MicroPython-compatible. Fidelity notes in hexapod_host.stubs.circuitpython.

Pin claims: every class takes `claims`, an object with claim(pin, owner) and release(pin)
(Claims below); a second claim of a pin raises ValueError("... in use"), as CircuitPython does.
"""

import _stub_clock as clock
import _stub_pins as pins
from _stub_pins import Pin
from i2c_bus import ADDR_NACK, TIMEOUT

FEATHER_RP2040_PINS = (
    "A0", "A1", "A2", "A3", "D4", "D5", "D6", "D9", "D10", "D11", "D12", "D13", "D24", "D25",
    "SCL", "SDA", "SCK", "MOSI", "MISO", "TX", "RX", "LED", "NEOPIXEL", "BUTTON",
)  # fmt: skip
SUPERVISOR_PERIOD_MS = 1 << 29
SUPERVISOR_START_MS = SUPERVISOR_PERIOD_MS - 65000  # CircuitPython: first wrap about 65 s after boot
MAX_PULSE_US = 65535


def supervisor_ticks_ms(start_ms):
    """supervisor.ticks_ms(): virtual ms from start_ms, wrapping at 2**29."""
    return (clock.now_us() // 1000 + start_ms) % SUPERVISOR_PERIOD_MS


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


class Claims:
    """Which pins are in use, by whom."""

    def __init__(self):
        self.claimed = {}

    def claim(self, pin, owner):
        if not isinstance(pin, BoardPin):
            raise TypeError("%r is not a board pin" % (pin,))
        if pin.name in self.claimed:
            raise ValueError("%s in use" % pin.name)
        self.claimed[pin.name] = owner

    def release(self, pin):
        self.claimed.pop(pin.name, None)


class BusI2C:
    """busio.I2C's methods (try_lock, unlock, writeto, readfrom_into, writeto_then_readfrom, scan)
    on an i2c_bus.I2CBus. Errors as CircuitPython raises them: OSError(19) for an address nobody
    acknowledges, OSError(5) for a data NACK, OSError(110) for a hung bus."""

    def __init__(self, bus, frequency=400000):
        self.bus = bus
        self.frequency = frequency
        self._locked = False

    def try_lock(self):
        if self._locked:
            return False
        self._locked = True
        return True

    def unlock(self):
        self._locked = False

    def deinit(self):
        self._locked = False

    def _need_lock(self):
        if not self._locked:
            raise RuntimeError("Function requires lock")

    def _fail(self, code):
        self.bus.stop()
        raise OSError(110 if code == TIMEOUT else 19 if code == ADDR_NACK else 5)

    def _start(self, address, read):
        r = self.bus.start(address, read, self.frequency)
        if r < 0:
            self._fail(r)

    def _send(self, buf, start, end):
        end = len(buf) if end is None else end
        a = self.bus.send(buf, start, end)
        if a == TIMEOUT:
            self._fail(TIMEOUT)
        if a < end - start:
            self._fail(0)

    def _recv(self, buf, start, end):
        end = len(buf) if end is None else end
        if self.bus.recv(buf, start, end) == TIMEOUT:
            self._fail(TIMEOUT)

    def scan(self):
        self._need_lock()
        return self.bus.scan(self.frequency)

    def writeto(self, address, buffer, *, start=0, end=None):
        self._need_lock()
        self._start(address, False)
        self._send(buffer, start, end)
        self.bus.stop()

    def readfrom_into(self, address, buffer, *, start=0, end=None):
        self._need_lock()
        self._start(address, True)
        self._recv(buffer, start, end)
        self.bus.stop()

    def writeto_then_readfrom(
        self, address, buffer_out, buffer_in, *, out_start=0, out_end=None, in_start=0, in_end=None
    ):
        """Write, repeated START, read: one transaction."""
        self._need_lock()
        self._start(address, False)
        self._send(buffer_out, out_start, out_end)
        self._start(address, True)
        self._recv(buffer_in, in_start, in_end)
        self.bus.stop()


class PinI2C(BusI2C):
    """busio.I2C(scl, sda, *, frequency, timeout) claiming its two pins, on bus."""

    def __init__(self, claims, bus, scl, sda, frequency=100000):
        if scl is sda:
            raise ValueError("scl and sda are both %r" % (scl,))
        claims.claim(scl, self)
        claims.claim(sda, self)
        self._claims = claims
        self._pins = (scl, sda)
        BusI2C.__init__(self, bus, frequency)

    def deinit(self):
        BusI2C.deinit(self)
        for p in self._pins:
            self._claims.release(p)


class DigitalInOut:
    """digitalio.DigitalInOut on a stub wire."""

    def __init__(self, claims, pin):
        claims.claim(pin, self)
        self._claims = claims
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
        self._claims.release(self.pin)


class PulseIn:
    """pulseio.PulseIn as on the RP2040 port (see hexapod_host.stubs.circuitpython)."""

    def __init__(self, claims, pin, maxlen, idle_state):
        if not isinstance(maxlen, int) or not 1 <= maxlen <= 65535:
            raise ValueError("maxlen must be 1-65535")
        claims.claim(pin, self)
        self._claims = claims
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
        self._claims.release(self.pin)
