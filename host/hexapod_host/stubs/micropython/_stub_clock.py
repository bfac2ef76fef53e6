"""Virtual clock: MicroPython's ticks_* and sleep_* on a counter that only moves when told.

Time in integer microseconds. Nothing here reads the host's clock, so a test or the
simulator runs as fast as the CPU allows and the same way every time. The tick values wrap
like a board's: ticks_us() and ticks_ms() count modulo TICKS_PERIOD (2**30, as on the rp2
and esp32 ports), and only ticks_diff / ticks_add may do arithmetic on them.

Pass this module wherever a driver takes a `clock` (on a board, pass `time`). Chip models
read `now_us()`, the unwrapped virtual time, to place their edges.
"""

TICKS_PERIOD = 1 << 30
TICKS_MAX = TICKS_PERIOD - 1
_HALF = TICKS_PERIOD // 2

_now = 0  # virtual microseconds since reset(), never wraps
# Set by _stub_pins while a Pin has an IRQ handler: called with the instant time is about to
# reach; it moves _now to each edge on the way and runs the handlers there, as a board would.
_edge_hook = None


def _to(t_us):
    global _now
    if _edge_hook is not None:
        _edge_hook(t_us)
    _now = t_us


def reset(start_us=0):
    """Set virtual time to start_us (us); start near TICKS_PERIOD to test the wrap."""
    global _now
    if not isinstance(start_us, int) or start_us < 0:
        raise ValueError("start_us: %r, allowed an int >= 0" % (start_us,))
    _now = start_us


def now_us():
    """Unwrapped virtual time in us (for models and tests, not for firmware)."""
    return _now


def advance_us(us):
    """Move virtual time forward by us (int >= 0)."""
    if us < 0:
        raise ValueError("advance_us: %r, time only moves forward" % (us,))
    _to(_now + us)


def advance_to(t_us):
    """Move virtual time forward to the unwrapped instant t_us; never backwards."""
    if t_us > _now:
        _to(t_us)


def ticks_us():
    """Wrapping microsecond tick, 0..TICKS_MAX."""
    return _now & TICKS_MAX


def ticks_ms():
    """Wrapping millisecond tick, 0..TICKS_MAX."""
    return (_now // 1000) & TICKS_MAX


def ticks_cpu():
    """Same as ticks_us here: one virtual CPU tick per microsecond."""
    return _now & TICKS_MAX


def ticks_add(ticks, delta):
    """ticks + delta (either sign) modulo the tick period."""
    return (ticks + delta) & TICKS_MAX


def ticks_diff(ticks1, ticks2):
    """Signed ticks1 - ticks2, correct across one wrap (result in -2**29 .. 2**29-1)."""
    return ((ticks1 - ticks2 + _HALF) & TICKS_MAX) - _HALF


def sleep_us(us):
    """Advance virtual time by us; a negative value returns at once, as on a board."""
    if us > 0:
        _to(_now + us)


def sleep_ms(ms):
    """Advance virtual time by ms milliseconds."""
    if ms > 0:
        _to(_now + ms * 1000)


def sleep(seconds):
    """Advance virtual time by seconds (int or float), rounded to the nearest us."""
    if seconds > 0:
        _to(_now + int(seconds * 1000000 + 0.5))


def monotonic():
    """CircuitPython's time.monotonic(): virtual seconds as a float."""
    return _now / 1000000


def monotonic_ns():
    """CircuitPython's time.monotonic_ns(): virtual nanoseconds."""
    return _now * 1000
