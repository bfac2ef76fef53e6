"""The viper stage (drivers/_pca9685_viper.py, MicroPython only) writes the very register bytes of
the plain path (CPython), and both the counts of the data sheet's formula, on every pulse width."""

from fractions import Fraction

SETTINGS = [(25000000, 50, 0), (25750000, 50, 500), (24250000, 60, 333), (29000000, 330, 0)]


def test_viper_stage_bytes_equal_the_plain_path_and_the_data_sheet(both_runtimes):
    cp, mp = both_runtimes.call("scenarios.pca9685_viper:stage_counts", SETTINGS)
    assert cp[0] is False and mp[0] is True  # CPython stages in Python, the VM in viper
    assert cp[1:] == mp[1:]  # byte for byte, 4 oscillator and frequency settings x 2001 pulse widths
    for osc, _freq, prescale, counts in cp[1:]:
        for k, (on, off) in enumerate(counts):
            us = 500 + k  # PULSE_MIN_US..PULSE_MAX_US
            exact = Fraction(us * osc, 1000000 * (prescale + 1))  # data sheet: counts = t * osc / (prescale + 1)
            assert off - on == int(exact + Fraction(1, 2)), (osc, us, on, off)  # rounded half up


# ServoBank.write's one-call staging (stage_all) against the plain path: two chips at different
# oscillators, servos on shuffled channels, ServoMaps with their own limits, one swapped and one
# recalibrated between frames; a pulse of 0 (full OFF), pulses at and 1 us past every limit.
LIMITS = [(600 + 40 * k, 2400 - 30 * k) for k in range(18)]
CHANNELS = [(k % 2, (5 * (k // 2)) % 9) for k in range(18)]


def bank_cases():
    import random

    rng = random.Random(7)
    cases = []
    for lo, hi in LIMITS[:6]:
        cases.append([lo - 1, lo, lo + 1, hi - 1, hi, hi + 1] * 3)
    for _ in range(40):
        cases.append([rng.choice((0, rng.randint(500, 2500), rng.randint(-5, 3000))) for _ in range(18)])
    return cases


def test_bank_staging_in_one_viper_call_equals_the_plain_path(both_runtimes):
    cases = bank_cases()
    bad = [True, False, 1500.0, "1500", None, 2**40]
    cp, mp = both_runtimes.call("scenarios.pca9685_viper:bank_frames", LIMITS, CHANNELS, cases, bad)
    assert cp[0] is False and mp[0] is True  # CPython stages in Python, the VM in one viper call
    assert cp[1:] == mp[1:]  # every frame byte for byte, the clamp counts, the refusals
    # The clamp count by hand: pulses outside each ServoMap's limits (0 is no pulse, not clamped).
    limits = list(LIMITS)
    clamped = 0
    for k, p in enumerate(cases):
        if k == 20:
            limits[3] = (1400, 1500)
            limits[5] = (1000, limits[5][1])
        clamped += sum(1 for v, (lo, hi) in zip(p, limits, strict=True) if v and not lo <= v <= hi)
        assert cp[1 + k][1] == clamped, k
    # 2**40 is an int: clamped to its max like any other; True, False, floats, str, None refused.
    refusals = cp[1 + len(cases) :]
    assert [r[0] for r in refusals] == ["ValueError"] * 5 + ["no error"]
    assert all("servo 7" in r[1] and r[2] for r in refusals[:5])  # named, and nothing staged
