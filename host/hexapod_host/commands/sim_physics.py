"""`hexapod sim physics`: the options checked, the walk simulated in MuJoCo (hexapod_host.physics.sim),
the results printed (a report, a table or JSON)."""

import json
import math
import sys

from hexapod import robotfile
from hexapod.gait import NAMES, TRIPOD, gait_number
from hexapod_host import drives
from hexapod_host.commands import checks
from hexapod_host.commands.cli import UsageError
from hexapod_host.drives import runs
from hexapod_host.physics.sim import TABLE_GAITS, format_table, report, simulate, table


def parse_servo_spec(text):
    """'key=value,key=value' (SERVO keys, integers) -> dict; ValueError names the bad part."""
    out = {}
    names = [f[0] for f in robotfile.SERVO_FIELDS]
    for part in text.split(","):
        part = part.strip()
        if not part:
            continue
        key, eq, value = part.partition("=")
        key = key.strip()
        if not eq or key not in names:
            raise ValueError("--servo: %r is not KEY=INTEGER with KEY one of %s" % (part, ", ".join(names)))
        try:
            out[key] = int(value)
        except ValueError:
            raise ValueError("--servo: %s=%r is not a whole number" % (key, value.strip())) from None
    return out


def register(sub):
    p = sub.add_parser("physics", help="the core's frames drive a MuJoCo model of the robot file; measured motion")
    p.add_argument(
        "--gait",
        default=NAMES[TRIPOD],
        help="%s (default %s); with --commands also all" % (", ".join(NAMES), NAMES[TRIPOD]),
    )
    p.add_argument("--speed", type=float, default=None, help="mm/s along --direction (negative: backward); default 60")
    p.add_argument("--direction", type=float, default=None, help="deg from forward, counter-clockwise (90 = left)")
    p.add_argument("--turn", type=float, default=None, help="yaw rate, deg/s, positive = left")
    p.add_argument(
        "--seconds", type=float, default=None, help="simulated time (0.6 s + a cycle settle first); default 6"
    )
    p.add_argument(
        "--commands",
        metavar="FILE",
        default=None,
        help="play a driver's command stream (JSON lines, docs/motion.md; or a shipped one: %s) from --gait"
        % ", ".join(drives.NAMES),
    )
    p.add_argument("--cycle", type=int, default=None, help="gait cycle, ms (default: the gait's own)")
    p.add_argument("--servo", default="", help="SERVO overrides, KEY=INT,...: e.g. stall_torque_mnm=1500")
    p.add_argument("--render", metavar="DIR", default=None, help="write PNG frames and walk.gif here")
    p.add_argument("--json", action="store_true", help="print the results as JSON")
    p.add_argument(
        "--table",
        action="store_true",
        help="%s at 60, 120 mm/s and turning 30 deg/s (8 s each, on every core): a table" % ", ".join(TABLE_GAITS),
    )
    p.set_defaults(func=main)


DEFAULTS = {"speed": 60.0, "direction": 0.0, "turn": 0.0, "seconds": 6.0}


def check_args(args):
    """UsageError for any bad option value, before anything runs."""
    if args.commands is not None:
        for name in ("speed", "direction", "turn", "seconds", "render"):
            if getattr(args, name) is not None:
                raise UsageError("--%s: not with --commands (the stream says what to walk, and for how long)" % name)
        if args.table:
            raise UsageError("--table: not with --commands")
    for name, value in DEFAULTS.items():
        if getattr(args, name) is None:
            setattr(args, name, value)
    try:
        if args.commands is None or args.gait != "all":
            gait_number(args.gait)
        servo = parse_servo_spec(args.servo)
    except ValueError as err:
        raise UsageError(str(err)) from None
    for name, v, lo, hi in (
        ("--speed", args.speed, -300.0, 300.0),
        ("--turn", args.turn, -90.0, 90.0),
        ("--seconds", args.seconds, 2.0, 600.0),
        ("--direction", args.direction, -180.0, 180.0),
    ):
        if not math.isfinite(v) or v < lo or v > hi:
            raise UsageError("%s: %r is outside %g..%g" % (name, v, lo, hi))
    if args.render is not None:
        checks.out_dir("--render", args.render)
    return servo


def main(args):
    servo = check_args(args)
    if args.commands is not None:
        return play_stream(args, servo)
    if args.table:
        rows = table(servo=servo, cycle_ms=args.cycle, progress=sys.stderr.isatty() and not args.json)
        print(json.dumps(rows, indent=1) if args.json else format_table(rows))
        return 0
    try:
        res = simulate(
            gait=args.gait,
            speed=args.speed,
            direction=args.direction,
            turn=args.turn,
            seconds=args.seconds,
            cycle_ms=args.cycle,
            servo=servo,
            render=args.render,
            progress=sys.stderr.isatty() and not args.json,
        )
    except ValueError as err:
        raise UsageError(str(err)) from None
    if args.json:
        print(json.dumps(res, indent=1))
    else:
        print(report(res))
    return 0


def play_stream(args, servo):
    """--commands: the stream checked in full, then played on each gait asked (docs/motion.md)."""
    try:
        commands = drives.load(args.commands)
    except drives.StreamError as err:
        raise UsageError(str(err)) from None
    gaits = runs.gaits(args.gait)
    progress = sys.stderr.isatty() and not args.json
    try:
        if len(gaits) == 1:
            from hexapod_host.physics.drive import play

            tick_bar = (
                (lambda k, n: runs.bar(k + 1, n, "ticks") if k % 25 == 0 or k == n - 1 else None) if progress else None
            )
            results = [play(commands, gaits[0], servo=servo, on_tick=tick_bar)]
        else:
            results = runs.run_all([("physics", commands, g, servo) for g in gaits], progress)
    except ValueError as err:
        raise UsageError(str(err)) from None
    for r in results:
        r["stream"] = args.commands
    if args.json:
        print(json.dumps(results[0] if len(results) == 1 else results, indent=1))
    else:
        print(runs.report(results))
    return 0
