"""The echo timed by pin IRQs: the stub Pin.irq runs handlers at the models' edges on the virtual
clock; the driver (irq=True) against hand-worked echoes at the range ends, timeouts to the us,
faults; Runner.wait holds the 20 ms grid to the us. Both runtimes."""

import pytest

PRELUDE = """
import _stub_clock as clock
import _stub_pins as pins
import hcsr04_model as model
from machine import Pin, time_pulse_us
from drivers import hcsr04 as drv
clock.reset(START)
pins.reset()
"""


def prelude(start=1000):
    return PRELUDE.replace("START", str(start))


def test_stub_irq_handlers_run_at_the_edges_in_time_order(rt):
    src = (
        prelude()
        + """
seen = []
a = model.HCSR04(2, 3, distance=1000)
b = model.HCSR04(4, 5, distance=1000)
Pin(3, Pin.IN).irq(lambda p: seen.append(("a", p.value(), clock.ticks_us())), Pin.IRQ_RISING | Pin.IRQ_FALLING)
Pin(5, Pin.IN).irq(lambda p: seen.append(("b", p.value(), clock.ticks_us())), Pin.IRQ_FALLING, hard=True)
ta, tb = Pin(2, Pin.OUT), Pin(4, Pin.OUT)
for t in (ta, tb):
    t.value(1)
    clock.sleep_us(10)
    t.value(0)  # triggers fall at 1010 and 1020: echoes rise 460 us later
clock.sleep_us(100000)
now = clock.now_us()
Pin(3).irq(None)
ta.value(1); clock.sleep_us(10); ta.value(0)
clock.sleep_ms(70)
print((seen, now))
"""
    )
    seen, now = rt.value(src)
    w = 582  # 2 * 100 mm / 343.42 mm/ms at 20 degC = 582.4 us, the model rounds
    assert seen == [("a", 1, 1470), ("a", 0, 1470 + w), ("b", 0, 1480 + w)]  # b only falling; a removed
    assert now == 101020


def test_stub_irq_sees_a_forced_or_unplugged_line_move(rt):
    src = (
        prelude()
        + """
seen = []
m = model.HCSR04(2, 3, distance=1000)
m.stuck_high = True
p = Pin(3, Pin.IN)
p.irq(lambda q: seen.append((q.value(), clock.ticks_us())))
clock.sleep_us(5)
pins.disconnect(3)  # the stuck module unplugged: the line falls to its pull (none: low)
clock.sleep_us(5)
pins.force(3, 1)
pins.force(3, 1)  # no change, no edge
clock.sleep_us(5)
pins.force(3, -1)
clock.sleep_us(5)
pins.connect(3, m)  # plugged back in, still stuck high
print(seen)
"""
    )
    assert rt.value(src) == [(0, 1005), (1, 1010), (0, 1015), (1, 1020)]


def test_stub_irq_two_pins_with_edges_at_one_instant_both_run(rt):
    src = (
        prelude()
        + """
seen = []
ms = [model.HCSR04(2 * k + 2, 2 * k + 3, distance=500) for k in range(2)]
for k in range(2):
    Pin(2 * k + 3, Pin.IN).irq(lambda p: seen.append((p.id, clock.ticks_us())))
ts = [Pin(2, Pin.OUT), Pin(4, Pin.OUT)]
for t in ts:
    t.value(1)
clock.sleep_us(10)
for t in ts:
    t.value(0)
clock.advance_to(50000)
print(seen)
"""
    )
    w = 291  # 2 * 50 mm / 343.42 mm/ms = 291.2 us
    assert rt.value(src) == [(3, 1470), (5, 1470), (3, 1470 + w), (5, 1470 + w)]


@pytest.mark.parametrize(
    "call,fragment",
    [
        ("irq(5)", "irq handler 5"),
        ("irq('go')", "irq handler 'go'"),
        ("irq(print, 0)", "irq trigger 0"),
        ("irq(print, 4)", "irq trigger 4"),
        ("irq(print, -1)", "irq trigger -1"),
        ("irq(print, True)", "irq trigger True"),
        ("irq(print, 1.0)", "irq trigger 1.0"),
        ("irq(print, None)", "irq trigger None"),
    ],
)
def test_stub_irq_bad_handler_or_trigger_is_refused_by_name(rt, call, fragment):
    src = prelude() + "p = Pin(7, Pin.IN)\ntry:\n    p.%s\nexcept ValueError as e:\n    print(repr(str(e)))\n" % call
    msg = rt.value(src)
    assert "Pin 7" in msg and fragment in msg and "allowed" in msg, msg


def c_mm_per_us(temp_centi_c):
    """Datasheet speed of sound (331.3 + 0.606 T m/s) in mm/us, float oracle."""
    return (331.3 + 0.606 * temp_centi_c / 100) / 1000


def expected(d, temp, max_range):
    """(status, 0.1 mm) a perfect driver reports for a target d (0.1 mm) the model echoes in whole us."""
    if not 200 <= d <= 40000:
        return 1, -1  # the module holds its echo 38 ms: out of range
    w = round(2 * d / 10 / c_mm_per_us(temp))
    got = w * c_mm_per_us(temp) / 2 * 10
    if got > max_range + 0.5:
        return 1, -1
    if got < 200 - 0.5:
        return 4, -1  # too close: 2 cm itself echoes 116 us = 19.92 mm at 20 degC
    return 0, got


@pytest.mark.parametrize("temp", [-1000, 2000, 4500])
def test_irq_distances_match_the_datasheet_and_the_blocking_path(rt, temp):
    # 2 cm and 4 m are the module's range ends; 10 m and 1 cm are outside it.
    targets = [100, 199, 200, 201, 205, 1000, 5000, 9999, 10000, 25000, 39990, 40000, 40001, 100000]
    src = (
        prelude()
        + """
out = []
m = model.HCSR04(2, 3, temp_centi_c=%d)
irq = drv.HCSR04(Pin(2, Pin.OUT), Pin(3, Pin.IN), clock, max_range=40000, temp_centi_c=%d, samples=1, irq=True)
for d in %r:
    m.set_distance(d)
    clock.sleep_ms(100)
    a = irq.fire()
    clock.sleep_ms(60)
    dist, st = [7], [7]
    b = irq.collect_into(dist, st, 0)
    out.append((a, b, dist[0], st[0]))
print(out)
"""
        % (temp, temp, targets)
    )
    blocking = (
        src.replace("irq=True", "irq=False")
        .replace("a = irq.fire()", "a = 6")
        .replace("b = irq.collect_into(dist, st, 0)", "b = irq.measure_into(dist, st, 0)")
    )
    got, got_blocking = rt.value(src), rt.value(blocking)
    assert got == got_blocking  # the IRQ's timestamps judge every echo as time_pulse_us does
    for d, (fired, st, dist, st_buf) in zip(targets, got, strict=True):
        want_st, want_d = expected(d, temp, 40000)
        assert fired == 6 and st == st_buf == want_st, (d, st)
        if st == 0:
            assert abs(dist - want_d) <= 0.5 + 0.2, (d, dist, want_d)  # rounding + the 2**14 scale
        else:
            assert dist == -1


def test_timeouts_to_the_microsecond_and_faults(rt):
    src = (
        prelude(0)
        + """
m = model.HCSR04(2, 3, distance=3000)
s = drv.HCSR04(Pin(2, Pin.OUT), Pin(3, Pin.IN), clock, max_range=10000, samples=1, irq=True)
to = s.timeout_us
out = [to]


def at(t_after_fire):
    # result() at fire + t_after_fire us
    clock.advance_to(t0 + t_after_fire)
    return s.result()


# missing echo: PENDING until the rise timeout, NO_ECHO at it
m.missing_echo = True
clock.advance_to(100000); s.fire(); t0 = clock.now_us()
out.append((at(to - 1), at(to)))
s.collect_into([0], [0], 0)
m.missing_echo = False
# 1 cm: the module holds its echo 38 ms from 460 us: OUT_OF_RANGE once the echo outlasts the timeout
m.set_distance(100)
clock.advance_to(200000); s.fire(); t0 = clock.now_us()
out.append((at(460 + to - 1), at(460 + to)))
s.collect_into([0], [0], 0)
# stuck high: STUCK at fire, nothing triggered
m.stuck_high = True
clock.advance_to(300000); pings = m.pings
out.append((s.fire(), s.result(), m.pings - pings))
s.collect_into([0], [0], 0)
m.stuck_high = False
# unplugged: the line floats low, no edge: NO_ECHO
pins.disconnect(3); pins.disconnect(2)
clock.advance_to(400000); s.fire(); t0 = clock.now_us()
out.append(at(to))
s.collect_into([0], [0], 0)
pins.connect(2, m); pins.connect(3, m)
# a good echo, then again within 60 ms of it: WAIT, buffers untouched
m.set_distance(3000)
clock.advance_to(500000); s.fire(); clock.advance_to(510000)
d, st = [5], [5]
out.append((s.collect_into(d, st, 0), d[0], st[0]))
out.append((s.fire(), s.collect_into(d, st, 0), d[0], st[0]))
# collected early: it waits for the echo, then reports it once
clock.advance_to(600000); s.fire(); t1 = clock.now_us()
out.append((s.collect_into(d, st, 0), d[0], st[0], clock.now_us() - t1 < 460 + 1748 + 100, s.result()))
print(out)
"""
    )
    to, missing, held, stuck, unplugged, ok, wait, early = rt.value(src)
    # 1 m at 20 degC: 5824 us round trip (rounded up), + 1/16, + 1000 us for the burst
    assert to == 5824 + 5824 // 16 + 1000
    assert missing == (6, 2)  # PENDING, then NO_ECHO
    assert held == (6, 1)  # PENDING, then OUT_OF_RANGE
    assert stuck == (3, 3, 0)  # STUCK, reported, no ping
    assert unplugged == 2
    assert ok[0] == 0 and abs(ok[1] - 3000) <= 2 and ok[2] == 0
    assert wait == (5, 5, ok[1], 0)  # fired again within 60 ms: WAIT, buffers as the last ping left them
    assert early[0] == 0 and abs(early[1] - 3000) <= 2 and early[3] and early[4] == 5  # then WAIT


def test_runner_wait_holds_the_20_ms_grid_to_the_us(rt):
    # Steps that take 3.456, 19.999, 23 (an overrun), 5, 45 (far behind) and 1 ms; hand-worked starts.
    src = """
import _stub_clock as clock
import _stub_pins
import _stub_i2c
_stub_pins.reset()
_stub_i2c.reset()
clock.reset(777)
import runner


class Stub(runner.Runner):
    def __init__(self):
        self.clock = clock
        self.next_us = clock.ticks_us()


r = Stub()
starts = []
for busy in (3456, 19999, 23000, 5000, 45000, 1000):
    starts.append(clock.now_us() - 777)
    clock.sleep_us(busy)
    r.wait()
starts.append(clock.now_us() - 777)
print(starts)
"""
    assert rt.value(src) == [0, 20000, 40000, 63000, 80000, 125000, 145000]


def test_a_port_without_pin_irq_falls_back_to_time_pulse_us(rt):
    src = (
        prelude()
        + """
class OldPin:
    # a port's Pin without irq(): value() only
    def __init__(self, pin):
        self._pin = pin

    def value(self, v=None):
        return self._pin.value(v)


m = model.HCSR04(2, 3, distance=2500)
def old_pulse(pin, level, timeout_us):
    return time_pulse_us(pin._pin, level, timeout_us)


s = drv.HCSR04(Pin(2, Pin.OUT), OldPin(Pin(3, Pin.IN)), clock, old_pulse, samples=1, irq=True)
rr = drv.RoundRobin([s], neighbours=())
d, st = [0], [0]
t0 = clock.now_us()
i = rr.tick(d, st)
print((s.split, rr.split, i, st[0], d[0], clock.now_us() - t0 > 460))
"""
    )
    split, rr_split, i, st, d, blocked = rt.value(src)
    assert (split, rr_split, i, st, blocked) == (False, False, 0, 0, True)  # same tick, blocking
    assert abs(d - 2500) <= 2


def test_main_build_times_the_echo_by_irq(rt):
    src = """
import _stub_clock as clock
import _stub_pins
import _stub_i2c
import hcsr04_model
from _stub_i2c import shared_bus
from pca9685_model import PCA9685Model
from hexapod import board as boards
import main
clock.reset(0)
_stub_pins.reset()
_stub_i2c.reset()
bus = shared_bus(0)
b = boards.load("pico")
for c in b["pca9685"]["chips"]:
    bus.attach(PCA9685Model(c["address"], osc_hz=c["osc_hz"]))
sonars = [hcsr04_model.HCSR04(t, e, distance=3000 + 1000 * k) for k, (t, e) in enumerate(boards.sonar_pins(b))]
r = main.build(clock=clock)
blocked = 0
for n in range(12):
    t0 = clock.now_us()
    r.step()
    blocked = max(blocked, clock.now_us() - t0)
    r.wait()
print((r.sonars.ring.split, blocked, r.distances))
"""
    split, blocked, dist = rt.value(src, heapsize="4m")
    assert split is True
    assert blocked <= 2 + 10 + 600  # the trigger and the driver's start-up sleeps, never an echo
    assert [abs(d - (3000 + 1000 * k)) <= 2 for k, d in enumerate(dist)] == [True] * 5
