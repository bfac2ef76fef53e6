"""CPython fakes that let Adafruit's CircuitPython libraries run against our chip models.

`I2C` (_stub_cp.BusI2C) has the busio.I2C methods adafruit_bus_device uses and drives an
i2c_bus.I2CBus, so its wire figures count the same way as the stub machine.I2C's.

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

# A bare name: the class sits with the MicroPython stubs, where the VM's fake busio uses it too.
from _stub_cp import BusI2C as I2C  # noqa: F401  (busio.I2C look-alike on a bus model)


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
