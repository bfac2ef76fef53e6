"""HC-SR04 ultrasonic ranger model on two stub pins (trigger in, echo out).

Distances in 0.1 mm, temperatures in 0.01 degC, times in unwrapped virtual us (_stub_clock).
What the datasheet and common modules do, and what is modelled:
- a trigger pulse >= 10 us starts a ping at its falling edge; a shorter one is ignored and
  counted as `short_trigger`;
- the module sends 8 cycles of 40 kHz, then raises echo (`burst_us` after the trigger,
  an assumed 460 us: bursts take 200 us, clones add their own MCU latency);
- echo stays high for the round trip 2 * d / c with c = 331.3 + 0.606 * T m/s (about
  58 us per cm at 20 degC);
- nothing inside 2 cm or beyond 4 m is heard: the module then holds echo high for its own
  timeout, `NO_ECHO_HOLD_US` (38 ms);
- a trigger while echo is still high is ignored (`busy`); pings of one module less than
  60 ms apart are counted as `ping_interval` (the datasheet's measurement cycle);
- a neighbour (see `link`) pinged less than `CROSSTALK_US` after this one can hear this
  one's burst: counted as `crosstalk` on both;
- faults: `stuck_high` (echo never falls), `missing_echo` (echo never rises).
Violation counters live in `flags` (a dict set up front, so counting never allocates).
"""

import _stub_clock as clock
import _stub_pins as pins

MIN_RANGE = 200  # 0.1 mm: 2 cm
MAX_RANGE = 40000  # 0.1 mm: 4 m
MIN_TRIGGER_US = 10
MIN_CYCLE_US = 60000
NO_ECHO_HOLD_US = 38000
CROSSTALK_US = 38000  # a ping is heard for as long as a module may listen for its echo
BURST_US = 460


def round_trip_us(distance, temp_centi_c=2000):
    """Echo width in us for a target distance (0.1 mm) at temp (0.01 degC), rounded."""
    c_x100 = 33130000 + 606 * temp_centi_c  # speed of sound in 0.01 mm/s
    # t[us] = 2 * d[mm] * 1e6 / c[mm/s] = 2 * (distance / 10) * 1e6 * 100 / c_x100
    return (2 * distance * 10000000 + c_x100 // 2) // c_x100


class HCSR04:
    """One module: connect it to trigger and echo pin ids, then set a distance."""

    def __init__(self, trigger_id, echo_id, distance=10000, temp_centi_c=2000, burst_us=BURST_US):
        self.trigger_id = trigger_id
        self.echo_id = echo_id
        self.burst_us = burst_us
        self.temp_centi_c = temp_centi_c
        self.stuck_high = False
        self.missing_echo = False
        self.neighbours = []
        self.pings = 0
        self.flags = {"short_trigger": 0, "ping_interval": 0, "busy": 0, "crosstalk": 0}
        self.last_ping_us = -1  # unwrapped us of the last accepted ping, -1 before any
        self._trig_level = 0
        self._trig_rise = 0
        self._rise = -1  # echo window [rise, fall) of the current ping
        self._fall = -1
        self.echo_us = 0
        self.set_distance(distance)
        pins.connect(trigger_id, self)
        pins.connect(echo_id, self)

    def set_distance(self, distance):
        """Target distance in 0.1 mm (applies to the next ping)."""
        self.distance = distance
        self.in_range = MIN_RANGE <= distance <= MAX_RANGE
        self.echo_us = round_trip_us(distance, self.temp_centi_c) if self.in_range else NO_ECHO_HOLD_US

    def set_temperature(self, temp_centi_c):
        self.temp_centi_c = temp_centi_c
        self.set_distance(self.distance)

    def pin_written(self, pin_id, lv):
        if pin_id != self.trigger_id or lv == self._trig_level:
            return
        self._trig_level = lv
        now = clock.now_us()
        if lv:
            self._trig_rise = now
            return
        if now - self._trig_rise < MIN_TRIGGER_US:
            self.flags["short_trigger"] += 1
            return
        if self._rise >= 0 and now < self._fall:
            self.flags["busy"] += 1
            return
        self._ping(now)

    def _ping(self, now):
        if self.last_ping_us >= 0 and now - self.last_ping_us < MIN_CYCLE_US:
            self.flags["ping_interval"] += 1
        for n in self.neighbours:
            if n.last_ping_us >= 0 and now - n.last_ping_us < CROSSTALK_US:
                self.flags["crosstalk"] += 1
                n.flags["crosstalk"] += 1
        self.last_ping_us = now
        self.pings += 1
        self._rise = now + self.burst_us
        self._fall = self._rise + self.echo_us

    def level(self, pin_id, t_us):
        if pin_id != self.echo_id:
            return -1
        if self.stuck_high:
            return 1
        if self.missing_echo or self._rise < 0:
            return 0
        return 1 if self._rise <= t_us < self._fall else 0

    def next_change(self, pin_id, t_us):
        if pin_id != self.echo_id or self.stuck_high or self.missing_echo or self._rise < 0:
            return -1
        if t_us < self._rise:
            return self._rise
        if t_us < self._fall:
            return self._fall
        return -1


def link(a, b):
    """Declare two modules neighbours: pings close together count as cross-talk."""
    if b not in a.neighbours:
        a.neighbours.append(b)
    if a not in b.neighbours:
        b.neighbours.append(a)
