"""MicroPython's `time` tick API on CircuitPython, for runner.Runner and the drivers' `clock`.

CircuitPython's integer clock is supervisor.ticks_ms(), which wraps at 2**29 ms (first wrap
about 65 s after power-on). hexapod.tick and MicroPython code expect ticks that wrap at 2**30
(intervals masked with 0x3FFFFFFF), so Clock keeps its own 2**30 ms and us counters, advanced
by the supervisor's ms since the last read. Every value stays a small int (< 2**30): no big
int is made in the steady state. ticks_us() moves in whole ms (1000 us steps): the source has
no finer integer clock (time.monotonic_ns() makes a big int per call).

Sleeps: sleep_us below 1 ms busy-waits in microcontroller.delay_us (time.sleep has 1 ms
resolution on CircuitPython; an HC-SR04 trigger needs 10 us); longer ones and sleep_ms go to
time.sleep, the one place here a float is made (seconds), outside the tick.
"""

from micropython import const

_MASK = const(0x3FFFFFFF)  # MicroPython's ticks period is 2**30
_HALF = const(0x20000000)
_SUP_MASK = const(0x1FFFFFFF)  # supervisor.ticks_ms() wraps at 2**29
SHORT_US = const(1000)  # sleep_us below this busy-waits in delay_us


def _add30(a, b):
    """(a + b) mod 2**30 for a, b in 0..2**30-1, never leaving the small ints."""
    r = a - (_MASK - b)  # a + b - (2**30 - 1)
    if r > 0:
        return r - 1
    return r + _MASK


def ms_to_us30(ms):
    """(ms * 1000) mod 2**30 for ms in 0..2**29-1, with no intermediate >= 2**30."""
    hi = ms >> 20
    lo = ms & 0xFFFFF  # lo * 1000 < 2**30
    return _add30(lo * 1000, ((hi * 1000) & 0x3FF) << 20)


class Clock:
    """ticks_ms/ticks_us/ticks_add/ticks_diff/sleep_us/sleep_ms/monotonic_ns, MicroPython-shaped.

    Sources default to supervisor.ticks_ms, time.sleep, microcontroller.delay_us and
    time.monotonic_ns; tests pass their own (keyword arguments, callables).
    """

    def __init__(self, *, ticks_ms=None, sleep=None, delay_us=None, monotonic_ns=None):
        for name, fn in (("ticks_ms", ticks_ms), ("sleep", sleep), ("delay_us", delay_us)):
            if fn is not None and not callable(fn):
                raise ValueError("%s: %r, allowed a function (or None for CircuitPython's own)" % (name, fn))
        if monotonic_ns is not None and not callable(monotonic_ns):
            raise ValueError("monotonic_ns: %r, allowed a function (or None for time.monotonic_ns)" % (monotonic_ns,))
        if ticks_ms is None:
            import supervisor

            ticks_ms = supervisor.ticks_ms
        if sleep is None or monotonic_ns is None:
            import time

            sleep = sleep or time.sleep
            monotonic_ns = monotonic_ns or time.monotonic_ns
        if delay_us is None:
            import microcontroller

            delay_us = microcontroller.delay_us
        self._source = ticks_ms
        self._sleep = sleep
        self._delay_us = delay_us
        self._monotonic_ns = monotonic_ns
        first = ticks_ms()
        if not isinstance(first, int) or isinstance(first, bool) or not 0 <= first <= _SUP_MASK:
            raise ValueError("ticks_ms() gave %r, allowed an int 0..2**29-1 (supervisor.ticks_ms)" % (first,))
        self._last = first
        self._ms = first  # any start will do: only differences mean anything
        self._us = ms_to_us30(first)

    def _update(self):
        s = self._source()
        d = (s - self._last) & _SUP_MASK  # ms since the last read, across the source's 2**29 wrap
        if d:
            self._last = s
            self._ms = _add30(self._ms, d)
            self._us = _add30(self._us, ms_to_us30(d))

    def ticks_ms(self):
        """Milliseconds, wrapping at 2**30 (read at least once every 2**29 ms to keep count)."""
        self._update()
        return self._ms

    def ticks_us(self):
        """Microseconds, wrapping at 2**30, in 1000 us steps."""
        self._update()
        return self._us

    def ticks_add(self, ticks, delta):
        """ticks + delta modulo 2**30; delta in -2**29..2**29-1 (as MicroPython's)."""
        if delta >= 0:
            return _add30(ticks, delta)
        r = ticks + delta
        if r < 0:
            r = (r + _MASK) + 1
        return r

    def ticks_diff(self, ticks1, ticks2):
        """Signed ticks1 - ticks2 across one wrap, in -2**29..2**29-1."""
        d = ticks1 - ticks2
        if d >= _HALF:
            return (d - _MASK) - 1
        if d < -_HALF:
            return (d + _MASK) + 1
        return d

    def sleep_us(self, us):
        """Wait us microseconds: busy below 1 ms, else time.sleep (1 ms resolution)."""
        if us <= 0:
            return
        if us < SHORT_US:
            self._delay_us(us)
        else:
            self._sleep(us / 1000000)

    def sleep_ms(self, ms):
        """Wait ms milliseconds in time.sleep (CircuitPython runs its background tasks meanwhile)."""
        if ms > 0:
            self._sleep(ms / 1000)

    def monotonic_ns(self):
        """time.monotonic_ns() (a big int: not for the tick)."""
        return self._monotonic_ns()
