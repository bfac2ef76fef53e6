"""`hexapod bench guard`: what the walker's servo speed guard (hexapod.reach.servo_radii) costs
per configure, and the exhaustive form it must agree with.

`exhaustive_radii` is the guard as first written: every one of the 8 step directions and every
tick pair of the swing solved in full (two IK solves a pair), the same bisection. The core's
guard stops a try at the first tick past the budget, tries the direction that failed last
first, and solves each tick once for both of its pairs; its radii must equal these
(tests/test_servo_guard.py), for a fraction of the IK solves counted here.
"""

import json
import os
import tempfile
import time

from hexapod import reach
from hexapod.leg import OK
from hexapod_host import VM_DIR, mpvm

VM_SCRIPT = os.path.join(VM_DIR, "bench_guard.py")
HEAP = "160k"


def exhaustive_peak(walker, body, leg, i, e, angle, swing, stance, lift):
    """Largest per-tick joint change (cdeg) of leg i's swing stepping e along angle: every tick pair solved twice."""
    u = reach.step_vector(e, angle, swing, stance, [0, 0, 0, 0])
    worst = 0
    tmp = [0, 0]
    buf = [0] * 9
    for t in range(swing):
        for v, at in ((t, 6), (t + 1, 3)):
            reach.swing_point(walker, body, i, u, v, swing, lift, tmp, buf)
            if leg.ik(buf[0], buf[1], buf[2], buf, at) != OK:
                return reach._UNREACHABLE
        worst = max(worst, *(abs(buf[3 + j] - buf[6 + j]) for j in range(3)))
    return worst


def exhaustive_all(walker, body, leg, i, e, swing, stance, lift):
    """The largest per-tick joint change over all 8 directions, each in full."""
    return max(exhaustive_peak(walker, body, leg, i, e, k * 4500, swing, stance, lift) for k in range(8))


def exhaustive_radii(walker, body, swing, stance, lift, limit, caps, out):
    """reach.servo_radii's answer the long way (same arguments, same bisection); returns the no-step peak."""
    legs = walker.geometry.legs
    worst0 = 0
    for i in range(6):
        j0 = exhaustive_peak(walker, body, legs[i], i, 0, 0, swing, stance, lift)
        worst0 = max(worst0, j0)
        if j0 > limit:
            out[i] = 0
            continue
        lo, hi = 0, caps[i]
        if exhaustive_all(walker, body, legs[i], i, hi, swing, stance, lift) <= limit:
            out[i] = hi
            continue
        while hi - lo > 16:
            mid = (lo + hi) >> 1
            if exhaustive_all(walker, body, legs[i], i, mid, swing, stance, lift) <= limit:
                lo = mid
            else:
                hi = mid
        out[i] = lo
    return worst0


class CountingIK:
    """Counts the IK solves of a Geometry's legs while installed (a with block)."""

    def __init__(self, geometry):
        self.legs = geometry.legs
        self.solves = 0

    def __enter__(self):
        for leg in self.legs:
            inner = leg.ik

            def ik(*a, _inner=inner):
                self.solves += 1
                return _inner(*a)

            leg.ik = ik
        return self

    def __exit__(self, *exc):
        for leg in self.legs:
            del leg.ik


def host_rows(geometry, cases):
    """For each (gait, cycle_ms): IK solves and host ms of the core's guard and of the exhaustive form."""
    from hexapod.gait import NAMES, swing_stance_ticks
    from hexapod.tick import FrameBuffer, Robot, default_servos

    robot = Robot(geometry, default_servos(geometry), FrameBuffer())
    w = robot.walker
    body = w.pose_body
    caps = [w.rho[i] if w.rho[i] < w.step else w.step for i in range(6)]
    rows = []
    for gait, cycle in cases:
        swing, stance = swing_stance_ticks(gait, cycle, [0, 0])
        row = {"gait": NAMES[gait], "cycle_ms": cycle, "swing_ticks": swing}
        for name, fn in (("guard", reach.servo_radii), ("exhaustive", exhaustive_radii)):
            out = [0] * 6
            with CountingIK(geometry) as count:
                t0 = time.perf_counter()
                fn(w, body, swing, stance, w.lift, geometry.servo_step, caps, out)
                ms = (time.perf_counter() - t0) * 1000
            row[name] = {"ik_solves": count.solves, "host_ms": round(ms, 1), "radii": out}
        rows.append(row)
    return rows


def bench_guard(args=None):
    """IK solves and time per configure: host CPython (guard and exhaustive), MicroPython VM (guard, .mpy)."""
    import robots.default as robot_file
    from hexapod import geometry as geo
    from hexapod_host.bench.tick import GAIT_HEAP, build_mpy

    g = geo.load(robot_file)
    cases = [(k, g.gait_cycle_ms[k]) for k in range(4)] + [(0, 1600)]
    rows = host_rows(g, cases)
    with tempfile.TemporaryDirectory() as tmp:
        build_mpy(tmp)
        arg = ";".join("%d,%d" % c for c in cases)
        out = mpvm.run(script=VM_SCRIPT, heapsize=GAIT_HEAP, args=(tmp, arg))
    vm = [json.loads(line) for line in out.strip().splitlines() if line.startswith("{")]
    for row, v in zip(rows, vm, strict=True):
        row["guard"]["vm_ms"] = v["ms"]
        row["guard"]["vm_radii_match"] = v["radii"] == row["guard"]["radii"]
    return {"bench": "guard", "servo_step_cdeg": g.servo_step, "heap": HEAP, "rows": rows}
