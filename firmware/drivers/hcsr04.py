"""HC-SR04 ranging on MicroPython: one sensor timed by echo pin IRQs (or machine.time_pulse_us),
on drivers.ranger's median filter; the five-sensor round robin (drivers.ranger.RoundRobin) and the
shared names are importable from here too.

Units: distances in 0.1 mm, temperature in 0.01 degC, pulse and block times in us, tick in ms.
Pins, the clock (`time` on a board, `_stub_clock` in tests) and time_pulse_us are passed in.
A ping reports a status; a distance is written only with OK, never in place of a fault. The
sonar order, names and status codes are the sensor contract's (hexapod.sensors).

With irq=True (main.py) the echo pin's IRQ stores ticks_us() at the echo's rise and fall into
a preallocated array (a hard IRQ: no allocation), so nothing waits for the echo: the round robin
fires a sensor in one tick and reads its echo at the next (one tick of latency, 20 ms, instead
of up to 14 ms of busy waiting per frame). Without Pin.irq on a port, or irq=False, ping()
blocks in time_pulse_us as before. Statuses, timeouts and limits are the same either way.
"""

from array import array

from micropython import const

from drivers.ranger import (  # noqa: F401 (the shared parts, importable from here as before)
    MAX_RANGE,
    MIN_CYCLE_US,
    NEIGHBOURS,
    RISE_US,
    TRIGGER_US,
    MedianRanger,
    RoundRobin,
    plan,
    round_trip_us,
    speed_x100,
)
from hexapod.sensors import (  # noqa: F401 (the contract's names, importable from the driver too)
    FRONT,
    LEFT_FRONT,
    LEFT_REAR,
    MIN_RANGE,
    NO_DISTANCE,
    NO_ECHO,
    OK,
    OUT_OF_RANGE,
    PENDING,
    RIGHT_FRONT,
    RIGHT_REAR,
    STUCK,
    TOO_CLOSE,
    WAIT,
)

# The contract's codes and the shared timings copied as private constants, folded into the code
# (the ping's path reads them every frame; an imported name is a dictionary lookup each time). The
# imports above keep them importable from here; tests/test_viper_twins.py checks each copy against
# its source.
_NO_ECHO = const(2)  # hexapod.sensors.NO_ECHO
_OK = const(0)  # hexapod.sensors.OK
_OUT_OF_RANGE = const(1)  # hexapod.sensors.OUT_OF_RANGE
_PENDING = const(6)  # hexapod.sensors.PENDING
_STUCK = const(3)  # hexapod.sensors.STUCK
_WAIT = const(5)  # hexapod.sensors.WAIT
_TRIGGER_US = const(10)  # drivers.ranger.TRIGGER_US
_MIN_CYCLE_US = const(60000)  # drivers.ranger.MIN_CYCLE_US
_SHIFT = const(14)  # drivers.ranger._SHIFT
_HALF = const(8192)  # drivers.ranger._HALF

# What the statuses mean here: OUT_OF_RANGE, an echo longer than max_range allows (incl. the
# module's 38 ms no-echo hold); NO_ECHO, no rise within the timeout; STUCK, the echo high before
# the trigger (nothing fired); TOO_CLOSE, an echo under MIN_RANGE (2 cm); WAIT, asked again within
# 60 ms of its last ping (nothing fired, buffers untouched); PENDING, fired and its echo still
# within its timeouts. dist[i] holds NO_DISTANCE whenever status[i] is not OK.


def _edge_handler(edges, ticks_us):
    """The echo pin's hard IRQ: ticks_us() of the first two edges into edges[1:3], edges[0] counts
    them (to 3). A closure, not a bound method: nothing to look up before the timestamp."""

    def edge(pin):
        t = ticks_us()
        n = edges[0]
        if n < 2:
            edges[n + 1] = t
        if n < 3:
            edges[0] = n + 1

    return edge


class HCSR04(MedianRanger):
    """One HC-SR04 on MicroPython: trigger is an output Pin, echo an input Pin; irq=True times
    the echo with the echo pin's IRQ (fire() now, collect_into() a tick later) where Pin.irq exists."""

    def __init__(
        self, trigger, echo, clock, time_pulse_us=None, *, max_range=10000, temp_centi_c=2000, samples=5, irq=False
    ):
        self.split = bool(irq) and hasattr(echo, "irq")  # fire and collect apart (RoundRobin)
        if time_pulse_us is None and not self.split:
            from machine import time_pulse_us
        self._trigger = trigger
        self._echo = echo
        self._clock = clock
        self._pulse = time_pulse_us
        self._last = 0  # ticks_us of the last trigger
        self._fired = False
        self._state = _WAIT  # of the ping fire() sent: PENDING while listening, else what to report
        self._t0 = 0  # ticks_us when the trigger fell: the rise timeout counts from here
        # The IRQ's only memory: edges since the trigger (0..3), ticks_us at the rise and the fall.
        self._edges = array("i", [0, 0, 0])
        MedianRanger.__init__(self, samples, max_range, temp_centi_c)
        trigger.value(0)
        if self.split:
            echo.irq(_edge_handler(self._edges, clock.ticks_us), echo.IRQ_RISING | echo.IRQ_FALLING, hard=True)

    def _block_us(self):
        # trigger, then the echo: up to timeout_us waiting for the rise, as long again timing it
        # (time_pulse_us blocks that long; with the IRQ the next tick collects it: it must fit a tick)
        return 2 + _TRIGGER_US + 2 * self.timeout_us

    def fire(self):
        """Trigger a ping and return at once: PENDING (the IRQ listens), or WAIT / STUCK, which
        collect_into() reports (irq=True; ping() fires through it too)."""
        clock = self._clock
        now = clock.ticks_us()
        if self._fired and clock.ticks_diff(now, self._last) < _MIN_CYCLE_US:
            s = _WAIT
        else:
            self._edges[0] = 0
            if self._echo.value():
                s = _STUCK
            else:
                t = self._trigger
                t.value(0)
                clock.sleep_us(2)
                t.value(1)
                clock.sleep_us(_TRIGGER_US)
                t.value(0)
                self._last = now
                self._fired = True
                s = _PENDING
        self._t0 = clock.ticks_us()  # the rise timeout counts from the trigger's fall
        self._state = s
        return s

    def result(self):
        """Status of the ping fire() sent, from the IRQ's timestamps (as time_pulse_us would
        judge it); PENDING while the echo may still rise or fall; OK sets self.distance."""
        s = self._state
        if s != _PENDING:
            return s
        clock = self._clock
        e = self._edges
        n = e[0]
        to = self.timeout_us
        if n == 0:
            return _PENDING if clock.ticks_diff(clock.ticks_us(), self._t0) < to else _NO_ECHO
        rise = clock.ticks_diff(e[1], self._t0)
        if rise < 0 or rise >= to:  # rose before our trigger fell (not ours), or too late
            return _NO_ECHO
        if n == 1:
            return _PENDING if clock.ticks_diff(clock.ticks_us(), e[1]) < to else _OUT_OF_RANGE
        us = clock.ticks_diff(e[2], e[1])
        if us >= to:
            return _OUT_OF_RANGE
        return self.accept((us * self._k + _HALF) >> _SHIFT)  # to_distance(us), a call less

    def _wait_result(self):
        s = self.result()
        while s == _PENDING:  # only when asked early (a ping(), or a tick sooner than max_block_us)
            self._clock.sleep_us(100)
            s = self.result()
        self._state = _WAIT  # reported once
        return s

    def collect_into(self, dist, status, i):
        """The ping fire() sent, into status[i] and dist[i] as measure_into(); waits for the rest
        of the echo only when called sooner than max_block_us after fire(). Returns the status."""
        s = self.result()
        if s == _PENDING:  # only when asked early: _wait_result's wait (a call less in the loop's frame)
            s = self._wait_result()
        self._state = _WAIT  # reported once
        return self._record(s, dist, status, i)

    def ping(self):
        """Fire one ping and wait for it; return a status code, and with OK the distance in
        self.distance (0.1 mm)."""
        s = self.fire()
        if self.split:
            return self._wait_result()
        if s != _PENDING:
            return s
        us = self._pulse(self._echo, 1, self.timeout_us)
        if us == -2:
            return _NO_ECHO
        if us < 0:
            return _OUT_OF_RANGE
        return self.accept(self.to_distance(us))
