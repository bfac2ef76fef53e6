"""drivers.cp_clock: MicroPython's 2**30 ticks from CircuitPython's 2**29 supervisor.ticks_ms (CPython).

The oracle is plain modular arithmetic on the virtual clock's unwrapped time; the small-int
check runs cp_clock rewritten so every arithmetic result passes a |v| < 2**30 check.
"""

import sys
import types

import _stub_clock as vclock
import pytest

from drivers import cp_clock
from hexapod_host.stubs.circuitpython import SUPERVISOR_PERIOD_MS, CircuitPython
from tests.test_leg_ranges import SMALL, Checker, instrumented

P = 1 << 30
MS_STEPS = (0, 1, 7, 999, 1000, 65000, 65001, 1 << 20, (1 << 20) + 1, 1073741, 1073742, 99999999, (1 << 29) - 1)


def sources(start_ms):
    """A fake supervisor.ticks_ms starting at start_ms (mod 2**29) on the virtual clock."""
    vclock.reset(0)
    return CircuitPython(bus=None, ticks_start_ms=start_ms)


VIRTUAL = {"sleep": vclock.sleep, "delay_us": vclock.sleep_us, "monotonic_ns": vclock.monotonic_ns}


def make(cp, module=cp_clock):
    return module.Clock(**dict(VIRTUAL, ticks_ms=cp.ticks_ms))


@pytest.mark.parametrize("start", [0, SUPERVISOR_PERIOD_MS - 65000, SUPERVISOR_PERIOD_MS - 1, 12345])
def test_ticks_follow_elapsed_time_across_both_wraps(start):
    cp = sources(start)
    clock = make(cp)
    ms0, us0 = clock.ticks_ms(), clock.ticks_us()
    elapsed = 0
    seen_source_wrap = seen_ms_wrap = seen_us_wrap = False
    prev_src, prev_ms, prev_us = cp.ticks_ms(), ms0, us0
    for step in MS_STEPS * 4:
        vclock.advance_us(step * 1000)
        elapsed += step
        ms, us = clock.ticks_ms(), clock.ticks_us()
        assert ms == (ms0 + elapsed) % P and us == (us0 + 1000 * elapsed) % P, (step, elapsed)
        assert clock.ticks_diff(ms, prev_ms) == (step if step < P // 2 else step - P)
        # hexapod.tick's way: (now - last) & 0x3FFFFFFF
        assert (ms - prev_ms) & 0x3FFFFFFF == step % P
        src = cp.ticks_ms()
        seen_source_wrap |= src < prev_src
        seen_ms_wrap |= ms < prev_ms
        seen_us_wrap |= us < prev_us
        prev_src, prev_ms, prev_us = src, ms, us
    assert seen_source_wrap and seen_ms_wrap and seen_us_wrap and elapsed > P


def test_wrap_65_s_after_boot_is_invisible_to_the_loop():
    cp = sources(SUPERVISOR_PERIOD_MS - 65000)  # as CircuitPython boots
    clock = make(cp)
    last = clock.ticks_ms()
    vclock.advance_us(64990 * 1000)
    before = cp.ticks_ms()
    for _ in range(3):  # 20 ms frames over the supervisor's wrap
        vclock.advance_us(20000)
        now = clock.ticks_ms()
        assert clock.ticks_diff(now, last) in (64990 + 20, 20)
        last = now
    assert cp.ticks_ms() < before  # the source did wrap meanwhile


def test_ticks_add_and_diff_match_micropython():
    clock = make(sources(0))
    ticks = (0, 1, 12345, P // 2 - 1, P // 2, P // 2 + 1, P - 1000, P - 1)
    deltas = (-P // 2, -P // 2 + 1, -70000, -1, 0, 1, 999, 60000, P // 2 - 1)
    for t in ticks:
        for d in deltas:
            t2 = clock.ticks_add(t, d)
            assert t2 == vclock.ticks_add(t, d) == (t + d) % P
            assert clock.ticks_diff(t2, t) == d
        for t2 in ticks:
            assert clock.ticks_diff(t, t2) == vclock.ticks_diff(t, t2) == ((t - t2 + P // 2) % P) - P // 2


def test_no_intermediate_leaves_the_small_ints():
    checker = Checker()
    mod = instrumented(cp_clock, checker, {})
    for start in (0, SUPERVISOR_PERIOD_MS - 1, SUPERVISOR_PERIOD_MS // 2):
        cp = sources(start)
        clock = make(cp, mod)
        for step in MS_STEPS * 3:
            vclock.advance_us(step * 1000)
            clock.ticks_ms()
            clock.ticks_us()
        edges = (0, 1, P // 2 - 1, P // 2, P - 1)
        for t in edges:
            for d in (-P // 2, -1, 0, 1, P // 2 - 1):
                clock.ticks_add(t, d)
            for t2 in edges:
                clock.ticks_diff(t, t2)
    for ms in (0, 1, (1 << 20) - 1, 1 << 20, (1 << 29) - 1):
        assert mod.ms_to_us30(ms) == ms * 1000 % P
    assert checker.biggest < SMALL and checker.biggest > P // 2  # it did see large values


def test_sleeps():
    cp = sources(0)
    calls = []
    clock = cp_clock.Clock(
        ticks_ms=cp.ticks_ms,
        sleep=lambda s: calls.append(("sleep", s)) or vclock.sleep(s),
        delay_us=lambda us: calls.append(("delay_us", us)) or vclock.sleep_us(us),
        monotonic_ns=vclock.monotonic_ns,
    )
    t0 = vclock.now_us()
    clock.sleep_us(10)
    clock.sleep_us(999)
    clock.sleep_us(1000)
    clock.sleep_us(0)
    clock.sleep_us(-5)
    clock.sleep_ms(20)
    clock.sleep_ms(0)
    clock.sleep_ms(-1)
    assert vclock.now_us() - t0 == 10 + 999 + 1000 + 20000
    assert calls == [("delay_us", 10), ("delay_us", 999), ("sleep", 0.001), ("sleep", 0.02)]
    assert clock.monotonic_ns() == vclock.now_us() * 1000


BAD = [
    ({"ticks_ms": 5}, "ticks_ms: 5"),
    ({"sleep": "time.sleep"}, "sleep: 'time.sleep'"),
    ({"delay_us": 1.5}, "delay_us: 1.5"),
    ({"monotonic_ns": 0}, "monotonic_ns: 0"),
    ({"ticks_ms": lambda: -1}, "gave -1"),
    ({"ticks_ms": lambda: 1 << 29}, "gave 536870912"),
    ({"ticks_ms": lambda: 12.5}, "gave 12.5"),
    ({"ticks_ms": lambda: True}, "gave True"),
    ({"ticks_ms": lambda: None}, "gave None"),
    ({"ticks_ms": lambda: "100"}, "gave '100'"),
]


@pytest.mark.parametrize("kw,message", BAD)
def test_bad_sources_are_refused_by_name(kw, message):
    full = dict(VIRTUAL, ticks_ms=lambda: 0)
    full.update(kw)
    with pytest.raises(ValueError, match="allowed") as e:
        cp_clock.Clock(**full)
    assert message in str(e.value)


def test_defaults_are_circuitpythons_modules(monkeypatch):
    cp = sources(SUPERVISOR_PERIOD_MS - 3)
    monkeypatch.setitem(sys.modules, "supervisor", cp.modules["supervisor"])
    monkeypatch.setitem(sys.modules, "microcontroller", cp.modules["microcontroller"])
    fake_time = types.SimpleNamespace(sleep=vclock.sleep, monotonic_ns=vclock.monotonic_ns)
    monkeypatch.setitem(sys.modules, "time", fake_time)
    clock = cp_clock.Clock()
    t = clock.ticks_ms()
    clock.sleep_ms(5)
    clock.sleep_us(7)
    assert clock.ticks_diff(clock.ticks_ms(), t) == 5 and vclock.now_us() == 5007


def test_same_ticks_in_both_runtimes(rt):
    # tests/scenarios/cp_clock.py: a supervisor.ticks_ms starting 65 s before its 2**29 ms wrap
    got = rt.call("scenarios.cp_clock:ticks", list(MS_STEPS * 3))
    start = SUPERVISOR_PERIOD_MS - 65000
    elapsed, expected = 0, []
    for step in MS_STEPS * 3:
        elapsed += step
        expected.append(((start + elapsed) % P, (start * 1000 + elapsed * 1000) % P))
    assert [tuple(x) for x in got] == expected


def test_a_frames_clock_reads_allocate_nothing(mp):
    assert mp.call("scenarios.cp_clock:frames_heap", 500) == 0
