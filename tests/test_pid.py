"""hexapod.pid: seed 000 eq. 14 in integers, step by step against the float form
(hexapod_host.testing.reference.PidFloat), hand-worked cases, both runtimes, bad gains."""

import random

import pytest

from hexapod import pid
from hexapod_host.testing.reference import PidFloat

PAPER = (25000, 500, 1000)  # seed 000: Kp = 25, Ki = 0.5, Kd = 1, in milli-units


def oracle(kp, ki, kd, out_max, i_max):
    return PidFloat(kp / 1000, ki / 1000, kd / 1000, out_max, i_max, pid.E_MAX, pid.TS_MAX_MS)


def sequence(seed, n=400):
    """(setpoint, measurement, now_ms) samples: round-robin intervals, noise, set point steps,
    a stale repeat now and then, a long gap, clock wrap at 2**30."""
    rnd = random.Random(seed)
    t = (1 << 30) - 3000  # wraps early in the run
    sp = 800
    m = 800
    out = []
    for _ in range(n):
        t = (t + rnd.choice((40, 60, 100, 100, 100, 200, 300))) & 0x3FFFFFFF
        if rnd.random() < 0.03:
            t = (t + rnd.randint(1001, 3000)) & 0x3FFFFFFF  # a gap longer than TS_MAX_MS
        if rnd.random() < 0.05:
            sp = rnd.randint(400, 5000)
        m = max(-20000, min(60000, m + rnd.randint(-300, 300) + (sp - m) // 8))
        if rnd.random() < 0.02:
            m = rnd.choice((-20000, 60000, sp + 30000))
        out.append((sp, m, t))
        if rnd.random() < 0.05:
            out.append((sp, m, t))  # the same reading again: must change nothing
    return out


GAINS = [
    (PAPER, 3000, 1000),
    ((60000, 4000, 8000), 3000, 1500),
    ((pid.GAIN_MAX, pid.GAIN_MAX, pid.GAIN_MAX), pid.OUT_LIMIT, pid.OUT_LIMIT),
    ((1, 0, 1), 1, 0),
    ((0, 3000, 0), 9000, 200),
]


@pytest.mark.parametrize("case", range(len(GAINS)))
def test_matches_the_float_form_of_eq_14_step_by_step(case):
    gains, out_max, i_max = GAINS[case]
    worst = 0
    for seed in range(6):
        p = pid.PID(*gains, out_max=out_max, i_max=i_max)
        f = oracle(*gains, out_max, i_max)
        for sp, m, t in sequence(seed * 10 + case):
            u = p.update(sp, m, t)
            v = f.update(sp, m, t)
            worst = max(worst, abs(u - v))
            assert abs(p.i - f.integral) <= 0.5 + 1e-9, (sp, m, t)
    # P, I and D are each rounded once to a whole output unit (bound 1.5); seen: 0.96.
    assert worst <= 1.0, worst


def test_matches_eq_14_as_printed_while_the_set_point_holds():
    """The paper's eq. 14 itself, derivative on the error, at a fixed Ts of 100 ms (the round
    robin's), written out here: u(k) = Kp e(k) + Ki Ts sum e(j) + Kd (e(k) - e(k-1)) / Ts. The
    sum starts at the first interval (the first sample has none: P only)."""
    kp, ki, kd, ts = 25.0, 0.5, 1.0, 0.1
    rnd = random.Random(14)
    p = pid.PID(*PAPER, out_max=9000, i_max=9000)
    m, total, e_last, worst = 800, 0.0, None, 0
    for k in range(300):
        m += rnd.randint(-40, 40) + (800 - m) // 4
        e = 800 - m
        want = kp * e
        if e_last is not None:
            total += e
            want += ki * ts * total + kd * (e - e_last) / ts
        e_last = e
        assert abs(want) < 9000  # no clamp reached: the bare equation
        worst = max(worst, abs(p.update(800, m, 100 * k) - want))
    assert worst <= 1.0, worst


def test_hand_worked_pure_p_step():
    p = pid.PID(25000, 0, 0, out_max=9000, i_max=0)
    # 8 cm set point, 7.6 cm reading: e = 40 (0.1 mm) -> u = 25 * 40 = 1000 cdeg/s.
    assert p.update(800, 760, 0) == 1000 and p.error == 40
    assert p.update(800, 813, 100) == -325  # 25 * -13
    assert p.update(800, 0, 200) == 9000  # e = 800 -> 20000, clamped to out_max
    assert (p.p, p.output) == (20000, 9000)


def test_hand_worked_integral_and_its_clamp():
    p = pid.PID(0, 500, 0, out_max=9000, i_max=30)
    assert p.update(800, 700, 0) == 0  # first sample: no interval, no integral step
    assert p.update(800, 700, 100) == 5  # 0.5 * 0.1 s * 100 = 5
    assert p.update(800, 700, 300) == 15  # + 0.5 * 0.2 s * 100 = 10
    for k in range(4, 10):
        p.update(800, 700, 100 * k)
    assert p.i == 30 and p.output == 30  # 0.5 * 0.9 s * 100 = 45 would be: the clamp holds 30
    assert p.update(800, 900, 1000) == 25  # and it unwinds at once: 30 - 0.5 * 0.1 * 100


def test_hand_worked_derivative_on_the_measurement():
    p = pid.PID(0, 0, 1000, out_max=9000, i_max=0)
    p.update(800, 800, 0)
    # Reading falls 5 mm in 100 ms: -Kd dm/Ts = -1 * (-50) / 0.1 s = +500.
    assert p.update(800, 750, 100) == 500
    # The set point jumps 4 cm with the reading still: no kick (eq. 14's e(k) - e(k-1) would give 4000).
    assert p.update(1200, 750, 200) == 0 and p.d == 0
    assert p.update(1200, 760, 240) == -250  # 10 in 40 ms: -1 * 10 / 0.04 s


def test_a_stale_reading_changes_nothing_and_a_long_gap_restarts():
    p = pid.PID(*PAPER, out_max=9000, i_max=1000)
    p.update(800, 700, 0)
    u = p.update(800, 690, 100)
    state = (p.i, p.d, p.p, p.samples, p.last_ms)
    assert p.update(800, 690, 100) == u and (p.i, p.d, p.p, p.samples, p.last_ms) == state
    i = p.i
    u = p.update(800, 780, 100 + pid.TS_MAX_MS + 1)  # no rate or rectangle over a 1 s gap
    assert p.d == 0 and p.i == i and p.p == 500 and u == 500 + i and p.ts_ms == 0


def test_reset_and_limits():
    p = pid.PID(*PAPER, out_max=3000, i_max=1000)
    for k in range(80):
        p.update(800, 500, 100 * k)  # 0.5 * 0.1 s * 300 = 15 a step: 79 steps would be 1185
    assert p.i == 1000
    p.reset(keep_integral=True)
    assert p.i == 1000 and p.samples == 0
    p.set_limits(3000, 400)
    assert p.i == 400
    p.reset()
    assert (p.i, p.output, p.samples) == (0, 0, 0)


@pytest.mark.parametrize(
    "gains, name",
    [
        ((-1, 0, 0), "kp"),
        ((pid.GAIN_MAX + 1, 0, 0), "kp"),
        ((25.0, 0, 0), "kp"),
        ((True, 0, 0), "kp"),
        (("25", 0, 0), "kp"),
        ((None, 0, 0), "kp"),
        ((0, -5, 0), "ki"),
        ((0, 0.5, 0), "ki"),
        ((0, pid.GAIN_MAX + 1, 0), "ki"),
        ((0, 0, -1), "kd"),
        ((0, 0, 10**9), "kd"),
        ((0, 0, [1]), "kd"),
    ],
)
def test_bad_gains_are_refused_and_change_nothing(gains, name):
    p = pid.PID(*PAPER)
    with pytest.raises(ValueError, match=name + ": .* is outside 0..100000"):
        p.set_gains(*gains)
    assert (p.kp, p.ki, p.kd) == PAPER


@pytest.mark.parametrize("limits", [(0, 0), (9001, 0), (3000, -1), (3000, 3001), (3000.0, 0), (3000, None)])
def test_bad_limits_are_refused(limits):
    p = pid.PID(*PAPER, out_max=3000, i_max=1000)
    with pytest.raises(ValueError, match="out_max|i_max"):
        p.set_limits(*limits)
    assert (p.out_max, p.i_max) == (3000, 1000)


def test_both_runtimes_bit_identical(both_runtimes):
    seq = sequence(99, 300)
    cp, mp = both_runtimes.call("scenarios.pid:updates", GAINS, seq)
    assert cp == mp and len(cp) == 2 * len(GAINS) * len(seq)
