"""HC-SR04: the model (host/stubs hcsr04_model) on stub pins, and drivers.hcsr04 against it."""

import _stub_clock as clock
import _stub_pins as pins
import hcsr04_model as model
from machine import Pin, time_pulse_us

from drivers import hcsr04 as drv


class Rig:
    """Five models (trigger 10 + 2k, echo 11 + 2k, 1000 + 500k 0.1 mm away), neighbours linked, a
    driver on each; the clock at start (virtual us)."""

    def __init__(self, start=0, temp=2000, max_range=10000, samples=5, irq=False):
        clock.reset(start)
        pins.reset()
        self.models = []
        self.sensors = []
        for k in range(5):
            self.models.append(model.HCSR04(10 + 2 * k, 11 + 2 * k, distance=1000 + 500 * k, temp_centi_c=temp))
            self.sensors.append(
                drv.HCSR04(
                    Pin(10 + 2 * k, Pin.OUT),
                    Pin(11 + 2 * k, Pin.IN),
                    clock,
                    time_pulse_us,
                    max_range=max_range,
                    temp_centi_c=temp,
                    samples=samples,
                    irq=irq,
                )
            )
        for a, b in drv.NEIGHBOURS:
            model.link(self.models[a], self.models[b])
        self.dist = [0] * 5
        self.status = [0] * 5

    def run(self, rr, ticks):
        """The control loop: one rr.tick per 20 ms; the longest any tick blocked (virtual us)."""
        worst = 0
        for _ in range(ticks):
            t0 = clock.now_us()
            rr.tick(self.dist, self.status)
            if clock.now_us() - t0 > worst:
                worst = clock.now_us() - t0
            clock.advance_to(t0 + 20000)
        return worst

    def flags(self):
        out = {}
        for m in self.models:
            for k in m.flags:
                out[k] = out.get(k, 0) + m.flags[k]
        return out


def _fixed_echo(width, max_range=40000):
    """A driver on pins 30/31 whose time_pulse_us returns width[0]."""
    return drv.HCSR04(
        Pin(30, Pin.OUT), Pin(31, Pin.IN), clock, lambda pin, level, timeout: width[0], max_range=max_range
    )


# -- the driver -----------------------------------------------------------------------------


def single_pings(temp, distances):
    """[(ping status, distance)] of sensor 0 with its model set at each distance, 60 ms apart."""
    rig = Rig(temp=temp, max_range=40000)
    s = rig.sensors[0]
    out = []
    for d in distances:
        rig.models[0].set_distance(d)
        clock.sleep_ms(60)
        out.append((s.ping(), s.distance))
    return out


def echo_distances(widths):
    """[(temperature, echo width, status, distance)] of a driver fed each width at each temperature."""
    Rig(max_range=40000)
    w = [0]
    s = _fixed_echo(w)
    out = []
    for t in (-4000, 0, 2000, 6000):
        s.set_temperature(t)
        for x in widths:
            w[0] = x
            clock.sleep_ms(60)
            out.append((t, x, s.ping(), s.distance))
    return out


def largest_intermediate():
    """The largest timeout * k + rounding the driver computes over -40..60 degC at a 4 m range."""
    Rig()
    worst = 0
    for t in range(-4000, 6001, 250):
        s = drv.HCSR04(Pin(30, Pin.OUT), Pin(31, Pin.IN), clock, time_pulse_us, max_range=40000, temp_centi_c=t)
        worst = max(worst, s.timeout_us * s._k + 16384)
    return worst


def timeouts(ranges):
    """[(max range, timeout us, max block us)] of a driver at each max range."""
    Rig()
    out = []
    for r in ranges:
        s = drv.HCSR04(Pin(30, Pin.OUT), Pin(31, Pin.IN), clock, time_pulse_us, max_range=r)
        out.append((r, s.timeout_us, s.max_block_us))
    return out


def measure_codes(widths):
    """[(measure_into's code, distance slot, status slot)] of a 1 m driver fed each echo width."""
    Rig()
    w = [0]
    s = _fixed_echo(w, max_range=10000)
    d = [7]
    st = [7]
    out = []
    for x in widths:
        w[0] = x
        clock.sleep_ms(60)
        out.append((s.measure_into(d, st, 0), d[0], st[0]))
    return out


def stuck_echo():
    """(ping status, us it blocked, model pings) with sensor 0's echo stuck high."""
    rig = Rig()
    rig.models[0].stuck_high = True
    t0 = clock.now_us()
    st = rig.sensors[0].ping()
    return (st, clock.now_us() - t0, rig.models[0].pings)


def ping_guard(start):
    """[first code, (code, distance, status) 20 ms later, ping at 59.999 ms, ping at 60 ms, model pings]."""
    rig = Rig(start=start)
    s = rig.sensors[0]
    d = [5]
    st = [6]
    t0 = clock.now_us()
    out = [s.measure_into(d, st, 0)]
    for dt in (20000, 59999, 60000):
        clock.advance_to(t0 + dt)
        if dt == 20000:
            out.append((s.measure_into(d, st, 0), d[0], st[0]))
        else:
            out.append(s.ping())
    out.append(rig.models[0].pings)
    return out


def median_rows(distances, samples):
    """[(code, status, distance slot, this ping's own distance or -1)] a ping per distance (-1: no echo)."""
    rig = Rig(samples=samples)
    s = rig.sensors[0]
    m = rig.models[0]
    d = [0]
    st = [0]
    out = []
    for x in distances:
        m.missing_echo = x < 0
        if x >= 0:
            m.set_distance(x)
        clock.sleep_ms(60)
        r = s.measure_into(d, st, 0)
        out.append((r, st[0], d[0], s.distance if r == 0 else -1))
    return out


def plan(n, tick_ms, neighbours, cycle_ms, crosstalk_ms):
    """drv.plan's slots."""
    return drv.plan(n, tick_ms, neighbours, cycle_ms, crosstalk_ms)


def five_in_the_loop(start, irq):
    """(slots, distances, statuses, model flags, pings per model, worst block, max block) of 100 ticks."""
    rig = Rig(start=start, irq=irq)
    rr = drv.RoundRobin(rig.sensors)
    worst = rig.run(rr, 100)
    return (rr.slots, rig.dist, rig.status, rig.flags(), [m.pings for m in rig.models], worst, rr.max_block_us)


def naive_order():
    """(slots, crosstalk flags) of a round robin told neighbours need no gap."""
    rig = Rig()
    rr = drv.RoundRobin(rig.sensors, crosstalk_ms=0)
    rig.run(rr, 50)
    return (rr.slots, rig.flags()["crosstalk"])


def faults_in_the_loop(irq):
    """((distances, statuses) with five faults, worst block then, worst block healed, max block,
    distances, statuses and model flags after the faults are gone)."""
    rig = Rig(irq=irq)
    models = rig.models
    rr = drv.RoundRobin(rig.sensors)
    rig.run(rr, 10)
    models[0].stuck_high = True  # front
    models[1].missing_echo = True  # left_front
    models[2].set_distance(30000)  # left_rear: 3 m, past the 1 m max range
    models[3].set_distance(100)  # right_front: 1 cm, the module holds echo 38 ms
    pins.disconnect(19)  # right_rear unplugged
    pins.disconnect(18)
    w1 = rig.run(rr, 25)
    faulty = (list(rig.dist), list(rig.status))
    models[0].stuck_high = False
    models[1].missing_echo = False
    models[2].set_distance(3000)
    models[3].set_distance(4000)
    pins.connect(18, models[4])
    pins.connect(19, models[4])
    w2 = rig.run(rr, 10)
    return (faulty, w1, w2, rr.max_block_us, list(rig.dist), list(rig.status), rig.flags())


class _ShortSleeps:
    """A board whose sleep_us undershoots by 3 us."""

    def ticks_us(self):
        return clock.ticks_us()

    def ticks_diff(self, a, b):
        return clock.ticks_diff(a, b)

    def sleep_us(self, us):
        clock.sleep_us(us - 3)


def short_trigger():
    """(code, distance slot, status slot, short_trigger flags, model pings, blocked within max_block_us)."""
    rig = Rig()
    s = drv.HCSR04(Pin(10, Pin.OUT), Pin(11, Pin.IN), _ShortSleeps(), time_pulse_us)
    d = [1]
    st = [1]
    t0 = clock.now_us()
    r = s.measure_into(d, st, 0)
    m = rig.models[0]
    return (r, d[0], st[0], m.flags["short_trigger"], m.pings, clock.now_us() - t0 <= s.max_block_us)


def tick_heap(irq):
    """MicroPython only (gc.mem_alloc): (heap bytes of 100 round-robin ticks with three sensors
    faulty, their statuses)."""
    import gc

    rig = Rig(irq=irq)
    rr = drv.RoundRobin(rig.sensors)
    rig.models[1].missing_echo = True
    rig.models[2].stuck_high = True
    rig.models[3].set_distance(30000)
    rig.run(rr, 20)
    dist = rig.dist
    status = rig.status
    gc.collect()
    gc.disable()
    before = gc.mem_alloc()
    for _ in range(100):
        t0 = clock.now_us()
        rr.tick(dist, status)
        clock.advance_to(t0 + 20000)
    used = gc.mem_alloc() - before
    gc.enable()
    return (used, status)


def bad_sensor(kwargs):
    """The ValueError text of drv.HCSR04(..., **kwargs), or "accepted"."""
    Rig()
    try:
        drv.HCSR04(Pin(30, Pin.OUT), Pin(31, Pin.IN), clock, time_pulse_us, **kwargs)
        return "accepted"
    except ValueError as e:
        return str(e)


def bad_round_robin(sensors, kwargs):
    """The ValueError text of drv.RoundRobin(the sensors, **kwargs), or "accepted". sensors: "five"
    (the rig's), "none" or "one_far" (one 4 m sensor)."""
    rig = Rig()
    if sensors == "five":
        chosen = rig.sensors
    elif sensors == "none":
        chosen = []
    else:
        chosen = [drv.HCSR04(Pin(30, Pin.OUT), Pin(31, Pin.IN), clock, time_pulse_us, max_range=40000)]
    try:
        drv.RoundRobin(chosen, **kwargs)
        return "accepted"
    except ValueError as e:
        return str(e)


# -- the model alone -------------------------------------------------------------------------


class Model:
    """One model on trigger 2 / echo 3 at distance (0.1 mm) and temp (0.01 degC), the clock at 0."""

    def __init__(self, distance=10000, temp=2000):
        clock.reset(0)
        pins.reset()
        self.trig = Pin(2, Pin.OUT, value=0)
        self.echo = Pin(3, Pin.IN)
        self.m = model.HCSR04(2, 3, distance=distance, temp_centi_c=temp)

    def pulse(self, trig, width_us=10):
        trig.value(1)
        clock.sleep_us(width_us)
        trig.value(0)

    def fire(self, width_us=10):
        """A trigger of width_us: (echo width or time_pulse_us's error, us waited from the trigger's end)."""
        self.pulse(self.trig, width_us)
        t0 = clock.now_us()
        w = time_pulse_us(self.echo, 1, 100000)
        return (w, clock.now_us() - t0)


def model_fire(distance, temp):
    """fire() once at distance and temperature."""
    return Model(distance, temp).fire()


def model_round_trips(distances, temp):
    """model.round_trip_us of each distance."""
    return [model.round_trip_us(d, temp) for d in distances]


def model_out_of_range():
    """Two fires: at 4.0001 m, then (60 ms later) at 19.9 mm."""
    r = Model(40001)
    out = [r.fire()]
    clock.sleep_ms(60)
    r.m.set_distance(199)
    out.append(r.fire())
    return out


def model_short_trigger():
    """[fire(9), short_trigger flags, pings, then 60 ms later fire(10)'s width, flags, pings]."""
    r = Model()
    m = r.m
    out = [r.fire(9), m.flags["short_trigger"], m.pings]
    clock.sleep_ms(60)
    out += [r.fire(10)[0], m.flags["short_trigger"], m.pings]
    return out


def model_ping_interval():
    """(ping_interval flags after a ping 59.999 ms after the last, after one 60 ms after, pings)."""
    r = Model()
    m = r.m
    r.fire()
    clock.advance_to(m.last_ping_us + 59999 - 10)  # the ping starts at the trigger's falling edge
    r.fire()
    a = m.flags["ping_interval"]
    clock.advance_to(m.last_ping_us + 60000 - 10)
    r.fire()
    return (a, m.flags["ping_interval"], m.pings)


def model_trigger_during_echo():
    """(echo level 1 ms into an echo, busy flags after a trigger then, pings)."""
    r = Model()
    r.pulse(r.trig)
    clock.sleep_us(1000)
    level = r.echo.value()
    r.pulse(r.trig)
    return (level, r.m.flags["busy"], r.m.pings)


def model_crosstalk():
    """((crosstalk of m, b) after b fires 20 ms after m, (m, b, unlinked c) after m fires 38 ms later)."""
    r = Model()
    m = r.m
    trig_b = Pin(4, Pin.OUT, value=0)
    b = model.HCSR04(4, 5)
    c = model.HCSR04(6, 7)
    model.link(m, b)
    r.fire()
    t = m.last_ping_us
    clock.advance_to(t + 20000)
    r.pulse(trig_b)
    first = (m.flags["crosstalk"], b.flags["crosstalk"])
    clock.advance_to(t + 20000 + 38000)
    r.fire()
    return (first, (m.flags["crosstalk"], b.flags["crosstalk"], c.flags["crosstalk"]))


def model_stuck_and_missing():
    """[(echo level, fire()) stuck high, (echo level, fire()) missing echo, the healed fire's width]."""
    r = Model()
    m = r.m
    out = []
    m.stuck_high = True
    out.append((r.echo.value(), r.fire()))
    m.stuck_high = False
    m.missing_echo = True
    clock.sleep_ms(100)
    out.append((r.echo.value(), r.fire()))
    m.missing_echo = False
    clock.sleep_ms(100)
    out.append(r.fire()[0])
    return out
