"""A command stream on the kinematic walker, in the MicroPython VM or on CPython (the same source,
hexapod_host/vm/drive_play.py; the integers it prints are compared, the figures made here from them)."""

import contextlib
import io
import math
import os

import robots.default as default_robot
from hexapod import geometry
from hexapod.body import FINE
from hexapod.gait import NAMES, TICK_MS
from hexapod_host import mpvm
from hexapod_host.drives import metrics

SCRIPT = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "vm", "drive_play.py")
NO_SUPPORT = -1000000  # hexapod.stability's: fewer than three feet down


def end_ticks(commands, gait):
    """How many ticks a stream plays: to its last line, then one cycle of the gait in force (a stop
    lands every foot within it)."""
    for c in commands:
        if c[5] >= 0:
            gait = c[5]
    end_ms = commands[-1][1] + default_robot.GAIT_CYCLE_MS[gait]
    return (end_ms + TICK_MS - 1) // TICK_MS + 1


def source(commands, gait, ticks):
    """The player's source with its inputs in front (plain literals: the same text on both runtimes)."""
    with open(SCRIPT) as f:
        body = f.read()
    rows = [tuple(c) for c in commands]
    return "COMMANDS = %r\nGAIT = %d\nTICKS = %d\n%s" % (rows, gait, ticks, body)


def run_source(text, runtime):
    """The player's printed lines, run in the VM ('micropython') or here ('cpython')."""
    if runtime == "micropython":
        return mpvm.run(text, timeout=600)
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(text, SCRIPT, "exec"), {"__name__": "__main__"})
    return out.getvalue()


def parse_output(text):
    """The player's lines -> (tick rows of ints, refusals [(line, what, code)], frame fault codes)."""
    rows, refused, faults = [], [], []
    ended = False
    for line in text.splitlines():
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "T":
            rows.append([int(v) for v in parts[1:]])
        elif parts[0] == "R":
            refused.append((int(parts[1]), parts[2], int(parts[3])))
        elif parts[0] == "F":
            faults.append(int(parts[1]))
        elif parts[0] == "E":
            ended = True
    if not ended:
        raise RuntimeError("the player stopped early:\n" + text[-500:])
    return rows, refused, faults


def records(rows):
    """The player's tick rows -> metrics records (mm, deg, the body's move turned into its own frame)."""
    out = []
    for held, dbx, dby, dpsi, psi, vx, vy, yaw, gait, margin in rows:
        mid = math.radians((psi + dpsi / 2) / 10000.0)
        gx, gy = dbx / FINE / 10.0, dby / FINE / 10.0
        dx = math.cos(mid) * gx + math.sin(mid) * gy
        dy = -math.sin(mid) * gx + math.cos(mid) * gy
        m = None if margin == NO_SUPPORT else margin / 10.0
        out.append((held, vx / 10.0, vy / 10.0, yaw / 100.0, dx, dy, dpsi / 10000.0, gait, m))
    return out


def play(commands, gait=0, runtime="micropython"):
    """The stream's figures on the kinematic walker (metrics.summarise, plus refusals and faults);
    also the raw integer rows under "_rows" (for comparing runtimes)."""
    ticks = end_ticks(commands, gait)
    rows, refused, faults = parse_output(run_source(source(commands, gait, ticks), runtime))
    res = metrics.summarise(records(rows), metrics.foot_radius_mm(geometry.load(default_robot)))
    unsupported = sum(1 for r in rows if r[9] == NO_SUPPORT)
    res.update(
        model="kinematic",
        runtime=runtime,
        gait=NAMES[gait],
        seconds=round(ticks * TICK_MS / 1000.0, 2),
        unsupported_ticks=unsupported,
        peak_torque_share=None,
        saturated_share=None,
        max_tilt_deg=None,
        frame_faults=len(faults),
        refused=[{"line": ln, "what": what, "code": code} for ln, what, code in refused],
        _rows=rows,
    )
    return res
