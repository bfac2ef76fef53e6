"""The stub pins (host/stubs _stub_pins, machine.Pin): shared wires, pulls, models, time_pulse_us, and
the rest of the stub machine (WDT, freq, reset_cause, unique_id)."""

import _stub_clock as clock
import _stub_pins as pins
import machine
from machine import Pin


def _reset():
    clock.reset(1000)
    pins.reset()


class Pulse:
    """A model driving pin_id high during [rise, fall) of unwrapped virtual us; it records writes."""

    def __init__(self, pin_id, rise, fall):
        self.pin_id = pin_id
        self.rise = rise
        self.fall = fall
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


def shared_wire():
    """(b after a.value(1), b() after a.off(), b at the end, the model's writes, repr(a), a.id): a and b
    are both pin 3."""
    _reset()
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
    return (r1, r2, b.value(), m.writes, repr(a), a.id)


def input_levels():
    """[(pull-up, pull-down) idle, driven by a model, forced low, model gone, pull removed]."""
    _reset()
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
    return out


def bad_mode_and_pull():
    """The ValueError texts of Pin("GP7", 7, -1) and Pin("GP7", Pin.IN, 9) ("accepted" if none)."""
    _reset()
    out = []
    for mode, pull in ((7, -1), (Pin.IN, 9)):
        try:
            Pin("GP7", mode, pull)
            out.append("accepted")
        except ValueError as e:
            out.append(str(e))
    return out


def pulse_width():
    """(time_pulse_us of a 1300..1800 us pulse on pin 6 from 1000 us, the clock after)."""
    _reset()
    e = Pin(6, Pin.IN)
    Pulse(6, 1300, 1800)
    w = machine.time_pulse_us(e, 1, 10000)
    return (w, clock.now_us())


def _timed(out, pin, level, timeout):
    t0 = clock.now_us()
    out.append((machine.time_pulse_us(pin, level, timeout), clock.now_us() - t0))


def pulse_timeouts():
    """[(time_pulse_us, us it took)]: a rise 4000 us away, the same with 3500 us to wait, a 700 us pulse
    timed to 700 us, a pulse already high, a low pulse on an undriven line."""
    _reset()
    out = []
    e = Pin(6, Pin.IN)
    m = Pulse(6, 5000, 5400)
    _timed(out, e, 1, 1000)
    _timed(out, e, 1, 3500)
    m.rise, m.fall = clock.now_us() + 100, clock.now_us() + 100 + 700
    _timed(out, e, 1, 700)
    m.rise, m.fall = clock.now_us() - 50, clock.now_us() + 300
    _timed(out, e, 1, 1000)
    _timed(out, Pin(8, Pin.IN), 0, 1000)
    return out


def machine_extras():
    """WDT expiry and its bad timeouts, freq set and refused, reset_cause, unique_id: the list test_pins checks."""
    _reset()
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
    return out


def second_model():
    """The ValueError text of connecting a second model to pin 9, or "accepted"."""
    _reset()
    Pulse(9, 0, 0)
    try:
        Pulse(9, 0, 0)
        return "accepted"
    except ValueError as e:
        return str(e)
