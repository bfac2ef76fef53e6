"""The echo timed by pin IRQs: the stub Pin.irq on the virtual clock, and drivers.hcsr04 with irq=True."""

import _stub_clock as clock
import _stub_pins as pins
import hcsr04_model as model
from machine import Pin, time_pulse_us
from scenarios.refusal import message

from drivers import hcsr04 as drv


def _reset(start=1000):
    clock.reset(start)
    pins.reset()


def _ping(trigger):
    trigger.value(1)
    clock.sleep_us(10)
    trigger.value(0)


def edges_in_time_order():
    """(seen, now): two models 100 mm away, handlers on both edges of one and the falling one of the other."""
    _reset()
    seen = []
    model.HCSR04(2, 3, distance=1000)
    model.HCSR04(4, 5, distance=1000)
    Pin(3, Pin.IN).irq(lambda p: seen.append(("a", p.value(), clock.ticks_us())), Pin.IRQ_RISING | Pin.IRQ_FALLING)
    Pin(5, Pin.IN).irq(lambda p: seen.append(("b", p.value(), clock.ticks_us())), Pin.IRQ_FALLING, hard=True)
    ta, tb = Pin(2, Pin.OUT), Pin(4, Pin.OUT)
    for t in (ta, tb):
        _ping(t)  # triggers fall at 1010 and 1020
    clock.sleep_us(100000)
    now = clock.now_us()
    Pin(3).irq(None)
    _ping(ta)
    clock.sleep_ms(70)
    return (seen, now)


def forced_or_unplugged():
    """(level, us) the handler saw as a stuck module is unplugged, the line forced, plugged back."""
    _reset()
    seen = []
    m = model.HCSR04(2, 3, distance=1000)
    m.stuck_high = True
    Pin(3, Pin.IN).irq(lambda q: seen.append((q.value(), clock.ticks_us())))
    clock.sleep_us(5)
    pins.disconnect(3)  # the stuck module unplugged: the line falls to its pull (none: low)
    clock.sleep_us(5)
    pins.force(3, 1)
    pins.force(3, 1)  # no change, no edge
    clock.sleep_us(5)
    pins.force(3, -1)
    clock.sleep_us(5)
    pins.connect(3, m)  # plugged back in, still stuck high
    return seen


def edges_at_one_instant():
    """(pin, us) of two models 50 mm away triggered together."""
    _reset()
    seen = []
    for k in range(2):
        model.HCSR04(2 * k + 2, 2 * k + 3, distance=500)
        Pin(2 * k + 3, Pin.IN).irq(lambda p: seen.append((p.id, clock.ticks_us())))
    ts = [Pin(2, Pin.OUT), Pin(4, Pin.OUT)]
    for t in ts:
        t.value(1)
    clock.sleep_us(10)
    for t in ts:
        t.value(0)
    clock.advance_to(50000)
    return seen


def bad_irq(args):
    """The message Pin(7).irq(*args) is refused with ("print" stands for a callable)."""
    _reset()
    return message(Pin(7, Pin.IN).irq, *[print if a == "print" else a for a in args])


def distances(temp, targets, irq):
    """(fired, status, distance, status in the buffer) of one ping at each target (0.1 mm)."""
    _reset()
    out = []
    m = model.HCSR04(2, 3, temp_centi_c=temp)
    s = drv.HCSR04(Pin(2, Pin.OUT), Pin(3, Pin.IN), clock, max_range=40000, temp_centi_c=temp, samples=1, irq=irq)
    for d in targets:
        m.set_distance(d)
        clock.sleep_ms(100)
        a = s.fire() if irq else 6
        clock.sleep_ms(60)
        dist, st = [7], [7]
        b = s.collect_into(dist, st, 0) if irq else s.measure_into(dist, st, 0)
        out.append((a, b, dist[0], st[0]))
    return out


def timeouts_and_faults():
    """[timeout_us, missing, held, stuck, unplugged, ok, wait, early]: see the test."""
    _reset(0)
    m = model.HCSR04(2, 3, distance=3000)
    s = drv.HCSR04(Pin(2, Pin.OUT), Pin(3, Pin.IN), clock, max_range=10000, samples=1, irq=True)
    to = s.timeout_us
    out = [to]
    t0 = [0]

    def fire_at(t):
        clock.advance_to(t)
        s.fire()
        t0[0] = clock.now_us()

    def at(t_after_fire):
        # result() at fire + t_after_fire us
        clock.advance_to(t0[0] + t_after_fire)
        return s.result()

    # missing echo: PENDING until the rise timeout, NO_ECHO at it
    m.missing_echo = True
    fire_at(100000)
    out.append((at(to - 1), at(to)))
    s.collect_into([0], [0], 0)
    m.missing_echo = False
    # 1 cm: the module holds its echo 38 ms from 460 us: OUT_OF_RANGE once the echo outlasts the timeout
    m.set_distance(100)
    fire_at(200000)
    out.append((at(460 + to - 1), at(460 + to)))
    s.collect_into([0], [0], 0)
    # stuck high: STUCK at fire, nothing triggered
    m.stuck_high = True
    clock.advance_to(300000)
    pings = m.pings
    out.append((s.fire(), s.result(), m.pings - pings))
    s.collect_into([0], [0], 0)
    m.stuck_high = False
    # unplugged: the line floats low, no edge: NO_ECHO
    pins.disconnect(3)
    pins.disconnect(2)
    fire_at(400000)
    out.append(at(to))
    s.collect_into([0], [0], 0)
    pins.connect(2, m)
    pins.connect(3, m)
    # a good echo, then again within 60 ms of it: WAIT, buffers untouched
    m.set_distance(3000)
    fire_at(500000)
    clock.advance_to(510000)
    d, st = [5], [5]
    out.append((s.collect_into(d, st, 0), d[0], st[0]))
    out.append((s.fire(), s.collect_into(d, st, 0), d[0], st[0]))
    # collected early: it waits for the echo, then reports it once
    fire_at(600000)
    t1 = t0[0]
    out.append((s.collect_into(d, st, 0), d[0], st[0], clock.now_us() - t1 < 460 + 1748 + 100, s.result()))
    return out


class _OldPin:
    """A port's Pin without irq(): value() only."""

    def __init__(self, pin):
        self._pin = pin

    def value(self, v=None):
        return self._pin.value(v)


def _old_pulse(pin, level, timeout_us):
    return time_pulse_us(pin._pin, level, timeout_us)


def without_pin_irq():
    """(split, rr split, index, status, distance, blocked past the echo) on a Pin with no irq()."""
    _reset()
    model.HCSR04(2, 3, distance=2500)
    s = drv.HCSR04(Pin(2, Pin.OUT), _OldPin(Pin(3, Pin.IN)), clock, _old_pulse, samples=1, irq=True)
    rr = drv.RoundRobin([s], neighbours=())
    d, st = [0], [0]
    t0 = clock.now_us()
    i = rr.tick(d, st)
    return (s.split, rr.split, i, st[0], d[0], clock.now_us() - t0 > 460)


def wait_grid(start, busy_us):
    """The start of each step (us from start) when steps take busy_us and Runner.wait follows each."""
    import runner

    class Waiter(runner.Runner):
        def __init__(self):
            self.clock = clock
            self.next_us = clock.ticks_us()
            self.frame_us = self.frame_us_max = 0  # as Runner.__init__
            self._frame_t0 = self.next_us

    _reset(start)
    r = Waiter()
    starts = []
    for busy in busy_us:
        starts.append(clock.now_us() - start)
        clock.sleep_us(busy)
        r.wait()
    starts.append(clock.now_us() - start)
    return starts
