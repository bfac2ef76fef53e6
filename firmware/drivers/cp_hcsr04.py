"""HC-SR04 on CircuitPython through Adafruit's adafruit_hcsr04, behind drivers.hcsr04's interface.

Same units as drivers.hcsr04 (0.1 mm, 0.01 degC, us), the status codes of hexapod.sensors, same
median filter and round robin. What Adafruit's library cannot tell apart is reported as NO_ECHO: its
RuntimeError("Timed out") covers a missing echo, an echo stuck high and an echo longer than
its timeout. It assumes 340 m/s; the distance is rescaled to the configured temperature.
Floats are unavoidable here (the library returns cm as a float), so unlike the MicroPython
driver a ping allocates.
"""

import adafruit_hcsr04

from drivers.ranger import MIN_CYCLE_US, MedianRanger, speed_x100
from hexapod.sensors import NO_ECHO, WAIT

ADAFRUIT_SPEED_X100 = 34000000  # adafruit_hcsr04: distance_cm = pulse_us * 0.017, i.e. 340 m/s
ADAFRUIT_MIN_TIMEOUT_S = 0.05  # the library's advice: a shorter timeout cuts off the 38 ms no-echo hold


class HCSR04(MedianRanger):
    """One HC-SR04 on CircuitPython; trigger_pin/echo_pin are `board` pins, clock is `time`."""

    def __init__(self, trigger_pin, echo_pin, clock, *, max_range=10000, temp_centi_c=2000, samples=5, timeout_s=None):
        if timeout_s is not None and (
            not isinstance(timeout_s, (int, float)) or isinstance(timeout_s, bool) or not 0.001 <= timeout_s <= 1
        ):
            raise ValueError("timeout_s: %r, allowed 0.001..1 s" % (timeout_s,))
        self._clock = clock
        self._last_ns = 0
        self._fired = False
        self._timeout_s = timeout_s
        MedianRanger.__init__(self, samples, max_range, temp_centi_c)
        if timeout_s is None:
            self._timeout_s = max(ADAFRUIT_MIN_TIMEOUT_S, self.timeout_us / 1000000)
        self.max_block_us = self._block_us()
        self.sonar = adafruit_hcsr04.HCSR04(trigger_pin, echo_pin, timeout=self._timeout_s)

    def set_temperature(self, temp_centi_c):
        MedianRanger.set_temperature(self, temp_centi_c)
        self._scale = 100 * speed_x100(temp_centi_c) / ADAFRUIT_SPEED_X100  # cm at 340 m/s -> 0.1 mm

    def _block_us(self):
        if self._timeout_s is None:
            return 0
        # bit-bang path: up to the timeout waiting for the rise and as long again for the fall
        return 10 + 2 * int(self._timeout_s * 1000000 + 0.5)

    def ping(self):
        """Fire one ping; return a status code, and with OK the distance in self.distance (0.1 mm)."""
        now = self._clock.monotonic_ns()
        if self._fired and now - self._last_ns < MIN_CYCLE_US * 1000:
            return WAIT
        self._last_ns = now
        self._fired = True
        try:
            cm = self.sonar.distance
        except RuntimeError:
            return NO_ECHO
        return self.accept(int(cm * self._scale + 0.5))

    def deinit(self):
        self.sonar.deinit()
