"""Gait changes while walking (issue 22 point 2): every ordered pair of the four gaits, asked as the
console asks it (wait=False) mid-walk on the default robot with its servo guard, on CPython and in the
MicroPython VM (the same integers). No held tick and no standstill, the new gait within one cycle of the
old, its slow-down over within one cycle of the new, every foot inside its reach disc, and the body
centre at least 10 mm inside the support polygon: a float polygon worked out here from the feet, not
hexapod.stability (which the tick's own margin report is checked against)."""

import math

import pytest

from hexapod.gait import NAMES

TARGET = "scenarios.gait_switch:"
PAIRS = [(a, b) for a in range(4) for b in range(4) if a != b]
NO_SUPPORT = -1000000
MARGIN_MIN_MM = 10.0


def float_margin(feet):
    """mm from the body centre to the nearest edge of the polygon of the feet down (leg order 1..6 runs
    clockwise seen from above); negative outside; None on fewer than three feet."""
    pts = [(x / 10.0, y / 10.0) for x, y, down in feet if down]
    if len(pts) < 3:
        return None
    area = sum(pts[k][0] * pts[k - 1][1] - pts[k - 1][0] * pts[k][1] for k in range(len(pts)))
    assert area > 0, pts  # clockwise (x forward, y left): the shoelace sum of (x_k-1 y_k - ...) flipped
    best = math.inf
    for k in range(len(pts)):
        (x0, y0), (x1, y1) = pts[k], pts[(k + 1) % len(pts)]
        # Clockwise: the inside is to the right of each edge; the origin's signed distance.
        d = ((x1 - x0) * y0 - (y1 - y0) * x0) / math.hypot(x1 - x0, y1 - y0)
        best = min(best, d)
    return best


@pytest.mark.parametrize("a,b", PAIRS, ids=["%s-%s" % (NAMES[a], NAMES[b]) for a, b in PAIRS])
def test_a_gait_change_while_walking_never_stops(both_runtimes, a, b):
    # 15 mm/s forward: within every gait's top speed at its own cycle (the wave's is 16.7 mm/s).
    cp, mp = both_runtimes.call(TARGET + "switch", a, b, 150, 0, 0)
    assert cp == mp
    faults, faulted, info, rows = cp
    assert faults == 0 and faulted == []  # every frame's IK and pulses passed
    came, held, margin_min, cycle, slot, old_cycle = info
    assert 0 < came <= old_cycle  # the new gait within one cycle of the old
    assert held == 0  # not one tick with the body held still
    assert [r[1] for r in rows[came - 1 :]] == [b] * (len(rows) - came + 1)
    # The slow-down (if any) ends within one cycle of the new gait, and the body never stands still.
    assert max(r[2] for r in rows) <= cycle and rows[came - 1 + cycle][2] == 0
    assert min(abs(r[4]) + abs(r[5]) for r in rows) > 0
    assert [r[4] for r in rows[-10:]] == [150] * 10  # back to the command
    worst = math.inf
    for k, r in enumerate(rows):
        feet = [r[7 + 5 * i : 10 + 5 * i] for i in range(6)]
        for i in range(6):
            dist, rho = r[10 + 5 * i], r[11 + 5 * i]
            assert dist <= rho, (k, i, dist, rho)  # inside its reach disc
        m = float_margin(feet)
        assert m is not None, (k, feet)
        worst = min(worst, m)
        if r[2] > 0:  # the tick reports the margin while the new gait settles
            assert r[3] / 10.0 == pytest.approx(m, abs=0.2), (k, r[3], m)
    assert worst >= MARGIN_MIN_MM
    assert margin_min / 10.0 >= MARGIN_MIN_MM and margin_min / 10.0 >= worst - 0.2


def test_a_refused_gait_change_changes_nothing(both_runtimes):
    cp, mp = both_runtimes.call(TARGET + "refusals")
    assert cp == mp
    names = "is not one of 0 tripod, 1 tetrapod, 2 ripple, 3 wave"
    assert cp == [
        "gait: 7 " + names,
        True,
        "gait: 'ripple' " + names,
        True,
        "gait: -1 " + names,
        True,
        "gait: True " + names,
        True,
        "cycle_ms: 100 ms is outside 500..5000 ms",
        True,
        "cycle_ms: 9000 ms is outside 500..5000 ms",
        True,
        32,  # hexapod.tick.CONFIGURING: the first change is still being checked
        True,
    ]


def test_a_change_on_the_move_allocates_nothing_a_tick(mp):
    # The fitting, the tick the new gait is taken (phase_in) and the slowed ticks after it.
    pairs = [[3, 0], [0, 3], [2, 1], [1, 2]]
    got = mp.call(TARGET + "heap_per_tick", pairs)
    assert got == [[a, b, b, 0, 299] for a, b in pairs]


@pytest.mark.parametrize("what", ["stop", "walk", "gait", "stopping"])
def test_a_change_interrupted_while_it_is_taken_still_phases_in(both_runtimes, what):
    # A change is taken over three ticks (walker.pending 2: the settings, 3: the rooms, then the slot;
    # hexapod.gaitswitch.after_tick). Asked the tripod into wave at 15 mm/s, the walker waits with
    # pending 1 until every foot is down; then, at the first of the three ticks:
    cp, mp = both_runtimes.call(TARGET + "interrupted", what)
    assert cp == mp
    seen, (state, pending, _phase, gait, held, lifted, faults) = cp
    k = seen.index(2) if 2 in seen else seen.index(0)
    assert seen[:k] == [1] * k and k > 0
    after = {
        "stop": [2, 3, 0],  # a stop lets the slot come (the walker still walks, slowing)
        "walk": [2, 3, 3, 0],  # a new command at the slot's tick: the rooms again, the slot a tick later
        "gait": [2, 3, 1, 2, 3, 0],  # tetrapod (table) taken at once after: waits, then its own three
        "stopping": [0],  # stopped in the settings' tick (asked after a stop): no slot, phase 0
    }[what]
    assert seen[k : k + len(after)] == after and set(seen[k + len(after) :]) == {0}, seen[k:]
    # Then (after a stop: standing, then walking again) it walks the new gait, every leg lifting, with
    # no tick held and no fault; a stop in the settings' tick keeps the new gait's swing budget
    # (without it the tripod's stayed, and the walk restarted from the stop held 120 ticks of 300).
    assert (state, pending, gait) == (2, 0, 1 if what == "gait" else 3)
    assert (held, lifted, faults) == (0, 6, 0)
