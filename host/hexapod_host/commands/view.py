"""`hexapod view --sim [--world W] | --virtual [--virtual-port PTY] | --pico [--sonar-cm CM...] |
--port PORT | --replay FILE.mcap [--world W] [--record FILE.mcap] [--listen HOST:PORT] [--no-browser]`:
the live 3-D page (hexapod_host.view, docs/view.md)."""

import os
import sys

from hexapod_host.commands.cli import UsageError
from hexapod_host.commands.sim_wall import _number, _whole
from hexapod_host.view import player as player_mod
from hexapod_host.wall.world import DEFAULT, WorldError, load, shipped

LISTEN = "127.0.0.1:8080"
# Hang guards only, never a pace: the emulated Pico runs 10-20 times slower than real time on a
# loaded 2-core machine (main.py's ~4 emulated s of boot: one to several minutes of wall time).
PICO_BOOT_S = 900
PICO_REPLY_S = 120
# The 3-D scene's frame rate (NiceGUI's own default is 20). Without a GPU (SwiftShader) each redraw
# holds the browser's main thread: at 20 a second a 2-core machine answered 14 WebDriver reads in
# 15 s, at 5 a second 131 (the telemetry's text and plots keep their own 4-25 Hz beat either way).
FPS, FPS_MIN, FPS_MAX = 20, 1, 60  # the scene's redraws a second: 20 is NiceGUI's own default


def register(sub):
    p = sub.add_parser("view", help="the live 3-D view of the robot in a web page (docs/view.md)")
    src = p.add_mutually_exclusive_group(required=True)
    src.add_argument("--sim", action="store_true", help="the wall simulator's room, trial after trial")
    src.add_argument(
        "--virtual", action="store_true", help="the virtual board (hexapod virtual-board), driven from the page"
    )
    src.add_argument(
        "--pico", action="store_true", help="the emulated Pico with its PCA9685s and HC-SR04s (hexapod pico serial)"
    )
    src.add_argument("--port", metavar="PORT", help="a board on this serial port (opened exclusively)")
    src.add_argument("--replay", metavar="FILE", help="play a recording made with --record (an .mcap file)")
    p.add_argument(
        "--world",
        help="with --sim (default %s), or --replay of a board's recording (its room): a world file or a shipped "
        "world: %s" % (DEFAULT, ", ".join(shipped())),
    )
    p.add_argument("--setpoint", metavar="CM", help="with --sim: the side sonar reading to hold (default 12)")
    p.add_argument("--seed", metavar="S", help="with --sim: the run's seed, as hexapod sim wall's (default 0)")
    p.add_argument(
        "--virtual-port",
        metavar="PTY",
        help="with --virtual: attach to a virtual board already running on this pty (default: start one)",
    )
    from hexapod_host.commands.pico import _sonar_option

    _sonar_option(p)
    p.add_argument("--speed", default="1", metavar="X", help="simulated seconds per second: %s (default 1)" % _speeds())
    p.add_argument(
        "--fps",
        default=str(FPS),
        metavar="N",
        help="the 3-D scene's redraws a second, %d..%d (default %d; lower it where the browser draws in software)"
        % (FPS_MIN, FPS_MAX, FPS),
    )
    p.add_argument(
        "--listen",
        default=LISTEN,
        metavar="HOST:PORT",
        help="where the page is served (default %s, this machine only; another interface only when named here)"
        % LISTEN,
    )
    p.add_argument("--no-browser", action="store_true", help="serve only; open no browser")
    p.add_argument(
        "--record", metavar="FILE", help="write every snapshot with its time into FILE (.mcap; replaced if there)"
    )
    p.set_defaults(func=run)


def _speeds():
    return ", ".join("%g" % s for s in player_mod.SPEEDS)


def parse_listen(text):
    """(host, port) of --listen HOST:PORT (a bare PORT: this machine). An empty host is refused:
    every interface must be asked for by name (0.0.0.0 or ::)."""
    host, sep, port = text.rpartition(":")
    if not sep:
        host, port = "127.0.0.1", text
    elif not host:
        raise UsageError(
            "--listen %r: no host; say 127.0.0.1:%s (this machine) or 0.0.0.0:%s (every interface)" % (text, port, port)
        )
    host = host.strip("[]")
    try:
        port = int(port)
    except ValueError:
        raise UsageError(
            "--listen %r: the port %r is not a whole number (HOST:PORT, port 1..65535)" % (text, port)
        ) from None
    if not 1 <= port <= 65535:
        raise UsageError("--listen %r: port %d is outside 1..65535" % (text, port))
    return host, port


def parse(args):
    """Checked options: (source, speed, host, port, the --record path or None). Nothing is
    written or opened for writing: a refused command leaves no file behind."""
    if args.virtual_port and not args.virtual:
        raise UsageError("--virtual-port: only with --virtual")
    if args.virtual_port and not os.path.exists(args.virtual_port):
        raise UsageError(
            "--virtual-port %s: no such port (hexapod virtual-board prints its pty's path first)" % args.virtual_port
        )
    if args.record is not None:
        if args.replay is not None:
            raise UsageError("--record: not with --replay (the recording is there already)")
        from hexapod_host.commands import checks

        checks.out_file("--record", args.record, suffix=".mcap")
    if args.sonar_cm is not None and not args.pico:
        raise UsageError("--sonar-cm: only with --pico (what the emulated HC-SR04s see)")
    for flag, value in (("--setpoint", args.setpoint), ("--seed", args.seed)):
        if value is not None and not args.sim:
            raise UsageError("%s: only with --sim (the simulator's trials)" % flag)
    if args.world is not None and not (args.sim or args.replay is not None):
        raise UsageError(
            "--world: only with --sim or --replay (a board's room is the real one: a recording of it can be "
            "replayed in a world with --replay FILE --world W)"
        )
    devices = pico_devices(args) if args.pico else None
    world = None
    if args.sim or args.world is not None:
        try:
            world = load(args.world or DEFAULT)
        except WorldError as err:
            raise UsageError("--world: %s" % err) from None
    if args.sim:
        setpoint = _number(args.setpoint or "12", "--setpoint", 4, 50, "cm (the side sonar's reading)")
        seed = _whole(args.seed or "0", "--seed", 0, 2**62)
    scene_fps(args)
    speed = _number(args.speed, "--speed", 0, 100, "simulated seconds per second")
    if speed not in player_mod.SPEEDS:
        raise UsageError("--speed: %s, allowed %s" % (args.speed, _speeds()))
    host, port = parse_listen(args.listen)
    from hexapod_host.view.server import check_free

    why = check_free(host, port)
    if why:
        raise UsageError("--listen %s: cannot listen there (%s)" % (args.listen, why))
    if args.replay is not None:
        from hexapod_host.view.replay import ReplayError, ReplaySource

        try:
            return ReplaySource(args.replay, world), speed, host, port, None
        except ReplayError as err:
            raise UsageError("--replay %s" % err) from None
    if args.virtual:
        return virtual_source(args.virtual_port), 1.0, host, port, args.record
    if args.pico:
        return pico_source(devices), 1.0, host, port, args.record
    if args.port is not None:
        return port_source(args.port), 1.0, host, port, args.record
    from hexapod_host.view.sim import SimSource

    try:
        source = SimSource(world, setpoint, seed)
    except WorldError as err:
        raise UsageError(str(err)) from None
    return source, speed, host, port, args.record


def virtual_source(pty=None):
    """A BoardSource on the virtual board: the one on pty, else one started here (stopped when the
    source closes, its temporary calibration directory removed)."""
    import tempfile

    proc = tmp = None
    flag = "--virtual-port"
    if pty is None:
        flag = "--virtual"
        from hexapod_host.commands.console import (
            CAL_PREFIX,
            remove_stale_cal_dirs,
            start_virtual_board,
            stop_virtual_board,
        )

        remove_stale_cal_dirs()
        tmp = tempfile.TemporaryDirectory(prefix=CAL_PREFIX % os.getpid())
        proc, pty, master, slave = start_virtual_board("pico", "default", tmp.name)

    def stop_board():
        if proc is not None:
            stop_virtual_board(proc, master, slave)
            tmp.cleanup()

    return open_board(pty, flag, "virtual", stop_board, boot_s=30)  # the VM takes a few seconds to start


def open_board(path, flag, name, on_close=None, boot_s=0, reply_s=10.0):
    """A BoardSource on the console line at path, opened exclusively as `hexapod send` opens a port
    (pyserial's lock: nobody else types on the robot's line meanwhile). boot_s: wait that long for
    an answer to `help` first (a board still booting), else refuse; 0: serve whatever answers.
    on_close runs when the source closes, or here when it is refused. UsageError names flag."""
    from hexapod_host.serial.link import Link, LinkError
    from hexapod_host.view.board import BoardSource
    from hexapod_host.view.board_link import BoardLink

    try:
        port = Link.open(path).port
    except LinkError as e:
        if on_close is not None:
            on_close()
        raise UsageError("%s: %s" % (flag, e)) from None
    link = BoardLink(port, path).start()
    if boot_s and link.request("help", timeout=boot_s) is None:
        link.close()
        if on_close is not None:
            on_close()
        raise UsageError("%s: no answer from the board on %s within %d s" % (flag, path, boot_s))
    return BoardSource(link, "pico", name, on_close=on_close, reply_s=reply_s)


def port_source(path):
    """A BoardSource on a board at the serial port path: no boot wait (a board that answers nothing,
    or `err` to `stream`, is served resting with what it said)."""
    return open_board(path, "--port", "port")


def pico_devices(args):
    """The emulated chips of --pico (its PCA9685s, its HC-SR04s at --sonar-cm), or UsageError when
    the emulator cannot run here (no Node.js, no firmware image) or a distance is refused."""
    from hexapod_host.commands import pico as pico_cmd
    from hexapod_host.pico import emulator

    why = emulator.missing()
    if why:
        raise UsageError("--pico: " + why)
    return pico_cmd._devices(args)


def pico_source(devices):
    """A BoardSource on the emulated Pico: the firmware as `hexapod flash --board pico` lands it,
    booted by `hexapod pico serial`'s machinery on a pty with devices attached; stopped (and its
    image removed) when the source closes. Its clock is emulated: telemetry frames and times are
    the board's, the page's rate is what the emulator gives."""
    import contextlib

    from hexapod_host.pico import emulator

    stack = contextlib.ExitStack()
    try:
        fs = stack.enter_context(emulator.flashed())
        path = stack.enter_context(emulator.serial(fs, devices=devices))
    except BaseException:
        stack.close()
        raise
    return open_board(path, "--pico", "pico", stack.close, boot_s=PICO_BOOT_S, reply_s=PICO_REPLY_S)


def scene_fps(args):
    """--fps N, checked: the scene's redraws a second."""
    return _whole(args.fps, "--fps", FPS_MIN, FPS_MAX)


def run(args):
    source, speed, host, port, record_path = parse(args)
    from hexapod_host.view.player import Player
    from hexapod_host.view.server import is_loopback, serve

    shown = "[%s]" % host if ":" in host else host
    d = source.describe()
    where = ("world %s" % d["world"]) if d.get("world") else getattr(source, "stream_reply", "-")
    print(
        "hexapod view: http://%s:%d  (source %s, %s%s); Ctrl-C stops"
        % (shown, port, d["source"], where, ", recording to %s" % record_path if record_path else "")
    )
    if not is_loopback(host):
        sys.stderr.write(
            "hexapod view: listening on %s: anyone who can reach this machine can open the page and press its buttons\n"
            % host
        )
    sys.stdout.flush()
    recorder = None
    if record_path:
        from hexapod_host.view.record import Recorder

        recorder = Recorder(record_path, d)
    player = Player(source, speed, recorder=recorder)
    try:
        serve(player, host, port, show=not args.no_browser, fps=scene_fps(args))
    finally:
        player.stop()  # after the server's own shutdown: nothing; after an error or Ctrl-C: finishes the recording
        if recorder is not None:
            print("hexapod view: %d snapshots recorded in %s" % (recorder.written, record_path))
    return 0
