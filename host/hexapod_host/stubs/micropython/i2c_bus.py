"""I2C bus model: chip models attach by 7-bit address; the bus counts what goes over the wire.

Runs on CPython and inside the MicroPython VM, and allocates nothing per transfer (the
zero-heap test of the servo driver runs through it). A controller (the stub machine.I2C or
the fake busio.I2C) drives it one condition at a time: start() sends START (or a repeated
START) and the address byte, send()/recv() move data bytes, stop() sends STOP.

Figures (see stats()):
  transactions  STOP conditions sent (a repeated START does not end a transaction)
  bytes         every byte clocked on SDA, address bytes included
  bits          SCL periods: 1 per START or repeated START + 9 per byte (8 data + ACK) + 1 per STOP
  time_ns       sum of bits * 1e9 / freq at each controller's clock, plus tBUF after each STOP
                (the bus free time before the next START, I2C spec UM10204 Table 10:
                4700 ns Standard-mode, 1300 ns Fast-mode, 500 ns Fast-mode Plus)
Counting START and STOP as one SCL period each is the model's rounding of their setup and
hold times (0.6 us each in Fast-mode, against a 2.5 us bit). Clock stretching is not modelled.

Time: the bus keeps a clock in ns that wire time advances; sleep_us() advances it too, so a
driver given bus.sleep_us waits in model time. A device reads it with now_us(). Give the bus
clock_us (a function returning monotonic us, e.g. the virtual clock's ticks_us) and now_us()
reads that instead, so a driver sleeping on that clock is seen by the chips; wire time is
then still counted in stats() but does not move that clock.

Faults, armed with fault(address, kind, byte=0, count=1), fire on the next `count` transfers
to that address:
  "nack"     byte 0: the address byte is not acknowledged; byte k >= 1: data byte k (1-based)
             is not acknowledged, so bytes 1..k-1 reached the chip and the rest never did
  "timeout"  the bus hangs (a chip holding SCL) at data byte `byte` (0: at the address);
             bytes before it reached the chip
  "reset"    the chip resets (brownout) just before the transfer, which then goes on
A detached address (detach()) does not acknowledge at all, like an unplugged chip.
"""

from micropython import const

ADDR_NACK = const(-1)  # start(): nobody acknowledged the address byte
TIMEOUT = const(-2)  # start()/send()/recv(): the bus hung

_NACK = const(1)
_TIMEOUT = const(2)
_RESET = const(3)
_KINDS = {"nack": _NACK, "timeout": _TIMEOUT, "reset": _RESET}
_MAX_SELECTED = const(8)


def t_buf_ns(freq):
    """Bus free time between a STOP and the next START, ns, for the speed mode of freq (Hz)."""
    if freq <= 100000:
        return 4700
    if freq <= 400000:
        return 1300
    return 500


class I2CBus:
    """Wires, pull-ups and chips: routes bytes to the chips that answer an address."""

    def __init__(self, clock_us=None):
        self.clock_us = clock_us
        self._devices = []
        self._selected = [None] * _MAX_SELECTED
        self._n_selected = 0
        self._open = False  # a START was sent and no STOP yet
        self._read = False
        self._freq = 400000
        self._fault_addr = -1
        self._fault_kind = 0
        self._fault_byte = 0
        self._fault_count = 0
        self._armed = 0  # fault kind armed for the current transfer
        self._byte_no = 0  # data bytes of the current transfer so far
        self._general = False  # the current transfer is a general call (address 0)
        self._t_ns = 0
        self.reset_stats()

    # -- devices --------------------------------------------------------------------------
    def attach(self, device):
        """Connect a chip model (it must have `address`); returns the device."""
        if not 0 <= device.address <= 0x7F:
            raise ValueError("address 0x%x is not a 7-bit I2C address" % device.address)
        for d in self._devices:
            if d.address == device.address:
                raise ValueError("address 0x%02x is already taken on this bus" % device.address)
        device.bus = self
        self._devices.append(device)
        return device

    def detach(self, address):
        """Unplug the chip at address (it keeps its registers); returns it, or None."""
        for d in self._devices:
            if d.address == address:
                self._devices.remove(d)
                return d
        return None

    def device(self, address):
        """The chip whose own address is address, or None."""
        for d in self._devices:
            if d.address == address:
                return d
        return None

    def fault(self, address, kind, byte=0, count=1):
        """Arm a fault ("nack", "timeout", "reset") for the next `count` transfers to address."""
        if kind not in _KINDS:
            raise ValueError("fault kind %r, allowed: nack, timeout, reset" % (kind,))
        if byte < 0 or count < 1:
            raise ValueError("fault byte=%r count=%r, allowed byte >= 0 and count >= 1" % (byte, count))
        self._fault_addr = address
        self._fault_kind = _KINDS[kind]
        self._fault_byte = byte
        self._fault_count = count

    def clear_faults(self):
        self._fault_count = 0

    # -- time -----------------------------------------------------------------------------
    def now_us(self):
        """Model time in us (wire time plus sleeps), or clock_us() when the bus was given one."""
        if self.clock_us is not None:
            return self.clock_us()
        return self._t_ns // 1000

    def sleep_us(self, us):
        """Let us microseconds pass on the model clock (pass this as the driver's sleep)."""
        self._t_ns += us * 1000

    def _clock(self, bits):
        self.bits += bits
        self._t_ns += (bits * 1000000000 + self._freq // 2) // self._freq

    # -- statistics -----------------------------------------------------------------------
    def reset_stats(self):
        self.transactions = 0
        self.bytes = 0
        self.bits = 0
        self.nacks = 0
        self.timeouts = 0
        self._t0_ns = self._t_ns
        self._wire_ns = 0

    def stats(self):
        """Figures since reset_stats(), as a dict (allocates: for tests and benches)."""
        return {
            "transactions": self.transactions,
            "bytes": self.bytes,
            "bits": self.bits,
            "time_ns": self._wire_ns,
            "nacks": self.nacks,
            "timeouts": self.timeouts,
        }

    # -- the wire -------------------------------------------------------------------------
    def start(self, address, read, freq):
        """START (or repeated START) and the address byte; 0, ADDR_NACK or TIMEOUT."""
        self._freq = freq
        before = self._t_ns
        self._clock(1)
        self._open = True
        self._read = read
        self._byte_no = 0
        self._armed = 0
        if self._fault_count and address == self._fault_addr:
            self._fault_count -= 1
            self._armed = self._fault_kind
            if self._armed == _RESET:
                d = self.device(address)
                if d is not None:
                    d.reset()
                self._armed = 0
        self.bytes += 1
        if self._armed == _TIMEOUT and self._fault_byte == 0:
            self.timeouts += 1
            self._wire_ns += self._t_ns - before
            return TIMEOUT
        self._clock(9)
        n = 0
        if address == 0:
            # General call: every chip listens; a chip that takes no general call ignores the bytes.
            for d in self._devices:
                if n < _MAX_SELECTED:
                    self._selected[n] = d
                    n += 1
        else:
            for d in self._devices:
                if n < _MAX_SELECTED and d.answers(address):
                    self._selected[n] = d
                    n += 1
        self._n_selected = n
        self._general = address == 0
        if self._armed == _NACK and self._fault_byte == 0:
            n = 0
            self._n_selected = 0
        self._wire_ns += self._t_ns - before
        if n == 0:
            self.nacks += 1
            return ADDR_NACK
        for i in range(n):
            if not self._general:
                self._selected[i].on_start(read)
        return 0

    def scan(self, freq):
        """7-bit addresses 0x08..0x77 that acknowledge (an address byte and a STOP each, at freq):
        what machine.I2C.scan and busio.I2C.scan both do on the wire."""
        found = []
        for addr in range(0x08, 0x78):
            if self.start(addr, False, freq) == 0:
                found.append(addr)
            self.stop()
        return found

    def _next_byte_times_out(self, before):
        """Count the next byte; True (timeout counted, wire time since before booked) if a timeout strikes it."""
        self._byte_no += 1
        self.bytes += 1
        if self._armed != _TIMEOUT or self._byte_no < self._fault_byte:
            return False
        self.timeouts += 1
        self._wire_ns += self._t_ns - before
        return True

    def send(self, buf, start, end):
        """Data bytes buf[start:end] to the addressed chips; the number acknowledged, or TIMEOUT."""
        before = self._t_ns
        acked = 0
        for i in range(start, end):
            if self._next_byte_times_out(before):
                return TIMEOUT
            self._clock(9)
            if self._armed == _NACK and self._byte_no >= self._fault_byte:
                self.nacks += 1
                self._wire_ns += self._t_ns - before
                return acked
            b = buf[i]
            ack = False
            for k in range(self._n_selected):
                d = self._selected[k]
                if self._general:
                    ack = d.general_call(b) or ack
                elif d.on_write(b):
                    ack = True
            if not ack:
                self.nacks += 1
                self._wire_ns += self._t_ns - before
                return acked
            acked += 1
        self._wire_ns += self._t_ns - before
        return acked

    def recv(self, buf, start, end):
        """Read bytes into buf[start:end] (wired-AND when several chips answer); 0 or TIMEOUT."""
        before = self._t_ns
        for i in range(start, end):
            if self._next_byte_times_out(before):
                return TIMEOUT
            self._clock(9)
            v = 0xFF
            for k in range(self._n_selected):
                v &= self._selected[k].on_read()
            buf[i] = v
        self._wire_ns += self._t_ns - before
        return 0

    def stop(self):
        """STOP: the end of a transaction (after an error too, as a controller releases the bus)."""
        if not self._open:
            return
        before = self._t_ns
        self._clock(1)
        self._t_ns += t_buf_ns(self._freq)
        self._open = False
        self.transactions += 1
        for k in range(self._n_selected):
            if not self._general:
                self._selected[k].on_stop()
            self._selected[k] = None
        self._n_selected = 0
        self._armed = 0
        self._wire_ns += self._t_ns - before
