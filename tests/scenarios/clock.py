"""The virtual clock (host/stubs/_stub_clock.py): wrapping tick arithmetic and sleeps."""

import _stub_clock as clock


def round_trips():
    """(t, d, ticks_add(t, d)) of every pair whose add and diff do not round-trip across the wrap."""
    clock.reset(0)
    p = clock.TICKS_PERIOD
    bad = []
    for t in (0, 1, 12345, p // 2 - 1, p // 2, p - 1000, p - 1):
        for d in (-p // 2, -70000, -1, 0, 1, 999, 60000, p // 2 - 1):
            t2 = clock.ticks_add(t, d)
            if (
                not 0 <= t2 < p
                or clock.ticks_diff(t2, t) != d
                or clock.ticks_diff(t, t2) != (-d if d != -p // 2 else d)
            ):
                bad.append((t, d, t2))
    return bad


def diffs(pairs):
    """ticks_diff(a, b) of each pair."""
    clock.reset(0)
    return [clock.ticks_diff(a, b) for a, b in pairs]


def sleeps():
    """(a, b, diff us, diff ms, slept us, now us) of sleeps from 4 us before the wrap."""
    clock.reset(clock.TICKS_PERIOD - 4)
    a = clock.ticks_us()
    clock.sleep_us(10)
    b = clock.ticks_us()
    m0 = clock.ticks_ms()
    clock.sleep_ms(3)
    m1 = clock.ticks_ms()
    t0 = clock.now_us()
    clock.sleep(0.00001)
    clock.sleep_us(-5)
    clock.sleep_ms(0)
    t1 = clock.now_us()
    return (a, b, clock.ticks_diff(b, a), clock.ticks_diff(m1, m0), t1 - t0, clock.now_us())


def backwards():
    """[now, advance_us(-1)'s error, reset(-5)'s error, now]: time only moves forward."""
    clock.reset(0)
    clock.advance_us(500)
    clock.advance_to(100)
    out = [clock.now_us()]
    for bad in ((clock.advance_us, -1), (clock.reset, -5)):
        try:
            bad[0](bad[1])
            out.append("accepted")
        except ValueError as e:
            out.append(str(e))
    out.append(clock.now_us())
    return out


def monotonic():
    """(monotonic(), monotonic_ns()) after sleeping 1.5 s."""
    clock.reset(0)
    clock.sleep_ms(1500)
    return (clock.monotonic(), clock.monotonic_ns())
