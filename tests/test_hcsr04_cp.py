"""CircuitPython backend on Adafruit's adafruit_hcsr04, against the same HC-SR04 model (CPython only).

adafruit_hcsr04 imports `digitalio` and, when present, `pulseio`; both are faked here on the stub
pins and the virtual clock, once with PulseIn (the hardware pulse timer) and once without (the
library's bit-bang loop on time.monotonic). Every poll of a loop costs POLL_US of virtual time.
"""

import importlib
import sys
import types

import _stub_clock as clock
import _stub_pins as pins
import hcsr04_model as model
import pytest
from machine import Pin, time_pulse_us

from drivers import hcsr04 as mp_driver

POLL_US = 10  # one pass of a CircuitPython polling loop, roughly


class FakeTime:
    """What adafruit_hcsr04 sees as `time`: every monotonic() read is a poll."""

    @staticmethod
    def monotonic():
        clock.advance_us(POLL_US)
        return clock.now_us() / 1e6

    @staticmethod
    def sleep(seconds):
        clock.sleep(seconds)


class Direction:
    INPUT = "input"
    OUTPUT = "output"


class DigitalInOut:
    def __init__(self, pin):
        self._pin = Pin(pin, Pin.IN)
        self.pin_id = pin

    @property
    def direction(self):
        return Direction.OUTPUT if self._pin._w.mode == Pin.OUT else Direction.INPUT

    @direction.setter
    def direction(self, d):
        self._pin.init(Pin.OUT if d == Direction.OUTPUT else Pin.IN)

    @property
    def value(self):
        return bool(self._pin.value())

    @value.setter
    def value(self, v):
        self._pin.value(1 if v else 0)

    def deinit(self):
        pass


class PulseIn:
    """Records the first complete high pulse after resume(), as CircuitPython's PulseIn does."""

    def __init__(self, pin, maxlen=2, idle_state=False):
        self.pin_id = pin
        Pin(pin, Pin.IN)
        self._rise = self._fall = -1
        self.paused = False

    def clear(self):
        self._rise = self._fall = -1

    def pause(self):
        self.paused = True

    def resume(self):
        self.paused = False
        now = clock.now_us()
        start = now if pins.level(self.pin_id) == 0 else pins.next_edge(self.pin_id, now)
        self._rise = pins.next_edge(self.pin_id, start) if start >= 0 else -1
        self._fall = pins.next_edge(self.pin_id, self._rise) if self._rise >= 0 else -1

    def __len__(self):
        clock.advance_us(POLL_US)
        return 1 if 0 <= self._fall <= clock.now_us() else 0

    def __getitem__(self, i):
        if i != 0 or len(self) == 0:
            raise IndexError("PulseIn index out of range")
        return min(self._fall - self._rise, 65535)

    def deinit(self):
        pass


@pytest.fixture(params=["pulseio", "bitbang"])
def cp(request, monkeypatch):
    """drivers.cp_hcsr04 freshly imported on top of adafruit_hcsr04 and the fakes."""
    clock.reset(0)
    pins.reset()
    digitalio = types.ModuleType("digitalio")
    digitalio.DigitalInOut = DigitalInOut
    digitalio.Direction = Direction
    monkeypatch.setitem(sys.modules, "digitalio", digitalio)
    if request.param == "pulseio":
        pulseio = types.ModuleType("pulseio")
        pulseio.PulseIn = PulseIn
        monkeypatch.setitem(sys.modules, "pulseio", pulseio)
    else:
        monkeypatch.setitem(sys.modules, "pulseio", None)  # import raises ImportError: bit-bang
    for name in ("adafruit_hcsr04", "drivers.cp_hcsr04"):
        monkeypatch.delitem(sys.modules, name, raising=False)
    adafruit_hcsr04 = importlib.import_module("adafruit_hcsr04")
    assert (request.param == "pulseio") == adafruit_hcsr04._USE_PULSEIO
    monkeypatch.setattr(adafruit_hcsr04, "time", FakeTime)
    return importlib.import_module("drivers.cp_hcsr04")


def tolerance(cp):
    # 0.1 mm. PulseIn times the pulse in hardware. The bit-bang loop sees each edge up to a poll late
    # and reads the clock once more after it, at both ends: +-POLL_US us, 1.72 (0.1 mm) per us.
    return 2 if cp.adafruit_hcsr04._USE_PULSEIO else 2 + POLL_US * 1.72


@pytest.mark.parametrize("temp", [0, 2000, 3500])
def test_cp_backend_reads_the_model_like_the_micropython_driver(cp, temp):
    m = model.HCSR04(2, 3, temp_centi_c=temp)
    ours = mp_driver.HCSR04(Pin(2, Pin.OUT), Pin(3, Pin.IN), clock, time_pulse_us, max_range=10000, temp_centi_c=temp)
    theirs = cp.HCSR04(2, 3, clock, max_range=10000, temp_centi_c=temp)
    for d in (300, 1000, 2500, 5000, 9000):
        m.set_distance(d)
        clock.sleep_ms(60)
        assert ours.ping() == mp_driver.OK
        clock.sleep_ms(60)
        assert theirs.ping() == mp_driver.OK
        assert abs(theirs.distance - d) <= tolerance(cp), (d, theirs.distance)
        assert abs(theirs.distance - ours.distance) <= tolerance(cp) + 2
    assert m.flags == {"short_trigger": 0, "ping_interval": 0, "busy": 0, "crosstalk": 0}


def test_cp_faults_are_statuses_and_the_block_is_bounded(cp):
    m = model.HCSR04(2, 3)
    s = cp.HCSR04(2, 3, clock, max_range=10000)
    dist, status = [5], [5]
    seen = []
    for fault in ("missing", "stuck", "far", "beyond 4 m", "near", "clear"):
        m.missing_echo = fault == "missing"
        m.stuck_high = fault == "stuck"
        m.set_distance({"far": 30000, "beyond 4 m": 50000, "near": 150}.get(fault, 1234))
        clock.sleep_ms(100)
        t0 = clock.now_us()
        seen.append((s.measure_into(dist, status, 0), dist[0]))
        assert clock.now_us() - t0 <= s.max_block_us
    nd = -1
    no_echo, out_of_range = mp_driver.NO_ECHO, mp_driver.OUT_OF_RANGE
    # the module's 38 ms hold (beyond 4 m or inside 2 cm) is timed by the 50 ms timeout: out of range
    assert seen[:5] == [(no_echo, nd), (no_echo, nd), (out_of_range, nd), (out_of_range, nd), (out_of_range, nd)]
    assert seen[5][0] == mp_driver.OK and abs(seen[5][1] - 1234) <= tolerance(cp)


def test_cp_sensors_run_in_the_round_robin(cp):
    models, sensors = [], []
    for k in range(5):
        models.append(model.HCSR04(10 + 2 * k, 11 + 2 * k, distance=1000 + 1200 * k))
        sensors.append(cp.HCSR04(10 + 2 * k, 11 + 2 * k, clock, max_range=5000))
    for a, b in mp_driver.NEIGHBOURS:
        model.link(models[a], models[b])
    with pytest.raises(ValueError, match="lower max_range"):
        mp_driver.RoundRobin(sensors)  # Adafruit's 50 ms minimum timeout cannot fit a 20 ms tick
    rr = mp_driver.RoundRobin(sensors, tick_ms=110)
    dist, status = [0] * 5, [0] * 5
    for _ in range(10):
        t0 = clock.now_us()
        rr.tick(dist, status)
        clock.advance_to(t0 + 110000)
    assert status == [0, 0, 0, 0, 1]  # 58 cm is past the 50 cm max range
    assert all(abs(dist[k] - (1000 + 1200 * k)) <= tolerance(cp) for k in range(4)) and dist[4] == -1
    assert sum(m.flags["crosstalk"] + m.flags["ping_interval"] for m in models) == 0


def test_cp_wait_guard_and_bad_timeout(cp):
    model.HCSR04(2, 3, distance=5000)
    s = cp.HCSR04(2, 3, clock)
    assert s.ping() == mp_driver.OK
    clock.sleep_ms(30)
    assert s.ping() == mp_driver.WAIT
    for bad in (0, 2, "0.1", True):
        with pytest.raises(ValueError, match="timeout_s"):
            cp.HCSR04(4, 5, clock, timeout_s=bad)
