"""fixmath: the literal tables, and each function's error bound against CPython's math."""

import math
import random
import sys

from hexapod import fixmath

sys.path.insert(0, "tools")
import gen_tables  # noqa: E402


def test_tables_are_the_generated_ones():
    assert gen_tables.atan_table() == fixmath._ATAN
    assert gen_tables.sin_table() == fixmath._SIN


def test_isqrt_is_the_floor_root_everywhere_it_is_used():
    rnd = random.Random(1)
    cases = list(range(0, 70000)) + [(1 << 30) - 1, (1 << 28), (1 << 28) - 1]
    cases += [rnd.randrange(1 << 30) for _ in range(100000)]
    cases += [k * k + d for k in range(0, 32768, 97) for d in (-1, 0, 1) if k * k + d >= 0]
    for n in cases:
        assert fixmath.isqrt(n) == math.isqrt(n), n


def test_atan2_within_two_thousandths_of_a_degree():
    rnd = random.Random(2)
    worst = 0.0
    pts = [(0, 1), (0, -1), (1, 0), (-1, 0), (1, 1), (-1, -1), ((1 << 30) - 1, 1), (1, -(1 << 30) + 1)]
    for _ in range(100000):
        pts.append(
            (
                rnd.randint(-(1 << 30) + 1, (1 << 30) - 1) >> rnd.randint(0, 29),
                rnd.randint(-(1 << 30) + 1, (1 << 30) - 1) >> rnd.randint(0, 29),
            )
        )
    for y, x in pts:
        if x == 0 and y == 0:
            continue
        got = fixmath.atan2(y, x)
        assert -1800000 < got <= 1800000
        err = abs(got / fixmath.ANGLE_UNIT - math.degrees(math.atan2(y, x)))
        worst = max(worst, min(err, 360 - err))
    assert worst <= 0.002, worst
    assert fixmath.atan2(0, -5) == 1800000 and fixmath.atan2(0, 0) == 0


def test_sin_and_cos_within_one_and_a_bit_q15_steps():
    for c in range(-72000, 72001, 7):
        assert abs(fixmath.sin(c) - math.sin(math.radians(c / 100)) * 32768) <= 1.1
        assert abs(fixmath.cos(c) - math.cos(math.radians(c / 100)) * 32768) <= 1.1
    assert fixmath.sin(9000) == 32768 and fixmath.cos(0) == 32768 and fixmath.sin(18000) == 0


def test_mul_q15_rounds_like_the_exact_product():
    rnd = random.Random(3)
    for _ in range(50000):
        a = rnd.randint(-(1 << 29) + 1, (1 << 29) - 1)
        q = rnd.randint(-32768, 32768)
        assert abs(fixmath.mul_q15(a, q) - a * q / 32768) <= 1


def test_to_cdeg_rounds_half_up():
    assert [fixmath.to_cdeg(v) for v in (0, 49, 50, 149, 150, -49, -50, -51)] == [0, 0, 1, 1, 2, 0, 0, -1]


def test_fixmath_bit_identical_in_both_runtimes(both_runtimes):
    cp, mp = both_runtimes.call("scenarios.fixmath:vectors", 3000)
    assert len(cp) == 3000
    assert cp == mp
