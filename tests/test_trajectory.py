"""Seed 003's swing trajectory (eq. 12-14): Table III exactly, in both runtimes, and the gait's swing.

The firmware side is tests/scenarios/trajectory.py."""

import math

# Table III (s = 5, x = 2, y = 0, z = 2; cm, six decimals), rows in the paper's order.
TABLE_III = [
    (0, 0, 0, 2),
    (1, 0.618034, 0, 1.902113),
    (2, 1.175571, 0, 1.618034),
    (3, 1.618034, 0, 1.175571),
    (4, 1.902113, 0, 0.618034),
    (5, 2, 0, 0),
    (4, 1.902113, 0, 0),
    (3, 1.618034, 0, 0),
    (2, 1.175571, 0, 0),
    (1, 0.618034, 0, 0),
    (0, 0, 0, 0),
    (-1, -0.618034, 0, 0),
    (-2, -1.175571, 0, 0),
    (-3, -1.618034, 0, 0),
    (-4, -1.902113, 0, 0),
    (-5, -2, 0, 0),
    (-4, -1.902113, 0, 0.618034),
    (-3, -1.618034, 0, 1.175571),
    (-2, -1.175571, 0, 1.618034),
    (-1, -0.618034, 0, 1.902113),
    (0, 0, 0, 2),
]


def test_table_iii_exact_in_integers(rt):
    rows = rt.call("scenarios.trajectory:table_iii", 21, 5)
    assert len(rows) == len(TABLE_III)
    for row, (t, fx, fy, fz) in zip(rows, TABLE_III, strict=True):
        assert row[0] == t
        # Integer trajectory at 1e-6 cm: every digit of the table.
        assert row[1:4] == [round(fx * 1e6), round(fy * 1e6), round(fz * 1e6)]
        # The tick's precision (Q15 sine) at 0.1 mm: the table rounded to 0.1 mm.
        assert row[4:7] == [round(fx * 100), round(fy * 100), round(fz * 100)]


def test_table_iii_float_form():
    from hexapod.trajectory import combined_step
    from hexapod_host.testing.reference import track_point as track_point_float

    step = [0, 0]
    for k, (t, fx, fy, fz) in enumerate(TABLE_III):
        combined_step(k, 5, step)
        assert step[0] == t
        x, y, z = track_point_float(t, 5, 2.0, 0.0, 2.0 if step[1] else 0.0)
        assert (round(x, 6), round(y, 6) + 0.0, round(z, 6)) == (fx, fy, fz)


def test_heading_form_splits_the_step_like_the_paper(rt):
    # Seed 003: x = L cos(theta), y = L sin(theta); eq. 12-13 then scale both the same way.
    rows = rt.call("scenarios.trajectory:heading", [0, 1500, 4500, 9000, -3000, 18000], 400, 300)
    assert len(rows) == 6
    for theta, x, y, fx, fy, fz in rows:
        assert abs(x - 400 * math.cos(math.radians(theta / 100))) <= 1
        assert abs(y - 400 * math.sin(math.radians(theta / 100))) <= 1
        assert (fx, fy, fz) == (x, y, 0)  # t = s: the full step, foot on the ground


def test_fine_sine_against_math(rt):
    cases = [(t, s) for s in (1, 3, 7, 90, 1000) for t in range(-s, s + 1, max(1, s // 7))]
    got = rt.call("scenarios.trajectory:fine_sines", cases)
    want = [round(math.sin(math.radians(t * 90 / s)) * 2**40) for t, s in cases]
    assert max(abs(a - b) for a, b in zip(got, want, strict=True)) <= 1


def test_swing_shape(rt):
    rows = rt.call("scenarios.trajectory:shapes", [4, 12, 25, 50])
    assert [len(shape) for shape in rows] == [5, 13, 26, 51]
    for shape in rows:
        w = len(shape) - 1
        assert shape[0] == [0, 0] and shape[-1] == [32768, 0]
        fwd = [p[0] for p in shape]
        up = [p[1] for p in shape]
        assert fwd == sorted(fwd)  # the foot only moves forward during a swing
        assert max(up) == up[w // 2] and up[w // 2] >= 32768 * 0.97
        # Smooth touch-down: one tick before landing, eq. 14 alone would still be at
        # sin(180/w); squared, the foot is already that factor lower (zero landing speed).
        eq14_last = 32768 * math.sin(math.radians(180 / w))
        assert up[w - 1] <= eq14_last * math.sin(math.radians(180 / w)) + 2
        assert up[w - 1] < eq14_last
        assert up[1] == up[w - 1]


def test_swing_stroke(rt):
    rows = rt.call("scenarios.trajectory:strokes", [4, 8, 25, 50, 208])
    assert [len(shape) for shape in rows] == [5, 9, 26, 51, 209]
    for shape in rows:
        w = len(shape) - 1
        for u, (stroke, carry) in enumerate(shape):
            # Float oracle: eq. 12/13's (1 + sin) / 2 over ticks 1..w-1; none on the first
            # and last tick (those move the foot with the stance only).
            k, n = u - 1, w - 2
            want = 0.0 if k <= 0 else 1.0 if k >= n else (1 + math.sin(math.radians((2 * k - n) * 90 / n))) / 2
            assert abs(stroke - want * 32768) <= 2, (w, u)
            assert carry == (u * 32768) // w
        assert shape[1][0] == 0 and shape[w - 1][0] == 32768
