"""The `hexapod` command line. Each subcommand lives in its own module with register(sub).

Exit status, for every command: 0 all done (every point solved), 1 some refused (unreachable
or beyond a limit), 2 bad input (the message names it and what is allowed), 3 internal error
(a bug: one line on stderr, no traceback unless HEXAPOD_TRACEBACK=1); 141 when the reader
of the output goes away (`| head`), quietly, as for a tool killed by SIGPIPE.
"""

import argparse
import importlib
import os
import sys

# Modules that add subcommands; each defines register(subparsers).
COMMAND_MODULES = (
    "hexapod_host.commands.kin",
    "hexapod_host.commands.bench",
    "hexapod_host.commands.sim",
    "hexapod_host.commands.plot",
    "hexapod_host.commands.flash",
    "hexapod_host.commands.jog",
    "hexapod_host.commands.console",
    "hexapod_host.commands.doctor",
    "hexapod_host.commands.pico",
    "hexapod_host.commands.view",
)


class UsageError(Exception):
    """Bad input from the user: printed as 'hexapod: error: ...' with exit status 2."""


INTERNAL_ERROR = 3
BROKEN_PIPE = 141  # 128 + SIGPIPE, what a shell reports for `yes | head -1`


def version():
    from importlib.metadata import PackageNotFoundError
    from importlib.metadata import version as dist_version

    try:
        return dist_version("hexapod")
    except PackageNotFoundError:
        return "unknown (not installed)"


def build_parser():
    parser = argparse.ArgumentParser(
        prog="hexapod",
        description=__doc__.splitlines()[0],
        epilog="Exit status: 0 all solved, 1 some refused, 2 bad input, 3 internal error (a bug).",
    )
    parser.add_argument("--version", action="version", version="hexapod " + version())
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    for name in COMMAND_MODULES:
        importlib.import_module(name).register(sub)
    return parser


def main(argv=None):
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        status = args.func(args) or 0
        sys.stdout.flush()
        return status
    except UsageError as err:
        parser.exit(2, "hexapod: error: %s\n" % err)
    except BrokenPipeError:
        _quiet_stdout()
        return BROKEN_PIPE
    except KeyboardInterrupt:
        return 130
    except OSError as err:
        if err.filename is not None:  # a file the code named itself: a bug (the user's paths are checked first)
            return _internal(err)
        # stdin, stdout or stderr failed (a directory as input, a full disk as output): the user's redirection
        sys.stderr.write("hexapod: error: input/output: %s\n" % err)
        return 2
    except Exception as err:
        return _internal(err)


def _internal(err):
    """A bug: one line naming the exception, status 3 (HEXAPOD_TRACEBACK=1 shows the traceback)."""
    if os.environ.get("HEXAPOD_TRACEBACK"):
        raise err
    sys.stderr.write("hexapod: internal error: %s: %s (a bug: please report it)\n" % (type(err).__name__, err))
    return INTERNAL_ERROR


def _quiet_stdout():
    """Point stdout at /dev/null, so the interpreter's last flush finds no broken pipe."""
    try:
        fd = sys.stdout.fileno()
    except (AttributeError, OSError, ValueError):
        return
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, fd)
    os.close(devnull)


if __name__ == "__main__":
    sys.exit(main())
