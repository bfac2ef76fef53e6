"""Gait tables on integer ticks: who swings when, duty factors, seed 001's phases.

The tables come from tests/scenarios/gait.py."""

import pytest

CYCLES = [500, 1000, 2345, 5000]  # ms


@pytest.fixture(scope="module")
def tables():
    from hexapod_host.testing.runtimes import CPythonRuntime

    return CPythonRuntime().call("scenarios.gait:tables", CYCLES)


def test_tables_identical_in_both_runtimes(rt, tables):
    assert rt.call("scenarios.gait:tables", CYCLES) == tables
    assert len(tables) == 4 * len(CYCLES)


def test_every_leg_swings_once_per_cycle_for_its_duty(tables):
    duty = {0: (1, 2), 1: (1, 3), 2: (1, 3), 3: (1, 6)}  # swing share of the cycle
    for gait, cycle_ms, ticks, swing, stance, real_ms, pattern, _ in tables:
        assert swing + stance == ticks and real_ms == 20 * ticks
        assert abs(real_ms - cycle_ms) <= 20 * {0: 2, 1: 3, 2: 6, 3: 6}[gait] // 2
        assert swing * duty[gait][1] == ticks * duty[gait][0]
        for leg in range(6):
            column = [row[leg] for row in pattern]
            assert sum(column) == swing
            # One contiguous swing per cycle (counting the wrap-around).
            rises = sum(1 for p in range(ticks) if column[p] and not column[p - 1])
            assert rises == 1


def test_tripod_groups_alternate(tables):
    for gait, _, _, swing, _, _, pattern, _ in tables:
        if gait != 0:
            continue
        for row in pattern:
            up = [leg + 1 for leg in range(6) if row[leg]]
            assert up in ([1, 3, 5], [2, 4, 6])  # seed 000: 1-3-5 swing while 2-4-6 push
        assert [leg + 1 for leg in range(6) if pattern[0][leg]] == [1, 3, 5]
        assert [leg + 1 for leg in range(6) if pattern[swing][leg]] == [2, 4, 6]


def test_ripple_wave_tetrapod_keep_enough_feet_down(tables):
    for gait, _, _, _, _, _, pattern, _ in tables:
        for row in pattern:
            up = [leg for leg in range(6) if row[leg]]
            if gait == 1:  # tetrapod: a diagonal pair at a time, four feet down
                assert sorted(up) in ([0, 3], [1, 4], [2, 5])
            if gait == 2:  # ripple: one leg per side in the air
                assert len(up) == 2 and sum(1 for leg in up if leg < 3) == 1
            if gait == 3:  # wave: one leg at a time
                assert len(up) == 1


def test_wave_and_ripple_run_rear_to_front(tables):
    for gait, _, ticks, _, _, _, pattern, _ in tables:
        if gait not in (2, 3):
            continue
        first = {leg: next(p for p in range(ticks) if pattern[p][leg] and not pattern[p - 1][leg]) for leg in range(6)}
        assert first[2] < first[1] < first[0]  # right: rear, middle, front
        if gait == 3:
            assert first[0] < first[3] < first[4] < first[5]  # then left: rear, middle, front


def test_seed_001_phases(tables):
    # power (stance), then lift, swing, contact in that order, each a third of the swing.
    for _, _, ticks, swing, _, _, pattern, phases in tables:
        for leg in range(6):
            seq = phases[leg]
            start = next(p for p in range(ticks) if pattern[p][leg] and not pattern[p - 1][leg])
            run = [seq[(start + k) % ticks] for k in range(ticks)]
            compact = [run[0]] + [run[k] for k in range(1, ticks) if run[k] != run[k - 1]]
            assert compact == [1, 2, 3, 0]
            assert run.count(1) >= swing // 3 and run.count(3) >= swing // 3


@pytest.mark.parametrize(
    "gait,cycle_ms,message",
    [
        (4, 1000, "gait: 4 is not one of 0 tripod"),
        (-1, 1000, "gait"),
        ("tripod", 1000, "gait"),
        (True, 1000, "gait"),
        (0, 499, "cycle_ms: 499 ms is outside 500..5000"),
        (0, 5001, "cycle_ms"),
        (0, 1000.0, "cycle_ms: need a whole number"),
        (0, None, "cycle_ms"),
    ],
)
def test_bad_gait_settings_are_refused(gait, cycle_ms, message):
    from hexapod.gait import GaitClock

    c = GaitClock(2, 1500)
    with pytest.raises(ValueError, match=message):
        c.set(gait, cycle_ms)
    assert (c.gait, c.cycle_ms) == (2, 1560)  # unchanged


def test_gait_names():
    from hexapod.gait import NAMES, gait_number

    assert [gait_number(n) for n in NAMES] == [0, 1, 2, 3]
    with pytest.raises(ValueError, match="'trot' is not one of tripod, tetrapod, ripple, wave"):
        gait_number("trot")


def test_gait_names_are_written_once_in_the_core():
    # Every other module (firmware, host, tools) takes them from hexapod.gait.NAMES: no string is a
    # gait name, and none lists two of them (a help text's "tripod, tetrapod ..."), outside gait.py.
    import ast
    import os

    from hexapod.gait import NAMES
    from hexapod_host import FIRMWARE, ROOT

    pairs = [a + sep + b for a in NAMES for b in NAMES if a != b for sep in (", ", " or ", " and ")]
    found = []
    for base in (FIRMWARE, os.path.join(ROOT, "host"), os.path.join(ROOT, "tools")):
        for folder, _, files in os.walk(base):
            for f in files:
                path = os.path.join(folder, f)
                if not f.endswith(".py") or path == os.path.join(FIRMWARE, "hexapod", "gait.py"):
                    continue
                with open(path) as fh:
                    tree = ast.parse(fh.read())
                for n in ast.walk(tree):
                    text = n.value if isinstance(n, ast.Constant) and isinstance(n.value, str) else ""
                    if text in NAMES or any(p in text for p in pairs):
                        found.append((os.path.relpath(path, ROOT), n.lineno, text[:60]))
    assert not found, found
