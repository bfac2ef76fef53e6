"""`hexapod flash --board B --port PORT | --drive PATH [--robot R] [--dry-run] [--verbose]`: put the firmware on
a board.

--dry-run prints the whole plan (every mpy-cross and mpremote command, or every copy onto the CIRCUITPY
drive and the circup command; PORT when no --port is given) and touches no board; a real flash prints
its steps as they run, and with --verbose every command too. docs/flashing.md.
"""

import os
import shlex

from hexapod_host.commands import checks
from hexapod_host.commands.cli import UsageError
from hexapod_host.serial import flash


def register(sub):
    p = sub.add_parser("flash", help="compile, copy what changed onto a board, reset (docs/flashing.md)")
    p.add_argument("--board", required=True, help="board file: " + ", ".join(flash.boards()))
    p.add_argument("--port", help="serial port of a MicroPython board (e.g. /dev/ttyACM0, COM3)")
    p.add_argument("--drive", help="the CIRCUITPY drive of a CircuitPython board (e.g. /media/$USER/CIRCUITPY)")
    p.add_argument("--robot", default="default", help="robot file (default: default): " + ", ".join(flash.robots()))
    p.add_argument("--dry-run", action="store_true", help="print the plan; compile into build/ but touch no board")
    p.add_argument("--full", action="store_true", help="copy every file, whatever the board's manifest says")
    p.add_argument(
        "--verbose", "-v", action="store_true", help="print every command of a real flash (a dry run always does)"
    )
    p.add_argument("--stage-dir", metavar="DIR", help="where the image is built (default: build/flash/BOARD)")
    p.add_argument(
        "--manifest-from",
        metavar="FILE",
        help="dry run: plan against this copy of the board's hexapod.manifest instead of a fresh board",
    )
    p.set_defaults(func=run)


def check_args(args):
    """UsageError naming the bad value; returns the board's runtime."""
    if args.board not in flash.boards():
        raise UsageError("no board %r; allowed: %s" % (args.board, ", ".join(flash.boards())))
    if args.robot not in flash.robots():
        raise UsageError("no robot %r; allowed: %s" % (args.robot, ", ".join(flash.robots())))
    rt = flash.runtime(args.board)
    if rt == "circuitpython":
        if not args.drive:
            raise UsageError("board %r runs CircuitPython: give its drive with --drive PATH (CIRCUITPY)" % args.board)
        if not os.path.isdir(args.drive):
            raise UsageError("drive %r: no such directory (is the CIRCUITPY drive mounted?)" % args.drive)
    else:
        if not args.port and not args.dry_run:  # a dry run's plan says PORT
            raise UsageError("board %r runs MicroPython: give its serial port with --port PORT" % args.board)
        if not args.dry_run and os.sep in args.port and not os.path.exists(args.port):
            raise UsageError("no such port %r (list ports with `mpremote connect list`)" % args.port)
    if args.stage_dir:
        # staging replaces the directory whole: only a new, empty or earlier stage's (its core package there)
        d = args.stage_dir
        if os.path.isdir(d) and os.listdir(d) and not os.path.isdir(os.path.join(d, "hexapod")):
            raise UsageError("--stage-dir: %r holds other files and staging replaces it: give a new or empty one" % d)
        checks.out_dir("--stage-dir", d)
    if args.manifest_from and not os.path.isfile(args.manifest_from):
        raise UsageError("--manifest-from %r: no such file" % args.manifest_from)
    return rt


def run(args):
    rt = check_args(args)
    try:
        return (flash_circuitpython if rt == "circuitpython" else flash_micropython)(args)
    except flash.FlashError as err:
        print("hexapod flash: error: %s" % err)
        return 1


def flash_micropython(args):
    staged = args.stage_dir or os.path.join(flash.ROOT, "build", "flash", args.board)
    port = args.port or "PORT"
    print(
        "# flash %s (MicroPython, %s), robot %s, staged in %s"
        % (args.board, flash.board_arch(args.board), args.robot, staged)
    )
    commands, image, _ = flash.stage(args.board, args.robot, staged)
    if args.dry_run or args.verbose:
        print("# compile")
        for cmd in commands:
            print(shlex.join(cmd))
    else:  # a real flash: the steps, not their ~80 lines of commands and embedded Python
        print("# compiled %d files with mpy-cross (--verbose prints every command)" % len(commands))
    if not args.dry_run:
        copied = flash.flash_micropython(args.port, staged, image, full=args.full, verbose=args.verbose)
        print("flashed %s on %s: %d of %d files copied" % (args.board, args.port, len(copied), len(image)))
        print(flash.after_reset(args.board))
        return 0
    if not args.port:
        print("# no --port given: PORT below stands for the board's serial port (hexapod ports lists them)")
    print("# probe the board: runtime, free space, its manifest")
    print(shlex.join(flash.probe_command(port)))
    on_board = {}
    if args.manifest_from and not args.full:
        with open(args.manifest_from) as f:
            on_board = flash.parse_manifest(f.read())
        print("# planned against %s (%d files)" % (args.manifest_from, len(on_board)))
    else:
        print("# planned for a board without a manifest (everything is copied)")
    copy, stale = flash.changes(image, on_board)
    print("# %d of %d files changed: %s" % (len(copy), len(image), " ".join(copy) or "none"))
    for what, cmd in flash.micropython_plan(port, staged, copy, stale):
        print("# " + what)
        print(shlex.join(cmd))
    print("# dry run: the board was not touched; " + flash.after_reset(args.board))
    return 0


def flash_circuitpython(args):
    staged = args.stage_dir or os.path.join(flash.ROOT, "build", "flash", args.board)
    print("# flash %s (CircuitPython, .py files), robot %s, staged in %s" % (args.board, args.robot, staged))
    _, image, libs = flash.stage(args.board, args.robot, staged)
    copy = list(image) if args.full else flash.drive_changes(args.drive, staged, image)
    print("# %d of %d files changed on %s: %s" % (len(copy), len(image), args.drive, " ".join(copy) or "none"))
    if args.dry_run or args.verbose:
        for p in copy:
            dest = os.path.join(args.drive, p.replace("/", os.sep))
            print(shlex.join(["cp", os.path.join(staged, p.replace("/", os.sep)), dest + flash.NEW]))
        for p in copy:
            dest = os.path.join(args.drive, p.replace("/", os.sep))
            print(shlex.join(["mv", dest + flash.NEW, dest]))
    elif copy:
        print("# copy them under temporary names, then rename each into place (--verbose prints every command)")
    circup = flash.circup_command(args.drive, libs)
    print("# Adafruit libraries (needs the network)")
    print(shlex.join(circup))
    if args.dry_run:
        print("# dry run: the drive was not touched")
        return 0
    flash.flash_drive(args.drive, staged, copy)
    status, out = flash.run(circup, timeout=300)
    if status:
        print(
            "hexapod flash: error: circup could not install %s (%s); the firmware files landed; once online run:\n  %s"
            % (" ".join(libs), (out.strip().splitlines() or ["no output"])[-1], shlex.join(circup))
        )
        return 1
    print(
        "flashed %s on %s: %d of %d files copied, libraries: %s"
        % (args.board, args.drive, len(copy), len(image), " ".join(libs))
    )
    print(flash.after_reset(args.board).replace("after its reset", "when CircuitPython restarts code.py"))
    return 0
