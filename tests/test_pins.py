"""Stub pins: shared wires, pulls, models driving inputs, time_pulse_us as MicroPython's. Both runtimes."""

PRELUDE = """
import _stub_clock as clock
import _stub_pins as pins
import machine
from machine import Pin
clock.reset(1000)
pins.reset()


class Pulse:
    # drives `pin_id` high during [rise, fall) of unwrapped virtual us
    def __init__(self, pin_id, rise, fall):
        self.pin_id, self.rise, self.fall = pin_id, rise, fall
        self.writes = []
        pins.connect(pin_id, self)

    def pin_written(self, pin_id, level):
        self.writes.append((pin_id, level, clock.now_us()))

    def level(self, pin_id, t):
        return 1 if self.rise <= t < self.fall else 0

    def next_change(self, pin_id, t):
        if t < self.rise:
            return self.rise
        if t < self.fall:
            return self.fall
        return -1
"""


def test_pins_with_one_id_share_a_wire_and_outputs_reach_the_model(rt):
    src = (
        PRELUDE
        + """
m = Pulse(3, 10**9, 10**9)
a = Pin(3, Pin.OUT)
b = Pin(3)
a.value(1)
r1 = b.value()
a.off()
r2 = b()
a.on()
a.toggle()
clock.sleep_us(7)
a(True)
print((r1, r2, b.value(), m.writes, repr(a), a.id))
"""
    )
    assert rt.value(src) == (
        1,
        0,
        1,
        [(3, 1, 1000), (3, 0, 1000), (3, 1, 1000), (3, 0, 1000), (3, 1, 1007)],
        "Pin(3)",
        3,
    )


def test_inputs_read_force_then_model_then_pull(rt):
    src = (
        PRELUDE
        + """
out = []
up = Pin(4, Pin.IN, Pin.PULL_UP)
down = Pin(5, Pin.IN, Pin.PULL_DOWN)
out.append((up.value(), down.value()))
Pulse(5, 1100, 1200)
clock.advance_to(1150)
out.append(down.value())
pins.force(5, 0)
out.append(down.value())
pins.force(5, -1)
pins.disconnect(5)
out.append(down.value())
up.init(pull=None)
out.append(up.value())
print(out)
"""
    )
    assert rt.value(src) == [(1, 0), 1, 0, 0, 0]


def test_bad_mode_or_pull_is_refused_with_the_pin_named(rt):
    src = (
        PRELUDE
        + """
out = []
for mode, pull in ((7, -1), (Pin.IN, 9)):
    try:
        Pin("GP7", mode, pull)
        out.append("accepted")
    except ValueError as e:
        out.append(str(e))
print(out)
"""
    )
    out = rt.value(src)
    assert "'GP7'" in out[0] and "mode 7" in out[0]
    assert "pull 9" in out[1]


def test_time_pulse_us_measures_and_advances_the_clock(rt):
    src = (
        PRELUDE
        + """
e = Pin(6, Pin.IN)
Pulse(6, 1300, 1800)
w = machine.time_pulse_us(e, 1, 10000)
print((w, clock.now_us()))
"""
    )
    assert rt.value(src) == (500, 1800)


def test_time_pulse_us_timeouts_are_minus_two_and_minus_one(rt):
    # -2: the pulse never starts within timeout; -1: it lasts >= timeout (MicroPython's >= test)
    src = (
        PRELUDE
        + """
out = []
e = Pin(6, Pin.IN)
m = Pulse(6, 5000, 5400)
t0 = clock.now_us(); out.append((machine.time_pulse_us(e, 1, 1000), clock.now_us() - t0))
t0 = clock.now_us(); out.append((machine.time_pulse_us(e, 1, 3500), clock.now_us() - t0))
m.rise, m.fall = clock.now_us() + 100, clock.now_us() + 100 + 700
t0 = clock.now_us(); out.append((machine.time_pulse_us(e, 1, 700), clock.now_us() - t0))
m.rise, m.fall = clock.now_us() - 50, clock.now_us() + 300
t0 = clock.now_us(); out.append((machine.time_pulse_us(e, 1, 1000), clock.now_us() - t0))
t0 = clock.now_us(); out.append((machine.time_pulse_us(Pin(8, Pin.IN), 0, 1000), clock.now_us() - t0))
print(out)
"""
    )
    assert rt.value(src) == [
        (-2, 1000),  # rise at 5000 is 4000 us away
        (400, 3400),  # waited 3000 for the rise, then timed 400
        (-1, 800),  # 100 us wait, then 700 us high hits the 700 us limit
        (300, 300),  # already high: timing starts at once, the pulse's past does not count
        (-1, 1000),  # undriven line sits low for ever: no end to a low pulse
    ]


def test_wdt_freq_reset_cause_unique_id(rt):
    src = (
        PRELUDE
        + """
out = []
w = machine.WDT(timeout=100)
clock.sleep_ms(100)
out.append(w.expired())
w.feed()
clock.sleep_ms(101)
out.append(w.expired())
for bad in (0, 100000, 1.5):
    try:
        machine.WDT(timeout=bad)
        out.append("accepted")
    except ValueError as e:
        out.append("WDT timeout" in str(e))
machine.freq(200000000)
out.append(machine.freq())
try:
    machine.freq(5)
except ValueError:
    out.append(machine.freq())
out.append(machine.reset_cause() == machine.PWRON_RESET)
pins.set_reset_cause(machine.WDT_RESET)
out.append(machine.reset_cause() == machine.WDT_RESET)
u = machine.unique_id()
out.append((type(u) is bytes, len(u)))
print(out)
"""
    )
    assert rt.value(src) == [False, True, True, True, True, 200000000, 200000000, True, True, (True, 8)]


def test_a_second_model_on_one_pin_is_refused(rt):
    src = (
        PRELUDE
        + """
Pulse(9, 0, 0)
try:
    Pulse(9, 0, 0)
    print("accepted")
except ValueError as e:
    print(repr(str(e)))
"""
    )
    assert "pin 9 is already connected" in rt.value(src)
