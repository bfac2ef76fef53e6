"""HC-SR04 model against the datasheet: trigger, echo width with temperature, range, faults. Both runtimes."""

import pytest

PRELUDE = """
import _stub_clock as clock
import _stub_pins as pins
from machine import Pin, time_pulse_us
import hcsr04_model as model
clock.reset(0)
pins.reset()
trig = Pin(2, Pin.OUT, value=0)
echo = Pin(3, Pin.IN)
m = model.HCSR04(2, 3, distance=DIST, temp_centi_c=TEMP)


def fire(width_us=10):
    trig.value(1)
    clock.sleep_us(width_us)
    trig.value(0)
    t0 = clock.now_us()
    w = time_pulse_us(echo, 1, 100000)
    return (w, clock.now_us() - t0)
"""


def prelude(distance=10000, temp=2000):
    return PRELUDE.replace("DIST", str(distance)).replace("TEMP", str(temp))


def expected_us(distance, temp_centi_c):
    c = 331.3 + 0.606 * temp_centi_c / 100  # m/s
    return 2 * distance / 10000 / c * 1e6


@pytest.mark.parametrize(
    "distance,temp", [(200, 2000), (201, 2000), (10000, 2000), (40000, 2000), (15000, -1000), (15000, 3500)]
)
def test_echo_width_is_the_round_trip_at_the_air_temperature(rt, distance, temp):
    width, waited = rt.value(prelude(distance, temp) + "print(fire())")
    assert abs(width - expected_us(distance, temp)) <= 0.5
    assert waited == width + 460  # echo rises after the 40 kHz burst


def test_about_58_us_per_cm_at_20_degrees(rt):
    src = prelude() + "print([model.round_trip_us(d, 2000) for d in (100, 1000, 10000)])"
    assert rt.value(src) == [58, 582, 5824]


def test_out_of_range_holds_echo_high_for_38_ms(rt):
    src = (
        prelude(40001)
        + """
out = [fire()]
clock.sleep_ms(60)
m.set_distance(199)
out.append(fire())
print(out)
"""
    )
    assert [w for w, _ in rt.value(src)] == [38000, 38000]


def test_a_trigger_shorter_than_10_us_starts_nothing_and_is_flagged(rt):
    src = (
        prelude()
        + """
out = [fire(9), m.flags["short_trigger"], m.pings]
clock.sleep_ms(60)
out += [fire(10)[0], m.flags["short_trigger"], m.pings]
print(out)
"""
    )
    (w9, waited9), flagged, pings, w10, flagged_after, pings_after = rt.value(src)
    assert w9 == -2 and waited9 == 100000
    assert (flagged, pings) == (1, 0)
    assert w10 == 5824 and (flagged_after, pings_after) == (1, 1)  # counted once, the good ping accepted


def test_pings_closer_than_60_ms_are_flagged(rt):
    src = (
        prelude()
        + """
fire()
clock.advance_to(m.last_ping_us + 59999 - 10)  # the ping starts at the trigger's falling edge
fire()
a = m.flags["ping_interval"]
clock.advance_to(m.last_ping_us + 60000 - 10)
fire()
print((a, m.flags["ping_interval"], m.pings))
"""
    )
    assert rt.value(src) == (1, 1, 3)


def test_a_trigger_during_the_echo_is_ignored(rt):
    src = (
        prelude()
        + """
trig.value(1); clock.sleep_us(10); trig.value(0)
clock.sleep_us(1000)
r = echo.value()
trig.value(1); clock.sleep_us(10); trig.value(0)
print((r, m.flags["busy"], m.pings))
"""
    )
    assert rt.value(src) == (1, 1, 1)


def test_neighbours_pinged_close_together_flag_crosstalk(rt):
    src = (
        prelude()
        + """
trig_b = Pin(4, Pin.OUT, value=0)
b = model.HCSR04(4, 5)
c = model.HCSR04(6, 7)
model.link(m, b)
fire()
t = m.last_ping_us
clock.advance_to(t + 20000)
trig_b.value(1); clock.sleep_us(10); trig_b.value(0)
first = (m.flags["crosstalk"], b.flags["crosstalk"])
clock.advance_to(t + 20000 + 38000)
fire()
second = (m.flags["crosstalk"], b.flags["crosstalk"], c.flags["crosstalk"])
print((first, second))
"""
    )
    assert rt.value(src) == ((1, 1), (1, 1, 0))


def test_stuck_high_and_missing_echo_faults(rt):
    src = (
        prelude()
        + """
out = []
m.stuck_high = True
out.append((echo.value(), fire()))
m.stuck_high = False
m.missing_echo = True
clock.sleep_ms(100)
out.append((echo.value(), fire()))
m.missing_echo = False
clock.sleep_ms(100)
out.append(fire()[0])
print(out)
"""
    )
    assert rt.value(src) == [(1, (-1, 100000)), (0, (-2, 100000)), 5824]
