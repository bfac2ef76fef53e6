"""HC-SR04 ranging shared by every driver: the median filter (MedianRanger, which a driver
subclasses with its ping()), the echo's arithmetic and the five-sensor round robin (RoundRobin).

drivers.hcsr04 (MicroPython's pin and IRQ driver) and the CircuitPython drivers
(drivers.cp_hcsr04_pulsein, drivers.cp_hcsr04) build on it; drivers.hcsr04 re-exports every name
here. A module of its own so that a CircuitPython board, which times the echo with pulseio,
compiles and keeps none of MicroPython's pin driver (docs/flashing.md).

Units: distances in 0.1 mm, temperature in 0.01 degC, pulse and block times in us, tick in ms.
"""

from array import array

from micropython import const

# The contract's codes (hexapod.sensors) copied as private constants, folded into the code;
# tests/test_viper_twins.py checks each copy against its source.
_FRONT = const(0)  # hexapod.sensors.FRONT
_LEFT_FRONT = const(1)  # hexapod.sensors.LEFT_FRONT
_LEFT_REAR = const(2)  # hexapod.sensors.LEFT_REAR
_RIGHT_FRONT = const(3)  # hexapod.sensors.RIGHT_FRONT
_RIGHT_REAR = const(4)  # hexapod.sensors.RIGHT_REAR
_MIN_RANGE = const(200)  # hexapod.sensors.MIN_RANGE
_NO_DISTANCE = const(-1)  # hexapod.sensors.NO_DISTANCE
_OK = const(0)  # hexapod.sensors.OK
_OUT_OF_RANGE = const(1)  # hexapod.sensors.OUT_OF_RANGE
_TOO_CLOSE = const(4)  # hexapod.sensors.TOO_CLOSE
_WAIT = const(5)  # hexapod.sensors.WAIT

MAX_RANGE = const(40000)  # 4 m
TRIGGER_US = const(10)
MIN_CYCLE_US = const(60000)  # datasheet: >= 60 ms between pings of one module
RISE_US = const(1000)  # allowance for the 8-cycle 40 kHz burst before echo rises
_SHIFT = const(14)
_HALF = const(8192)  # rounding for >> _SHIFT

# Pairs that face the same wall or corner: each can hear the other's burst.
NEIGHBOURS = ((_FRONT, _LEFT_FRONT), (_FRONT, _RIGHT_FRONT), (_LEFT_FRONT, _LEFT_REAR), (_RIGHT_FRONT, _RIGHT_REAR))


def speed_x100(temp_centi_c):
    """Speed of sound in 0.01 mm/s at temp (0.01 degC): c = 331.3 + 0.606 T m/s."""
    return 33130000 + 606 * temp_centi_c


def round_trip_us(distance, temp_centi_c):
    """Echo width in us for distance (0.1 mm), rounded up (init-time helper: may use big ints)."""
    c = speed_x100(temp_centi_c)
    return (2 * distance * 10000000 + c - 1) // c


def _check_int(name, v, lo, hi, unit):
    if not isinstance(v, int) or isinstance(v, bool) or v < lo or v > hi:
        raise ValueError("%s: %r, allowed %d..%d %s" % (name, v, lo, hi, unit))


class MedianRanger:
    """Median of the last N pings; subclasses provide ping() -> status and set self.distance."""

    def __init__(self, samples, max_range, temp_centi_c):
        _check_int("samples", samples, 1, 9, "pings")
        _check_int("max_range", max_range, _MIN_RANGE, MAX_RANGE, "(0.1 mm)")
        _check_int("temp_centi_c", temp_centi_c, -4000, 6000, "(0.01 degC)")
        self.max_range = max_range
        self.distance = _NO_DISTANCE  # 0.1 mm, valid after a ping returned OK
        self._win = array("i", [_NO_DISTANCE] * samples)
        self._sorted = array("i", [0] * samples)
        self._head = 0
        self.set_temperature(temp_centi_c)

    def set_temperature(self, temp_centi_c):
        """Air temperature in 0.01 degC; recomputes the scale and the timeout (not for the tick)."""
        _check_int("temp_centi_c", temp_centi_c, -4000, 6000, "(0.01 degC)")
        self.temp_centi_c = temp_centi_c
        # 0.1 mm per us of echo = c[0.01 mm/s] / 2e7, as a 2**14 fixed-point factor: echo_us * k
        # stays below 2**30 (a small int on a 32-bit board) up to the 4 m timeout at -40..60 degC.
        self._k = (speed_x100(temp_centi_c) * (1 << _SHIFT) + 10000000) // 20000000
        rt = round_trip_us(self.max_range, temp_centi_c)
        self.timeout_us = rt + rt // 16 + RISE_US  # per phase of time_pulse_us
        self.max_block_us = self._block_us()

    def _block_us(self):
        return 0

    def to_distance(self, echo_us):
        """0.1 mm for an echo width in us (rounded)."""
        return (echo_us * self._k + _HALF) >> _SHIFT

    def accept(self, d):
        """Status of a measured distance d (0.1 mm); OK keeps it in self.distance."""
        if d > self.max_range:
            return _OUT_OF_RANGE
        if d < _MIN_RANGE:
            return _TOO_CLOSE
        self.distance = d
        return _OK

    def measure_into(self, dist, status, i):
        """Ping; write status[i] and dist[i] (median 0.1 mm, or NO_DISTANCE); return the status.

        WAIT leaves both buffers untouched. The median covers the OK pings among the last N.
        """
        return self._record(self.ping(), dist, status, i)

    def _record(self, s, dist, status, i):
        if s == _WAIT:
            return s
        status[i] = s
        win = self._win
        if len(win) == 1:  # one sample is its own median: no window to keep (~25 us a ping on a Pico)
            dist[i] = self.distance if s == _OK else _NO_DISTANCE
            return s
        win[self._head] = self.distance if s == _OK else _NO_DISTANCE
        self._head += 1
        if self._head == len(win):
            self._head = 0
        dist[i] = self._median() if s == _OK else _NO_DISTANCE
        return s

    def _median(self):
        win = self._win
        srt = self._sorted
        m = 0
        for j in range(len(win)):
            v = win[j]
            if v < 0:
                continue
            k = m
            while k > 0 and srt[k - 1] > v:
                srt[k] = srt[k - 1]
                k -= 1
            srt[k] = v
            m += 1
        return (srt[(m - 1) >> 1] + srt[m >> 1]) >> 1


def plan(count, tick_ms, neighbours, cycle_ms, crosstalk_ms):
    """Slot table: sensor index per tick (-1 idle), shortest cycle meeting both gaps.

    Each sensor fires once per cycle (cycle length * tick_ms >= cycle_ms), and two neighbours
    are at least crosstalk_ms apart in both directions around the cycle.
    """
    for slots in range(count, 4 * count + 4):
        if slots * tick_ms < cycle_ms:
            continue
        gap = (crosstalk_ms + tick_ms - 1) // tick_ms  # ticks between neighbours
        at = [-1] * count
        if _place(0, at, slots, gap, neighbours):
            table = [-1] * slots
            for i in range(count):
                table[at[i]] = i
            return tuple(table)
    raise ValueError(
        "no round robin of %d sensors fits neighbours %d ms apart at %d ms ticks" % (count, crosstalk_ms, tick_ms)
    )


def _place(i, at, slots, gap, neighbours):
    if i == len(at):
        return True
    for s in range(slots if i else 1):  # sensor 0 in slot 0: rotations are the same plan
        if s in at:
            continue
        ok = True
        for a, b in neighbours:
            o = b if a == i else (a if b == i else -1)
            if o >= 0 and o < i:
                d = (s - at[o]) % slots
                if min(d, slots - d) < gap:
                    ok = False
                    break
        if ok:
            at[i] = s
            if _place(i + 1, at, slots, gap, neighbours):
                return True
            at[i] = -1
    return False


class RoundRobin:
    """Fires one sensor per tick from a fixed slot table; results into caller-owned buffers.

    Sensors that split (HCSR04 with irq=True) report a tick after they fire: each tick collects
    the previous slot's echo, then fires this slot's."""

    def __init__(self, sensors, *, tick_ms=20, neighbours=NEIGHBOURS, cycle_ms=60, crosstalk_ms=38):
        n = len(sensors)
        if n < 1:
            raise ValueError("sensors: need at least one")
        _check_int("tick_ms", tick_ms, 1, 1000, "ms")
        _check_int("cycle_ms", cycle_ms, 0, 10000, "ms")
        _check_int("crosstalk_ms", crosstalk_ms, 0, 10000, "ms")
        for pair in neighbours:
            if (
                not isinstance(pair, (tuple, list))
                or len(pair) != 2
                or pair[0] not in range(n)
                or pair[1] not in range(n)
                or pair[0] == pair[1]
            ):
                raise ValueError("neighbours: %r, allowed pairs of two different indices 0..%d" % (pair, n - 1))
        worst = 0
        for s in sensors:
            worst = max(worst, s.max_block_us)
        if worst > tick_ms * 1000:
            raise ValueError("a ping may block %d us, more than the %d ms tick: lower max_range" % (worst, tick_ms))
        self.sensors = sensors
        self.slots = plan(n, tick_ms, neighbours, cycle_ms, crosstalk_ms)
        self.max_block_us = worst
        self.split = True
        for s in sensors:
            self.split = self.split and getattr(s, "split", False)
        self._pos = 0
        self._fired = -1  # the sensor fired on the last tick (split sensors)

    def tick(self, dist, status):
        """Run this tick's slot into dist/status; return the index of the sensor whose result
        came in (this slot's, or with split sensors the last slot's), -1 when none."""
        i = self.slots[self._pos]
        self._pos += 1
        if self._pos == len(self.slots):
            self._pos = 0
        if not self.split:
            if i >= 0:
                self.sensors[i].measure_into(dist, status, i)
            return i
        j = self._fired
        if j >= 0:
            self.sensors[j].collect_into(dist, status, j)
        if i >= 0:
            self.sensors[i].fire()
        self._fired = i
        return j
