"""HC-SR04 on CircuitPython that never waits for its echo: pulseio.PulseIn times it in the background.

Same interface and units as drivers.ranger (MedianRanger: ping, measure_into, max_block_us;
0.1 mm, 0.01 degC, us), the status codes of hexapod.sensors. On its slot a sensor reads the echo PulseIn captured
since its previous ping, then fires the next ping (10 us trigger) and returns: it blocks for
the trigger only, where adafruit_hcsr04 waits up to twice its 50 ms timeout.

One slot of latency: the distance a slot reports is the echo of the ping fired on the
previous slot of that sensor, one round-robin cycle earlier (100 ms for five sensors at
20 ms ticks). The first slot only fires (WAIT: buffers untouched, no result yet).

What the capture says (PulseIn with idle_state=False records the high time first, then
alternating low/high widths in us, each written when its level ends, 65535 at most):
- one high width (or three: a stray pulse after ours) -> the echo; wider than timeout_us,
  e.g. the module's 38 ms hold when nothing is within 4 m -> OUT_OF_RANGE; else the
  distance, with drivers.ranger's OUT_OF_RANGE / TOO_CLOSE checks;
- nothing -> NO_ECHO: no echo rose (missing echo, unplugged), or it never fell (stuck high;
  PulseIn cannot see a level that does not change, so STUCK is not reported here);
- two widths (the line went high again and stays high), or a full buffer (a noisy line) ->
  NO_ECHO: which pulse is ours is unknown.
A ping fired while the echo line may have been high (the capture before it was not one clean
pulse) is not trusted either: PulseIn would time the rest of that high level as if it were
an echo. It is reported NO_ECHO, so after a missing or stuck echo the first good distance
comes one cycle later. Integer maths only on the slot's path.
"""

import digitalio
import microcontroller
import pulseio
from micropython import const

from drivers.ranger import TRIGGER_US, MedianRanger
from hexapod.sensors import NO_ECHO, OUT_OF_RANGE, WAIT

MAXLEN = const(4)  # pulse widths PulseIn keeps: ours, then room to see a stray one
MIN_CYCLE_MS = const(60)  # datasheet: >= 60 ms between pings of one module


class HCSR04(MedianRanger):
    """One HC-SR04 on CircuitPython: trigger_pin and echo_pin are `board` pins, clock a cp_clock.Clock."""

    def __init__(self, trigger_pin, echo_pin, clock, *, max_range=10000, temp_centi_c=2000, samples=5):
        for name, pin in (("trigger_pin", trigger_pin), ("echo_pin", echo_pin)):
            if not isinstance(pin, microcontroller.Pin):
                raise ValueError("%s: %r, allowed a `board` pin such as board.D5" % (name, pin))
        if trigger_pin is echo_pin or trigger_pin == echo_pin:
            raise ValueError("trigger_pin and echo_pin are both %r: allowed two different pins" % (trigger_pin,))
        for name in ("ticks_ms", "ticks_diff", "sleep_us"):
            if not callable(getattr(clock, name, None)):
                raise ValueError("clock %r has no %s(): allowed a cp_clock.Clock" % (clock, name))
        MedianRanger.__init__(self, samples, max_range, temp_centi_c)  # checks the numbers before any pin
        self._clock = clock
        self._last = 0  # ticks_ms of the last trigger
        self._fired = False
        # Before PulseIn owns the echo pin: the line must be low for the first capture to be trusted.
        probe = digitalio.DigitalInOut(echo_pin)
        probe.switch_to_input()
        self._clean = not probe.value
        probe.deinit()
        self._trigger = digitalio.DigitalInOut(trigger_pin)
        self._trigger.switch_to_output(value=False)
        self._echo = pulseio.PulseIn(echo_pin, maxlen=MAXLEN, idle_state=False)
        self._echo.pause()
        self._echo.clear()

    def _block_us(self):
        # the trigger pulse only; reading the capture and re-arming PulseIn do not wait
        return TRIGGER_US

    def _capture(self, n):
        """Status of the ping fired on the previous slot, from the n widths PulseIn holds now."""
        if not self._clean or n == 0 or n == 2 or n >= MAXLEN:
            return NO_ECHO
        us = self._echo[0]
        if us > self.timeout_us:  # keeps us * k below 2**30 in to_distance
            return OUT_OF_RANGE
        return self.accept(self.to_distance(us))

    def ping(self):
        """Read the last ping's echo, fire the next; return a status, with OK self.distance (0.1 mm)."""
        clock = self._clock
        now = clock.ticks_ms()
        if self._fired:
            if clock.ticks_diff(now, self._last) < MIN_CYCLE_MS:
                return WAIT
            n = len(self._echo)
            status = self._capture(n)
            self._clean = n == 1 or n == 3  # the capture ended low: the next ping starts on a low line
        else:
            status = WAIT
        echo = self._echo
        echo.pause()
        echo.clear()
        echo.resume()  # waits for the echo to rise: PulseIn's first width is the high one
        t = self._trigger
        t.value = True
        clock.sleep_us(TRIGGER_US)
        t.value = False
        self._last = now
        self._fired = True
        return status

    def deinit(self):
        """Release both pins."""
        self._echo.deinit()
        self._trigger.deinit()
