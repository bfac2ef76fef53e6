"""`hexapod bench ik --json` runs in the VM and reports what the issue asks for (no timing asserts)."""

import json
import os
import subprocess
import sys

HEXAPOD = os.path.join(os.path.dirname(sys.executable), "hexapod")


def test_bench_ik_json(mp):
    proc = subprocess.run([HEXAPOD, "bench", "ik", "--json"], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    result = json.loads(proc.stdout)
    for key in ("fixed_us", "float_us", "fixed_bytes", "float_bytes", "ratio", "plain_us"):
        assert key in result, key
    assert result["fixed_bytes"] == 0 and result["plain_bytes"] == 0
    assert result["float_bytes"] > 0  # a MicroPython float is a heap object
    assert result["max_diff_cdeg"] <= 1  # both solvers answered the same feet
    assert abs(result["ratio"] - result["fixed_us"] / result["float_us"]) < 0.01


def test_bench_unknown_name_is_a_usage_error():
    proc = subprocess.run([HEXAPOD, "bench", "nope"], capture_output=True, text=True, timeout=60)
    assert proc.returncode == 2 and "no benchmark 'nope'" in proc.stderr
