"""State the VM's fake CircuitPython modules share: pin claims, supervisor ticks, the serial line.

This folder serves CircuitPython's hardware modules (board, busio, digitalio, pulseio, supervisor,
microcontroller) to the MicroPython VM as real modules, on the stub wires, the I2C bus model and
the virtual clock (stubs/micropython/_stub_cp.py holds the pieces; the CPython twin is
hexapod_host.stubs.circuitpython). Put it on MICROPYPATH only for a CircuitPython run: it shadows
nothing MicroPython has, but firmware that tries `import board` to tell the runtimes apart would be
fooled. busio.I2C drives _stub_i2c.shared_bus(None), the bus of a board file whose "i2c" id is None.
"""

import _stub_clock as clock
from _stub_cp import SUPERVISOR_START_MS, Claims

CLAIMS = Claims()
START_MS = [SUPERVISOR_START_MS]  # supervisor.ticks_ms() at virtual time 0


class NoMachine:
    """Stands in for `machine` in sys.modules: CircuitPython has no such module, the VM has one built
    in; firmware that asks it for anything (machine.reset_cause) meets an AttributeError."""


class Serial:
    """The USB serial line: bytes a run schedules at virtual instants (ms), read one at a time.

    supervisor.runtime.serial_bytes_available and a stand-in for sys.stdin.read(1) (the VM cannot
    swap sys.stdin): code.SerialReader reads this as it reads the board's."""

    def __init__(self):
        self.lines = []  # [(at_ms, text)], in time order
        self.pos = 0
        self.watch = None  # called on every poll (a run's heap sampler), or None

    def send(self, at_ms, text):
        self.lines.append((at_ms, text))

    @property
    def serial_bytes_available(self):
        if self.watch is not None:
            self.watch()
        if not self.lines or self.lines[0][0] * 1000 > clock.now_us():
            return 0
        return len(self.lines[0][1]) - self.pos

    def read(self, n=1):
        if not self.serial_bytes_available:
            return ""
        text = self.lines[0][1]
        c = text[self.pos : self.pos + n]
        self.pos += len(c)
        if self.pos >= len(text):
            self.lines.pop(0)
            self.pos = 0
        return c


SERIAL = Serial()
