"""`hexapod bench ik`: fixed-point vs float six-leg IK inside the MicroPython VM (vm/bench_ik.py)."""

import json
import os

from hexapod_host import VM_DIR, mpvm


def bench_ik(args):
    """Fixed-point vs float six-leg IK inside the MicroPython VM."""
    out = mpvm.run(script=os.path.join(VM_DIR, "bench_ik.py"), heapsize="128k")
    return json.loads(out.strip().splitlines()[-1])
