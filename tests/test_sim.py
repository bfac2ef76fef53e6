"""`hexapod sim kinematics` (the leg demo) runs, round-trips, and agrees across runtimes; `hexapod sim` alone
runs the default kind (the wall experiment, tests/test_wall_sim.py)."""

import os
import subprocess
import sys

HEXAPOD = os.path.join(os.path.dirname(sys.executable), "hexapod")


def test_sim_demo(mp):
    proc = subprocess.run([HEXAPOD, "sim", "kinematics"], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    lines = proc.stdout.splitlines()
    assert "worst FK round-trip error: 0.0 mm" in lines
    assert lines[-1] == "MicroPython VM: identical integers"
    rows = [line for line in lines if line.strip()[:1].isdigit()]
    assert len(rows) == 21 and not any("unreachable" in r for r in lines)
    for row in rows:
        pulses = [int(v) for v in row.split()[6:9]]
        assert all(600 <= p <= 2400 for p in pulses), row
    # Every number's last character sits under its heading's last character.
    heads = lines[2]
    assert heads.split() == ["x", "y", "z", "theta1", "theta2", "theta3", "coxa", "femur", "tibia", "x", "y", "z"]
    for row in rows:
        assert ends(row) == ends(heads), row


def ends(line):
    return [k for k in range(len(line)) if line[k] != " " and (k + 1 == len(line) or line[k + 1] == " ")]


def test_sim_alone_is_the_default_kind():
    from hexapod_host.commands import sim as cmd_sim

    proc = subprocess.run([HEXAPOD, "sim", "--help"], capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0 and cmd_sim.DEFAULT in proc.stdout
    proc = subprocess.run([HEXAPOD, "sim", "no-such-kind"], capture_output=True, text=True, timeout=60)
    assert proc.returncode == 2 and "invalid choice" in proc.stderr
