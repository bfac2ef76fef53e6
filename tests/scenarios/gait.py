"""hexapod.gait's GaitClock: who swings when, on integer ticks."""

from hexapod.gait import NAMES, GaitClock


def tables(cycles):
    """[gait, cycle_ms asked, cycle ticks, swing ticks, stance ticks, cycle_ms, [swinging legs a tick],
    [[phase a tick] a leg]] of every gait at each cycle."""
    swing = [0] * 6
    rows = []
    for gait in range(len(NAMES)):
        for cycle_ms in cycles:
            c = GaitClock(gait, cycle_ms)
            pattern = [list(c.swinging_at(p, swing)) for p in range(c.cycle_ticks)]
            phases = [[c.phase_of(leg, p) for p in range(c.cycle_ticks)] for leg in range(6)]
            rows.append([gait, cycle_ms, c.cycle_ticks, c.swing_ticks, c.stance_ticks, c.cycle_ms, pattern, phases])
    return rows
