"""The `hexapod` command line. Each subcommand lives in its own module with register(sub)."""

import argparse
import importlib
import sys

# Modules that add subcommands; each defines register(subparsers).
COMMAND_MODULES = (
    "hexapod_host.cmd_kin",
    "hexapod_host.cmd_bench",
    "hexapod_host.cmd_sim",
    "hexapod_host.cmd_plot",
    "hexapod_host.cmd_pico",
)


class UsageError(Exception):
    """Bad input from the user: printed as 'hexapod: error: ...' with exit status 2."""


def build_parser():
    parser = argparse.ArgumentParser(prog="hexapod", description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    for name in COMMAND_MODULES:
        importlib.import_module(name).register(sub)
    return parser


def main(argv=None):
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args.func(args) or 0
    except UsageError as err:
        parser.exit(2, "hexapod: error: %s\n" % err)


if __name__ == "__main__":
    sys.exit(main())
