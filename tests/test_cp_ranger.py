"""drivers.cp_hcsr04_pulsein: the non-blocking CircuitPython HC-SR04 (CPython, fake CircuitPython modules).

Two echo sources: the HC-SR04 model (distances, temperatures, the round robin, faults) and
Script below, which plays any echo pulse train after a trigger, to reach every capture
PulseIn can hold. Time is the virtual clock; the ranger's clock is cp_clock on a fake supervisor.
"""

import sys
import types

import _stub_clock as vclock
import _stub_pins as pins
import hcsr04_model as model
import pytest
from i2c_bus import I2CBus
from machine import Pin, time_pulse_us

from drivers import hcsr04
from drivers import ranger as shared
from hexapod_host.stubs import circuitpython as fakes_cp
from tests.test_leg_ranges import SMALL, Checker, instrumented

NAME = "drivers.cp_hcsr04_pulsein"
OK, OUT, NO_ECHO, TOO_CLOSE, WAIT = hcsr04.OK, hcsr04.OUT_OF_RANGE, hcsr04.NO_ECHO, hcsr04.TOO_CLOSE, hcsr04.WAIT
SLOT_US = 100000  # five sensors at 20 ms ticks: each one every 100 ms


@pytest.fixture
def cp(monkeypatch):
    vclock.reset(0)
    pins.reset()
    fake = fakes_cp.CircuitPython(I2CBus(clock_us=vclock.now_us)).install(monkeypatch)
    fake.ranger = fakes_cp.reimport(NAME)
    fake.board = fake.modules["board"]
    fake.vclock = fake.clock()
    yield fake
    fakes_cp.forget(NAME)


class Script:
    """An echo line that plays scripts[k] after the k-th trigger (the last repeats).

    A script is a list of (rise_us, fall_us) after the trigger's fall; fall None: stays high.
    The line is high wherever any window played so far is.
    """

    def __init__(self, trigger_id, echo_id, scripts):
        self.trigger_id, self.echo_id, self.scripts = trigger_id, echo_id, scripts
        self.windows = []
        self.triggers = 0
        self._rise = 0
        self._trig = 0
        pins.connect(trigger_id, self)
        pins.connect(echo_id, self)

    def pin_written(self, pin_id, lv):
        now = vclock.now_us()
        if pin_id != self.trigger_id or lv == self._trig:
            return
        self._trig = lv
        if lv:
            self._rise = now
            return
        assert now - self._rise >= 10, "trigger shorter than 10 us"
        for r, f in self.scripts[min(self.triggers, len(self.scripts) - 1)]:
            self.windows.append((now + r, now + f if f is not None else 1 << 62))
        self.triggers += 1

    def level(self, pin_id, t):
        if pin_id != self.echo_id:
            return -1
        return 1 if any(r <= t < f for r, f in self.windows) else 0

    def next_change(self, pin_id, t):
        if pin_id != self.echo_id:
            return -1
        here = self.level(pin_id, t)
        for c in sorted({x for w in self.windows for x in w if x > t}):
            if self.level(pin_id, c) != here:
                return c
        return -1


def us_for(distance, temp=2000):
    return model.round_trip_us(distance, temp)


def slots(sensor, n):
    """n slots 100 ms apart; [(status, distance or -1)]."""
    out = []
    for _ in range(n):
        s = sensor.ping()
        out.append((s, sensor.distance if s == OK else -1))
        vclock.advance_us(SLOT_US)
    return out


@pytest.mark.parametrize("temp", [-1000, 2000, 3500])
def test_distances_one_cycle_late_like_the_micropython_driver(cp, temp):
    m = model.HCSR04("D4", "D5", temp_centi_c=temp)
    twin = model.HCSR04("D6", "D9", temp_centi_c=temp)
    mp = hcsr04.HCSR04(Pin("D6", Pin.OUT), Pin("D9", Pin.IN), vclock, time_pulse_us, max_range=20000, temp_centi_c=temp)
    s = cp.ranger.HCSR04(cp.board.D4, cp.board.D5, cp.vclock, max_range=20000, temp_centi_c=temp)
    targets = [250, 1000, 2500, 5000, 9000, 15000, 19990]
    seen = []
    for d in targets + [targets[-1]]:
        m.set_distance(d)
        twin.set_distance(d)
        seen.append(s.ping())
        assert mp.ping() == OK and abs(mp.distance - d) <= 2
        if seen[-1] == OK:
            seen[-1] = s.distance
        vclock.advance_us(SLOT_US)
    assert seen[0] == WAIT  # the first slot only fires
    for d, got in zip(targets, seen[1:], strict=True):  # each slot reports the previous slot's ping
        assert abs(got - d) <= 2, (d, got)
    assert m.flags == {"short_trigger": 0, "ping_interval": 0, "busy": 0, "crosstalk": 0}


def test_block_is_the_trigger_only_and_the_round_robin_takes_it(cp):
    b = cp.board
    pairs = [(b.D4, b.D5), (b.D6, b.D9), (b.D10, b.D11), (b.D13, b.D12), (b.A0, b.A1)]
    models = [model.HCSR04(t.name, e.name, distance=1500 + 1700 * k) for k, (t, e) in enumerate(pairs)]
    for a, c in hcsr04.NEIGHBOURS:
        model.link(models[a], models[c])
    sensors = [cp.ranger.HCSR04(t, e, cp.vclock) for t, e in pairs]
    assert [s.max_block_us for s in sensors] == [hcsr04.TRIGGER_US] * 5 == [10] * 5
    rr = hcsr04.RoundRobin(sensors)  # refused for adafruit_hcsr04 at 20 ms (test_hcsr04_cp.py)
    assert rr.max_block_us == 10
    dist, status = [-1] * 5, [WAIT] * 5
    blocks = []
    for _ in range(300):
        t0 = vclock.now_us()
        if rr.tick(dist, status) >= 0:
            blocks.append(vclock.now_us() - t0)
        vclock.advance_to(t0 + 20000)
    assert max(blocks) == min(blocks) == 10 and len(blocks) == 300 * 5 // len(rr.slots)
    assert status == [OK] * 5
    assert [abs(dist[k] - (1500 + 1700 * k)) <= 2 for k in range(5)] == [True] * 5, dist
    assert sum(sum(m.flags.values()) for m in models) == 0  # no crosstalk, no ping closer than 60 ms
    assert min(m.pings for m in models) >= 59


def test_model_faults_are_statuses_never_distances(cp):
    m = model.HCSR04("D4", "D5", distance=3000)
    s = cp.ranger.HCSR04(cp.board.D4, cp.board.D5, cp.vclock, max_range=10000)
    dist, status = [7], [7]
    log = []
    for fault in ("ok", "ok", "missing", "missing", "ok", "ok", "ok", "stuck", "stuck", "ok", "ok", "ok", "far", "4m+",
                  "near", "ok", "ok"):  # fmt: skip
        m.missing_echo = fault == "missing"
        m.stuck_high = fault == "stuck"
        m.set_distance({"far": 15000, "4m+": 45000, "near": 150}.get(fault, 3000))
        s.measure_into(dist, status, 0)
        log.append((fault, status[0], dist[0]))
        vclock.advance_us(SLOT_US)
    for _, st, d in log[1:]:
        assert (st == OK) == (d >= 0) and (d < 0 or abs(d - 3000) <= 2), log
    ne = NO_ECHO
    # A slot reads the ping fired one slot earlier; the fake applies a fault from the previous ask
    # on (so a fault set at slot k already spoils the echo read at k). A capture after an empty one
    # is not trusted (the line may have been high when that ping fired); a stuck line costs one
    # more: the ping fired into it comes back as two widths.
    assert [st for _, st, _ in log] == [7, OK, ne, ne, ne, OK, OK, ne, ne, ne, ne, OK, OK, OUT, OUT, OUT, OK]
    # 7: the first slot left the buffers alone; OUT: 1.5 m > max_range, 38 ms holds beyond 4 m and inside 2 cm


def one_capture(cp, script, max_range=10000, temp=2000):
    """Status and distance of the second slot after a first ping that played script."""
    Script("D4", "D5", [script, [(460, 460 + us_for(3000, temp))]])
    s = cp.ranger.HCSR04(cp.board.D4, cp.board.D5, cp.vclock, max_range=max_range, temp_centi_c=temp)
    return s, slots(s, 4)


def w(distance):
    return (460, 460 + us_for(distance))


CAPTURES = [
    # first ping's echo, (status, distance) read for it, status of the next ping (played clean)
    ([w(5000)], (OK, 5000), OK),
    ([], (NO_ECHO, -1), NO_ECHO),  # nothing rose: and the line may be high, so the next is not trusted
    ([(460, 150000)], (NO_ECHO, -1), NO_ECHO),  # stuck high past the next ping, whose capture is then partial
    ([(460, 38460)], (OUT, -1), OK),  # the module's 38 ms hold
    ([(460, 460 + 70000)], (OUT, -1), OK),  # PulseIn saturates at 65535 us
    ([(460, 460 + 100)], (TOO_CLOSE, -1), OK),  # 100 us: 1.7 cm
    ([w(10000)], (OK, 10000), OK),  # exactly max_range
    ([w(10006)], (OUT, -1), OK),
    ([w(205)], (OK, 205), OK),  # just past the 2 cm minimum
    ([w(4000), (20000, 20100)], (OK, 4000), OK),  # a stray pulse after ours (3 widths): ours is the first
    ([w(4000), (20000, 150000)], (NO_ECHO, -1), NO_ECHO),  # high again past the next ping (2 widths)
    ([w(4000), (20000, 20100), (30000, 30100)], (NO_ECHO, -1), NO_ECHO),  # 5 widths > maxlen 4: noise
]


@pytest.mark.parametrize("script,first,after", CAPTURES)
def test_every_capture_pulsein_can_hold(cp, script, first, after):
    s, got = one_capture(cp, script)
    assert got[0] == (WAIT, -1)
    st, d = got[1]
    assert st == first[0] and (d == -1 if first[1] < 0 else abs(d - first[1]) <= 2), got
    assert got[2][0] == after
    assert got[3][0] == OK and abs(got[3][1] - 3000) <= 2  # always back one clean cycle later


def test_a_released_stuck_line_is_never_timed_as_an_echo(cp):
    # Ping 1's echo is followed by a level that goes high at 50 ms and falls 3 ms after ping 2 fired:
    # PulseIn, armed by ping 2 while the line was high, times those last 3 ms, a 51 cm "echo".
    Script("D4", "D5", [[w(3000), (50000, 103000)], [w(6000)]])
    s = cp.ranger.HCSR04(cp.board.D4, cp.board.D5, cp.vclock, max_range=10000)
    first = slots(s, 2)
    held = s._echo[0]
    assert 0 < held <= s.timeout_us and hcsr04.MIN_RANGE < s.to_distance(held) < 10000  # would pass as a distance
    rest = slots(s, 2)
    assert [st for st, _ in first + rest] == [WAIT, NO_ECHO, NO_ECHO, OK]
    assert abs(rest[1][1] - 6000) <= 2


def test_an_echo_line_high_at_start_up_is_not_trusted(cp):
    model.HCSR04("D4", "D5", distance=2500)
    pins.force("D5", 1)
    s = cp.ranger.HCSR04(cp.board.D4, cp.board.D5, cp.vclock)
    pins.force("D5", -1)
    assert [st for st, _ in slots(s, 3)] == [WAIT, NO_ECHO, OK]


def test_wait_guard_leaves_buffers_and_fires_nothing(cp):
    m = model.HCSR04("D4", "D5", distance=2500)
    s = cp.ranger.HCSR04(cp.board.D4, cp.board.D5, cp.vclock)
    dist, status = [11], [12]
    assert s.measure_into(dist, status, 0) == WAIT and (dist, status) == ([11], [12]) and m.pings == 1
    vclock.advance_us(59000)
    assert s.measure_into(dist, status, 0) == WAIT and (dist, status) == ([11], [12]) and m.pings == 1
    vclock.advance_us(1000)
    assert s.measure_into(dist, status, 0) == OK and abs(dist[0] - 2500) <= 2 and m.pings == 2


class SlotChecker(Checker):
    """Checks only while armed: set_temperature may use big ints at start-up (not the slot's path)."""

    armed = False

    def __call__(self, value):
        return Checker.__call__(self, value) if self.armed else value


def test_no_intermediate_leaves_the_small_ints(cp, monkeypatch):
    checker = SlotChecker()
    monkeypatch.setitem(sys.modules, "drivers.ranger", instrumented(shared, checker, {}))
    ranger = instrumented(cp.ranger, checker, {})
    for temp in (-4000, 6000):
        for rng in (200, 40000):
            Script("D4", "D5", [[(460, 460 + width)] for width in (1, 100, 11000, 26000, 38000, 65535, 70000)])
            s = ranger.HCSR04(cp.board.D4, cp.board.D5, cp.vclock, max_range=rng, temp_centi_c=temp)
            checker.armed = True
            assert {st for st, _ in slots(s, 8)} >= {OUT}
            checker.armed = False
            s.deinit()
            pins.reset()
    assert 1 << 28 < checker.biggest < SMALL


def test_deinit_releases_both_pins(cp):
    s = cp.ranger.HCSR04(cp.board.D4, cp.board.D5, cp.vclock)
    assert set(cp.claimed) == {"D4", "D5"}
    s.deinit()
    assert cp.claimed == {}
    cp.ranger.HCSR04(cp.board.D4, cp.board.D5, cp.vclock)  # free again


def bad_cases(cp):
    b, c = cp.board, cp.vclock
    no_diff = types.SimpleNamespace(ticks_ms=c.ticks_ms, ticks_diff=5, sleep_us=c.sleep_us)
    return [
        ((None, b.D5, c), {}, "trigger_pin: None"),
        ((b.D4, None, c), {}, "echo_pin: None"),
        (("D4", b.D5, c), {}, "trigger_pin: 'D4'"),
        ((b.D4, 5, c), {}, "echo_pin: 5"),
        ((b.D4, b.D4, c), {}, "both board.D4"),
        ((b.D4, b.D5, None), {}, "no ticks_ms()"),
        ((b.D4, b.D5, object()), {}, "no ticks_ms()"),
        ((b.D4, b.D5, no_diff), {}, "no ticks_diff()"),
        ((b.D4, b.D5, c), {"max_range": 199}, "max_range: 199, allowed 200..40000"),
        ((b.D4, b.D5, c), {"max_range": 40001}, "max_range: 40001"),
        ((b.D4, b.D5, c), {"max_range": 1000.0}, "max_range: 1000.0"),
        ((b.D4, b.D5, c), {"max_range": "1000"}, "max_range: '1000'"),
        ((b.D4, b.D5, c), {"max_range": True}, "max_range: True"),
        ((b.D4, b.D5, c), {"samples": 0}, "samples: 0, allowed 1..9"),
        ((b.D4, b.D5, c), {"samples": 10}, "samples: 10"),
        ((b.D4, b.D5, c), {"samples": None}, "samples: None"),
        ((b.D4, b.D5, c), {"temp_centi_c": -4001}, "temp_centi_c: -4001, allowed -4000..6000"),
        ((b.D4, b.D5, c), {"temp_centi_c": 6001}, "temp_centi_c: 6001"),
        ((b.D4, b.D5, c), {"temp_centi_c": 20.5}, "temp_centi_c: 20.5"),
    ]


def test_bad_arguments_name_the_value_and_claim_nothing(cp):
    m = model.HCSR04("D4", "D5", distance=2500)
    cases = bad_cases(cp)
    for args, kw, message in cases:
        with pytest.raises(ValueError) as e:
            cp.ranger.HCSR04(*args, **kw)
        assert message in str(e.value) and "allowed" in str(e.value), (message, str(e.value))
        assert cp.claimed == {} and m.pings == 0, message
    with pytest.raises(TypeError):
        cp.ranger.HCSR04(cp.board.D4, cp.board.D5, cp.vclock, 10000)  # settings are keyword-only
    assert len(cases) >= 19
