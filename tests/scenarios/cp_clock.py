"""drivers.cp_clock on a fake supervisor.ticks_ms (2**29 ms, starting 65 s before it wraps) over the
virtual clock."""

import _stub_clock as v

from drivers import cp_clock

START = (1 << 29) - 65000


def _sup():
    return (v.now_us() // 1000 + START) & ((1 << 29) - 1)


def _clock():
    v.reset(0)
    return cp_clock.Clock(ticks_ms=_sup, sleep=v.sleep, delay_us=v.sleep_us, monotonic_ns=v.monotonic_ns)


def ticks(steps_ms):
    """[(ticks_ms, ticks_us)] after each step of virtual time (ms)."""
    c = _clock()
    out = []
    for step in steps_ms:
        v.advance_us(step * 1000)
        out.append((c.ticks_ms(), c.ticks_us()))
    return out


def frames_heap(n):
    """MicroPython only (gc.mem_alloc): heap bytes of n frames' clock reads (ticks_ms, ticks_diff,
    ticks_add, ticks_us, sleep_us), after a first n."""
    import gc

    c = _clock()

    def frames():
        t = c.ticks_ms()
        for _ in range(n):
            v.advance_us(20000)
            now = c.ticks_ms()
            c.ticks_diff(now, t)
            c.ticks_add(now, 20)
            c.ticks_us()
            c.sleep_us(10)
            t = now

    frames()
    gc.collect()
    gc.disable()
    before = gc.mem_alloc()
    frames()
    used = gc.mem_alloc() - before
    gc.enable()
    return used
