"""CircuitPython backend of the PCA9685 servo driver: same interface, busio.I2C passed in.

Start-up is Adafruit's adafruit_pca9685 (reset, then its frequency setter with the board's
oscillator trim as reference_clock_speed: sleep, PRE_SCALE, wake, 5 ms, RESTART + AI), plus
MODE2 = OUTDRV | OCH. Frames, read-back, retries and status bits are drivers.pca9685's:
the two I2C calls go through Adafruit's I2CDevice (bus lock included), and a frame is still
one auto-increment burst per chip. adafruit_servokit is not used for frames: it writes one
channel per transaction (18 for 18 servos) and rounds through a float duty cycle.

adafruit_pca9685 and adafruit_register serve the start-up only: init() imports them and lets
them go when it is done (13.5 KB of the VM's heap, more than a Feather can spare while the loop
runs); a re-init after bus trouble loads them again for its time.
"""

from micropython import const

from drivers import pca9685
from drivers.pca9685 import FAILED, OFFLINE, OK, REINIT, RETRIED, ServoBank  # noqa: F401  (one import for callers)
from hexapod import release

_AI = const(0x20)
_OCH = const(0x08)
_OUTDRV = const(0x04)
# Adafruit's modules the start-up loads (adafruit_bus_device stays: every frame goes through it).
STARTUP_ONLY = (
    "adafruit_pca9685",
    "adafruit_register.i2c_struct",
    "adafruit_register.i2c_struct_array",
    "adafruit_register",
)


class PCA9685(pca9685.PCA9685):
    """One PCA9685 on a busio.I2C; same arguments as drivers.pca9685.PCA9685 except ext_clock."""

    def __init__(self, i2c, address=0x40, **kw):
        if kw.get("ext_clock"):
            raise ValueError("ext_clock: adafruit_pca9685 has no EXTCLK start-up; use the MicroPython driver")
        kw.setdefault("sleep_us", _no_sleep)  # Adafruit's start-up does its own 5 ms wait
        self._dev = None
        super().__init__(i2c, address, **kw)

    def init(self):
        """Adafruit's start-up and frequency setter, then MODE2; False marks the chip offline."""
        import adafruit_pca9685

        dev = None
        try:
            pca = adafruit_pca9685.PCA9685(self.i2c, address=self.address, reference_clock_speed=self.osc_hz)
            pca.frequency = self.freq_hz
            pca.mode2_reg = _OUTDRV | _OCH
            prescale = pca.prescale_reg
            ok = pca.mode1_reg & 0x7F == _AI and prescale >= 3
            dev = pca.i2c_device  # Adafruit's object goes with its modules: the frames need only this
        except (OSError, ValueError):  # ValueError: I2CDevice's probe found nobody at the address
            ok = False
        pca = adafruit_pca9685 = None
        release(*STARTUP_ONLY)
        if ok:
            self._dev = dev
            # Adafruit computes PRE_SCALE in floats; counts follow what the chip really holds.
            self._set_prescale(prescale)
        self.offline = not ok
        self._since = 0
        return ok

    def _send(self, buf, n):
        status = OK
        for _ in range(self._retries + 1):
            try:
                with self._dev as d:
                    d.write(buf, end=n)
                return status
            except OSError as e:
                self.errors += 1
                self.last_errno = e.args[0]
                status = RETRIED
        return FAILED

    def _read_reg(self, reg):
        for _ in range(self._retries + 1):
            try:
                self._ptr[0] = reg
                with self._dev as d:
                    d.write_then_readinto(self._ptr, self._reg1)
                return self._reg1[0]
            except OSError as e:
                self.errors += 1
                self.last_errno = e.args[0]
        return -1

    def _write_reg(self, reg, value):
        if self._dev is None:
            return FAILED
        return super()._write_reg(reg, value)


def _no_sleep(_us):
    pass


def servo_bank(i2c, pca, table, **kw):
    """drivers.pca9685.servo_bank with this backend's chips (busio.I2C in)."""
    return pca9685.servo_bank(i2c, pca, table, chip_class=PCA9685, **kw)


__all__ = ["PCA9685", "ServoBank", "servo_bank", "OK", "RETRIED", "FAILED", "REINIT", "OFFLINE"]
