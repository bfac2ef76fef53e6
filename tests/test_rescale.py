"""Walker._rescale (one function, roots only for a foot that is over, compared as squares) equals
the plain form it replaced (one half_stance and one _outward call per leg per try, kept as the
reference in tests/scenarios/rescale.py) exactly: scale, command, stance discs and the aim/scratch it
leaves, on CPython, the MicroPython VM and the emulated Pico, over random commands, gaits, cycle
times, steps, reach and servo-speed discs (some zero, some tiny) and outward limits (off, tight, loose).
"""

import ast

import pytest
from scenarios import on_board

from hexapod_host.pico import emulator as pico


def check(result, cases):
    (count, slowed, far, turned, many, zero, differ), samples = result
    assert count == cases
    # Every branch: scaled by the discs, by the outward limit, by the turn bound, after three or
    # more tries, down to nothing (a zero disc).
    assert cases // 3 < slowed < cases - cases // 20, result
    assert far > cases // 50 and turned > cases // 50 and many > cases // 20 and zero > cases // 50, result
    assert differ == 0 and samples == [], result


@pytest.mark.parametrize("fast", [1, 0])
def test_rescale_equals_the_plain_form_in_both_runtimes(both_runtimes, fast):
    # The VM runs the viper rescale (fast) or the bytecode one; CPython always the bytecode one.
    cp, mp = both_runtimes.call("scenarios.rescale:rescales", 3000, bool(fast))
    assert cp == mp
    check(cp, 3000)


def test_the_vm_uses_the_viper_rescale(mp):
    assert mp.call("scenarios.rescale:rescale_fast").startswith("<function")


def pico_calls(fs, *calls):
    """The values `print(repr(scenarios.rescale.<call>))` prints on the emulated Pico, one per call, all
    in one boot and one import (each boot and each import of the scenario, compiled from source
    on the board, costs ~40 M emulated instructions: ~4 s of the host's CPU). A raw script: the
    emulator runs files, not calls."""
    source = "import scenarios.rescale as s\n" + "".join("print(repr(s.%s))\n" % call for call in calls)
    status, out, err, _ = pico.run_source(source, fs=fs, timeout=900)
    assert status == 0, out + err
    lines = out.strip().splitlines()
    assert len(lines) == len(calls), out
    return [ast.literal_eval(line) for line in lines]


@pytest.mark.skipif(pico.missing() is not None, reason=pico.missing() or "")
def test_rescale_equals_the_plain_form_on_the_emulated_pico():
    with pico.flashed(extra=on_board("lcg.py", "rescale.py")) as fs:
        rescaled, aimed, sined, rooted = pico_calls(
            fs, "rescales(300, True)", "aims(1000)", "sines(3000)", "roots(3000)"
        )
    check(rescaled, 300)
    count, odd, differ = aimed
    assert count == 1000 and odd > 100 and differ == 0, aimed
    assert sined == (3000, 0, True)
    assert rooted[0] > 20000 and rooted[1:] == (0, True), rooted  # on Thumb: 32-bit machine words


def test_aim_equals_the_plain_form_in_both_runtimes(both_runtimes):
    cp, mp = both_runtimes.call("scenarios.rescale:aims", 5000)
    assert cp == mp
    count, odd, differ = cp
    assert count == 5000 and odd > 500 and differ == 0, (count, odd, differ)


# hexapod/_fixmath_viper.py's sin (walk's sine on a MicroPython with viper) against fixmath.sin, over
# every table step and its edges, both signs, whole turns away, up to the 2**29 the docstrings allow.
def test_viper_sine_equals_fixmath_on_the_vm(mp):
    assert mp.call("scenarios.rescale:sines", 20000) == (20000, 0, True)


# hexapod/_fixmath_viper.py's isqrt (gaitswitch's and stability's root on a MicroPython with viper: the
# rooms and the support margin of a gait change on the move, in the tick) and fixmath's: the floor root.
def test_isqrt_is_the_floor_root_in_both_runtimes_and_viper_in_the_vm(both_runtimes):
    cp, mp = both_runtimes.call("scenarios.rescale:roots", 20000)
    assert cp[1:] == (0, False) and mp[1:] == (0, True), (cp, mp)
    assert cp[0] == mp[0] > 150000  # both roots on every n (CPython runs the twin's source as Python)


# Walker.command checks its own input unless told its caller just did (Robot.walk, which checks
# first so that a bad command raises whatever the robot's mode): bad input raises and changes nothing.
def test_walker_command_refuses_bad_input_and_changes_nothing(both_runtimes):
    bad = [(True, 0, 0), (1.5, 0, 0), (3001, 0, 0), (0, -3001, 0), (0, "1", 0), (0, 0, 9001), (0, 0, None)]
    cp, mp = both_runtimes.call("scenarios.rescale:bad_commands", bad)
    assert cp == mp
    assert cp == ["vx", "vx", "vx", "vy", "vy", "yaw_rate", "yaw_rate", True]
