"""Virtual clock: MicroPython's wrapping tick arithmetic, sleeps that cost no real time. Both runtimes."""

PERIOD = 1 << 30

PRELUDE = """
import _stub_clock as clock
clock.reset(0)
"""


def test_ticks_add_and_diff_round_trip_across_the_wrap(rt):
    src = (
        PRELUDE
        + """
P = clock.TICKS_PERIOD
bad = []
for t in (0, 1, 12345, P // 2 - 1, P // 2, P - 1000, P - 1):
    for d in (-P // 2, -70000, -1, 0, 1, 999, 60000, P // 2 - 1):
        t2 = clock.ticks_add(t, d)
        if not 0 <= t2 < P or clock.ticks_diff(t2, t) != d or clock.ticks_diff(t, t2) != (-d if d != -P // 2 else d):
            bad.append((t, d, t2))
print(bad)
"""
    )
    assert rt.value(src) == []


def test_ticks_diff_matches_the_modular_definition(rt):
    # independent oracle: the representative of (a - b) mod P in [-P/2, P/2)
    pairs = [(0, PERIOD - 1), (PERIOD - 1, 0), (5, 10), (10, 5), (PERIOD // 2, 0), (0, PERIOD // 2), (123, 123)]
    expected = [((a - b + PERIOD // 2) % PERIOD) - PERIOD // 2 for a, b in pairs]
    src = PRELUDE + "print([clock.ticks_diff(a, b) for a, b in %r])" % (pairs,)
    assert rt.value(src) == expected
    assert expected[0] == 1 and expected[1] == -1  # the wrap itself


def test_sleeps_move_virtual_time_and_ticks_wrap(rt):
    src = """
import _stub_clock as clock
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
print((a, b, clock.ticks_diff(b, a), clock.ticks_diff(m1, m0), t1 - t0, clock.now_us()))
"""
    a, b, diff, diff_ms, slept, now = rt.value(src)
    assert a == PERIOD - 4 and b == 6 and diff == 10
    assert diff_ms == 3
    assert slept == 10
    assert now == PERIOD - 4 + 10 + 3000 + 10


def test_time_only_moves_forward(rt):
    src = (
        PRELUDE
        + """
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
print(out)
"""
    )
    out = rt.value(src)
    assert out[0] == 500 and out[3] == 500
    assert "forward" in out[1] and ">= 0" in out[2]


def test_monotonic_is_seconds_of_virtual_time(rt):
    src = PRELUDE + "clock.sleep_ms(1500)\nprint((clock.monotonic(), clock.monotonic_ns()))"
    assert rt.value(src) == (1.5, 1500000000)
