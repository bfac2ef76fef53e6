"""machine.I2C and machine.SoftI2C on the I2C bus model (i2c_bus.I2CBus).

Same methods and error behaviour as MicroPython's extmod/machine_i2c.c and the ports:
  SoftI2C           address NACK -> OSError(19) ENODEV; a data NACK stops the write, which
                    returns the number of bytes acknowledged (writeto_mem then says nothing)
  I2C port="esp32"  any NACK -> OSError(19) ENODEV (ESP_FAIL)
  I2C port="rp2"    any NACK -> OSError(5) EIO (PICO_ERROR_GENERIC)
  all               a hung bus -> OSError(110) ETIMEDOUT
Nothing here allocates on the writeto / readfrom_into / readfrom_mem_into / writeto_mem path.
Each hardware id has one shared bus (bus(id)) so firmware calling machine.I2C(0) meets the
chips a test attached (shared_bus(id)); pass bus= to use another.
"""

from i2c_bus import ADDR_NACK, TIMEOUT, I2CBus
from micropython import const

_EIO = const(5)
_ENODEV = const(19)
_ETIMEDOUT = const(110)
_DATA_NACK = const(-3)

_buses = {}


def shared_bus(id=0):
    """The shared bus model behind machine.I2C(id) (id -1: SoftI2C)."""
    b = _buses.get(id)
    if b is None:
        b = I2CBus()
        _buses[id] = b
    return b


class SoftI2C:
    """Bit-banged I2C: MicroPython's SoftI2C(scl, sda, *, freq=400000, timeout=50000)."""

    _nack_errno = 0  # 0: a data NACK is reported as a short ACK count, not raised

    def __init__(self, scl=None, sda=None, *, freq=400000, timeout=50000, bus=None):
        self._setup(freq, timeout, bus if bus is not None else shared_bus(-1))
        self.scl = scl
        self.sda = sda

    def _setup(self, freq, timeout, the_bus):
        if not isinstance(freq, int) or freq <= 0 or freq > 5000000:
            raise ValueError("freq: %r Hz, allowed 1..5000000" % (freq,))
        if not isinstance(timeout, int) or timeout < 0:
            raise ValueError("timeout: %r us, allowed >= 0" % (timeout,))
        self._freq = freq
        self.timeout = timeout
        self._bus = the_bus
        self._mem = bytearray(4)  # memory address bytes, made once

    def init(self, *args, **kw):
        """Change freq/timeout as the real init() does."""
        self._setup(kw.get("freq", self._freq), kw.get("timeout", self.timeout), self._bus)

    @property
    def bus_model(self):
        return self._bus

    def _fail(self, code):
        self._bus.stop()
        if code == TIMEOUT:
            raise OSError(_ETIMEDOUT)
        if code == ADDR_NACK and self._nack_errno == 0:
            raise OSError(_ENODEV)  # SoftI2C; a soft data NACK is never raised
        raise OSError(self._nack_errno)

    def _begin(self, addr, read):
        r = self._bus.start(addr, read, self._freq)
        if r < 0:
            self._fail(r)

    def _send(self, buf, start, end):
        """Send buf[start:end]; the bytes acknowledged. A data NACK raises on hardware ports and
        leaves a short count on SoftI2C; the transfer stays open either way (the caller stops it)."""
        a = self._bus.send(buf, start, end)
        if a == TIMEOUT:
            self._fail(TIMEOUT)
        if a < end - start and self._nack_errno:
            self._fail(_DATA_NACK)
        return a

    def _put(self, buf, start, end):
        """Send buf[start:end]; True when all were acknowledged (raises on hardware ports)."""
        return self._send(buf, start, end) == end - start

    def _memaddr(self, memaddr, addrsize):
        if addrsize not in (8, 16, 24, 32):
            raise ValueError("addrsize: %r, allowed 8, 16, 24, 32" % (addrsize,))
        n = addrsize // 8
        for i in range(n):
            self._mem[i] = (memaddr >> (8 * (n - 1 - i))) & 0xFF
        return n

    def scan(self):
        """7-bit addresses 0x08..0x77 that acknowledge."""
        return self._bus.scan(self._freq)

    def writeto(self, addr, buf, stop=True):
        """Write buf; returns the number of bytes acknowledged."""
        self._begin(addr, False)
        a = self._send(buf, 0, len(buf))
        if stop or a < len(buf):  # a short write ends the transfer whatever stop says
            self._bus.stop()
        return a

    def writevto(self, addr, vector, stop=True):
        """Write the buffers of vector back to back in one transfer; returns bytes acknowledged."""
        self._begin(addr, False)
        total = 0
        for buf in vector:
            a = self._send(buf, 0, len(buf))
            total += a
            if a < len(buf):
                self._bus.stop()
                return total
        if stop:
            self._bus.stop()
        return total

    def readfrom_into(self, addr, buf, stop=True):
        """Read len(buf) bytes into buf."""
        self._begin(addr, True)
        if self._bus.recv(buf, 0, len(buf)) == TIMEOUT:
            self._fail(TIMEOUT)
        if stop:
            self._bus.stop()

    def readfrom(self, addr, nbytes, stop=True):
        """Read nbytes; returns bytes (allocates, as the real one does)."""
        buf = bytearray(nbytes)
        self.readfrom_into(addr, buf, stop)
        return bytes(buf)

    def writeto_mem(self, addr, memaddr, buf, *, addrsize=8):
        """Write buf from memory address memaddr in one transfer."""
        n = self._memaddr(memaddr, addrsize)
        self._begin(addr, False)
        if self._put(self._mem, 0, n):
            self._put(buf, 0, len(buf))
        self._bus.stop()

    def readfrom_mem_into(self, addr, memaddr, buf, *, addrsize=8):
        """Write memaddr, repeated START, read len(buf) bytes into buf."""
        n = self._memaddr(memaddr, addrsize)
        self._begin(addr, False)
        if not self._put(self._mem, 0, n):
            # The real read_mem stops and returns without reading: buf keeps what it had.
            self._bus.stop()
            return
        self._begin(addr, True)
        if self._bus.recv(buf, 0, len(buf)) == TIMEOUT:
            self._fail(TIMEOUT)
        self._bus.stop()

    def readfrom_mem(self, addr, memaddr, nbytes, *, addrsize=8):
        """Read nbytes from memory address memaddr; returns bytes."""
        buf = bytearray(nbytes)
        self.readfrom_mem_into(addr, memaddr, buf, addrsize=addrsize)
        return bytes(buf)


class I2C(SoftI2C):
    """Hardware I2C: I2C(id, freq=400000, *, scl, sda, timeout, bus=None, port="esp32")."""

    def __init__(self, id=0, freq=400000, *, scl=None, sda=None, timeout=50000, bus=None, port="esp32"):
        if port == "esp32":
            self._nack_errno = _ENODEV
        elif port == "rp2":
            self._nack_errno = _EIO
        else:
            raise ValueError("port: %r, allowed 'esp32' (NACK -> ENODEV) or 'rp2' (NACK -> EIO)" % (port,))
        if not isinstance(id, int) or id < 0:
            raise ValueError("I2C(%r) doesn't exist" % (id,))
        self.id = id
        self.port = port
        self._setup(freq, timeout, bus if bus is not None else shared_bus(id))
        self.scl = scl
        self.sda = sda


def reset():
    """Forget every shared bus (a fresh machine for the next test)."""
    _buses.clear()
