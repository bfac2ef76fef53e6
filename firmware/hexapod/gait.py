"""Gaits on integer ticks: which legs swing at which tick of the cycle (StanfordQuadruped style).

A gait splits its cycle into equal slots; each leg swings for a fixed number of slots from
its own start slot and pushes (stance) for the rest. Ticks are the 50 Hz control frames
(TICK_MS each); a slot is a whole number of ticks, so every leg's swing has an exact tick
count. Legs are 0-based here (0 = leg 1 RF ... 5 = leg 6 LF).

- tripod: legs 1, 3, 5 swing while 2, 4, 6 push, then the reverse (seeds 000, 001); duty 1/2.
- tetrapod: pairs {3, 6}, {2, 5}, {1, 4} swing in turn; four feet down; duty 2/3.
- ripple: one leg per side swings, the sides half a cycle apart, rear to front; duty 2/3.
- wave: one leg at a time, right rear to front, then left rear to front; duty 5/6.

Seed 001's four phases of a leg map onto a cycle as: power = stance; lift, swing and
contact = the first, middle and last third of the swing (the foot rises, travels, lands).
"""

from array import array

from micropython import const

TRIPOD = const(0)
TETRAPOD = const(1)
RIPPLE = const(2)
WAVE = const(3)
NAMES = ("tripod", "tetrapod", "ripple", "wave")

POWER = const(0)
LIFT = const(1)
SWING = const(2)
CONTACT = const(3)
PHASE_NAMES = ("power", "lift", "swing", "contact")

TICK_MS = const(20)  # one control frame at 50 Hz
CYCLE_MS_MIN = const(500)
CYCLE_MS_MAX = const(5000)

_SLOTS = (2, 3, 6, 6)
_SWING_SLOTS = (1, 1, 2, 1)
_START_SLOT = (
    (0, 1, 0, 1, 0, 1),
    (2, 1, 0, 2, 1, 0),
    (4, 2, 0, 3, 5, 1),
    (2, 1, 0, 3, 4, 5),
)


def check_gait(gait):
    """ValueError unless gait is one of the gait numbers."""
    if not isinstance(gait, int) or isinstance(gait, bool) or gait < 0 or gait >= len(NAMES):
        raise ValueError(
            "gait: %r is not one of %s" % (gait, ", ".join("%d %s" % (k, NAMES[k]) for k in range(len(NAMES))))
        )


def gait_number(name):
    """The gait number of a name such as 'ripple'; ValueError lists the names."""
    for k in range(len(NAMES)):
        if NAMES[k] == name:
            return k
    raise ValueError("gait: %r is not one of %s" % (name, ", ".join(NAMES)))


def check_cycle_ms(cycle_ms):
    if not isinstance(cycle_ms, int) or isinstance(cycle_ms, bool):
        raise ValueError("cycle_ms: need a whole number of milliseconds, got %r" % (cycle_ms,))
    if cycle_ms < CYCLE_MS_MIN or cycle_ms > CYCLE_MS_MAX:
        raise ValueError("cycle_ms: %d ms is outside %d..%d ms" % (cycle_ms, CYCLE_MS_MIN, CYCLE_MS_MAX))


def slot_ticks(gait, cycle_ms):
    """Ticks per slot a gait gets for a cycle time (ms): the nearest whole number."""
    slots = _SLOTS[gait]
    return (cycle_ms + (TICK_MS * slots >> 1)) // (TICK_MS * slots)


def actual_cycle_ms(gait, cycle_ms):
    """The cycle time (ms) a gait really runs for a cycle_ms: whole ticks per slot."""
    return slot_ticks(gait, cycle_ms) * _SLOTS[gait] * TICK_MS


def swing_stance_ticks(gait, cycle_ms, out):
    """(swing ticks, stance ticks) of a gait at a cycle time (ms), into out[0:2]."""
    st = slot_ticks(gait, cycle_ms)
    out[0] = st * _SWING_SLOTS[gait]
    out[1] = st * _SLOTS[gait] - out[0]
    return out


class GaitClock:
    """Tick timing of one gait at one cycle time: slot, swing and stance lengths in ticks."""

    def __init__(self, gait=TRIPOD, cycle_ms=1000):
        # each leg's first swing tick in the cycle (hexapod/_walk_viper.py reads the words)
        self.start = array("i", [0] * 6)
        self.set(gait, cycle_ms)

    def set(self, gait, cycle_ms):
        """Take a gait number and a cycle time in ms (rounded to whole ticks per slot)."""
        check_gait(gait)
        check_cycle_ms(cycle_ms)
        slots = _SLOTS[gait]
        self.gait = gait
        self.slot_ticks = slot_ticks(gait, cycle_ms)
        self.cycle_ticks = self.slot_ticks * slots
        self.cycle_ms = self.cycle_ticks * TICK_MS
        self.swing_ticks = self.slot_ticks * _SWING_SLOTS[gait]
        self.stance_ticks = self.cycle_ticks - self.swing_ticks
        for i in range(6):
            self.start[i] = _START_SLOT[gait][i] * self.slot_ticks

    def swing_tick(self, leg, phase):
        """Ticks since leg's swing began (0..swing_ticks-1) at cycle tick phase, or -1 in stance."""
        u = phase - self.start[leg]
        if u < 0:
            u += self.cycle_ticks
        return u if u < self.swing_ticks else -1

    def phase_of(self, leg, phase):
        """Seed 001's phase of a leg at a cycle tick: POWER, LIFT, SWING or CONTACT."""
        u = self.swing_tick(leg, phase)
        if u < 0:
            return POWER
        third = u * 3 // self.swing_ticks
        return LIFT if third == 0 else (SWING if third == 1 else CONTACT)

    def swinging_at(self, phase, out):
        """1 for each leg in swing at a cycle tick, else 0, into out[0:6]."""
        for i in range(6):
            out[i] = 1 if self.swing_tick(i, phase) >= 0 else 0
        return out
