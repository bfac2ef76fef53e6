"""CPython fakes that let Adafruit's CircuitPython libraries run against our chip models.

`I2C` has the busio.I2C methods adafruit_bus_device uses (try_lock, unlock, writeto,
readfrom_into, writeto_then_readfrom, scan) and drives an i2c_bus.I2CBus, so its wire
figures count the same way as the stub machine.I2C's. Errors are raised as CircuitPython
does: OSError(19) for an address nobody acknowledges, OSError(5) for a data NACK,
OSError(110) for a hung bus.

`model_time(bus)` swaps adafruit_pca9685's `time` for one whose sleep() advances the bus
model's clock, so the chip model sees Adafruit's 5 ms oscillator wait as time that passed
(otherwise it would flag RESTART_TOO_SOON).

`ensure_board()`: adafruit_servokit imports `board` (Blinka) at module top. On this PC
Blinka's board module loads (GENERIC_LINUX_PC); where it fails (no platform detected),
ensure_board() puts an empty stand-in in sys.modules. ServoKit only touches board.I2C()
when no i2c is passed, and we always pass the fake.
"""

import contextlib
import sys
import types

# A bare name: the bus model sits with the MicroPython stubs, where the VM imports it so.
from i2c_bus import ADDR_NACK, TIMEOUT


class I2C:
    """busio.I2C look-alike on a bus model."""

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
        found = []
        for addr in range(0x08, 0x78):
            if self.bus.start(addr, False, self.frequency) == 0:
                found.append(addr)
            self.bus.stop()
        return found

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


class _ModelTime:
    """The bits of `time` adafruit_pca9685 calls, on the bus model's clock."""

    def __init__(self, bus):
        self.bus = bus

    def sleep(self, seconds):
        self.bus.sleep_us(int(seconds * 1000000 + 0.5))

    def monotonic(self):
        return self.bus.now_us() / 1000000


@contextlib.contextmanager
def model_time(bus):
    """Within the block, adafruit_pca9685's time.sleep advances bus's model clock."""
    import adafruit_pca9685

    saved = adafruit_pca9685.time
    adafruit_pca9685.time = _ModelTime(bus)
    try:
        yield
    finally:
        adafruit_pca9685.time = saved


def ensure_board():
    """Make `import board` work for adafruit_servokit (a stand-in only if Blinka's fails)."""
    if "board" in sys.modules:
        return sys.modules["board"]
    try:
        import board
    except Exception:  # Blinka raises NotImplementedError/RuntimeError on unknown platforms
        board = types.ModuleType("board")
        board.__doc__ = "stand-in: no board on the host; pass i2c= explicitly"
        sys.modules["board"] = board
    return board
