"""The firmware on an emulated Raspberry Pi Pico: rp2040js (npm, pinned in host/pico/package.json,
installed on demand) running MicroPython's RPI_PICO firmware under Node.js (host/pico/run.mjs).

stage() lays out what a flash puts on a Pico (.mpy for armv6m, main.py as source), image() packs
it into the littlefs2 image the rp2 port mounts, run() boots it. Times on the board are emulated
microseconds at 125 MHz: deterministic, and a lower bound on silicon (zero-wait flash, approximate
cycle costs; docs/pico.md).
"""

import contextlib
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

from hexapod_host import ROOT
from hexapod_host.pico import image as rp2040_image

HERE = os.path.join(ROOT, "host", "pico")
RUNNER = os.path.join(HERE, "run.mjs")
# Our own image, built from Debian's source packages by host/pico/firmware.py (`make pico-firmware`).
DEFAULT_FIRMWARE = os.path.join(ROOT, "build", "pico-firmware", "firmware.bin")
CLOCK = "emulated rp2040 125 MHz"
NODE_MIN = 18
# littlefs2 geometry of the rp2 port's RPI_PICO filesystem (ports/rp2, v1.28): 1408 KiB at 0xA0000.
FS_BLOCK_SIZE = 4096
FS_BLOCKS = 352
FS_PROG_SIZE = 256


class PicoError(RuntimeError):
    """The emulator cannot start: the message says what is missing and how to get it."""


def node():
    """Path of a Node.js >= 18, else PicoError saying how to get one."""
    exe = os.environ.get("NODE") or shutil.which("node") or shutil.which("nodejs")
    if exe is None:
        raise PicoError("the Pico emulator needs Node.js >= %d: install it (e.g. apt-get install nodejs)" % NODE_MIN)
    try:
        out = subprocess.run([exe, "--version"], capture_output=True, text=True, timeout=60).stdout.strip()
    except OSError as err:
        raise PicoError("the Pico emulator needs Node.js >= %d; %s does not run: %s" % (NODE_MIN, exe, err)) from None
    m = re.match(r"v(\d+)\.", out)
    if not m or int(m.group(1)) < NODE_MIN:
        raise PicoError("the Pico emulator needs Node.js >= %d; %s is %s" % (NODE_MIN, exe, out or "unknown"))
    return exe


def firmware(path=None):
    """The MicroPython RPI_PICO image: path, else $PICO_FIRMWARE, else the one `make pico-firmware` builds."""
    given = path or os.environ.get("PICO_FIRMWARE")
    path = given or DEFAULT_FIRMWARE
    if not os.path.isfile(path):
        if given:
            raise PicoError("no Pico firmware at %s: pass --firmware FILE (a MicroPython RPI_PICO .uf2 or .bin)" % path)
        raise PicoError(
            "no Pico firmware image (%s): run `make pico-firmware`, which builds MicroPython from Debian's "
            "source packages (needs apt access to the Debian archive), or pass --firmware FILE" % os.path.relpath(path)
        )
    try:
        rp2040_image.check(path)
    except (rp2040_image.ImageError, OSError) as err:
        raise PicoError("not an RP2040 UF2/bin: %s: %s" % (path, err)) from None
    return os.path.abspath(path)


def missing():
    """Why the emulator cannot run here (a skip reason for tests), or None."""
    try:
        node()
        firmware()
    except PicoError as err:
        return str(err)
    return None


def rp2040js():
    """Install rp2040js (the version package.json pins) into host/pico/node_modules when absent."""
    with open(os.path.join(HERE, "package.json")) as f:
        want = json.load(f)["dependencies"]["rp2040js"]
    have = os.path.join(HERE, "node_modules", "rp2040js", "package.json")

    def installed():
        with contextlib.suppress(OSError, ValueError), open(have) as f:
            return json.load(f)["version"] == want
        return False

    if installed():
        return
    import fcntl  # several test workers may ask at once: one installs, the others wait

    with open(os.path.join(HERE, ".npm-lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if installed():
            return
        npm = shutil.which("npm")
        if npm is None:
            raise PicoError("npm is missing: install Node.js >= %d with npm, then retry" % NODE_MIN)
        proc = subprocess.run(
            [npm, "install", "--no-audit", "--no-fund", "--loglevel=error"], cwd=HERE, capture_output=True, text=True
        )
        if proc.returncode != 0 or not installed():
            raise PicoError("npm install rp2040js@%s failed:\n%s" % (want, proc.stderr.strip()))


def stage(dest, board="pico", robot="default", arch="armv6m"):
    """Lay out under dest exactly what `hexapod flash` puts on the board (hexapod_host.serial.flash.stage:
    the entry's import closure and the core as .mpy for arch, main.py as source); returns dest."""
    from hexapod_host.serial import flash

    try:
        flash.stage(board, robot, dest, arch=arch)
    except flash.FlashError as e:
        raise PicoError(str(e)) from None
    return dest


def image(src_dir, out):
    """Pack the tree under src_dir into a littlefs2 image for the rp2 port's filesystem; returns out."""
    from littlefs import LittleFS

    lfs = LittleFS(block_size=FS_BLOCK_SIZE, block_count=FS_BLOCKS, prog_size=FS_PROG_SIZE, read_size=32)
    for root, _, names in sorted(os.walk(src_dir)):
        rel = os.path.relpath(root, src_dir)
        target = "/" if rel == "." else "/" + rel.replace(os.sep, "/")
        if target != "/":
            lfs.makedirs(target, exist_ok=True)
        for name in sorted(names):
            with open(os.path.join(root, name), "rb") as s, lfs.open(target.rstrip("/") + "/" + name, "wb") as d:
                d.write(s.read())
    with open(out, "wb") as f:
        f.write(lfs.context.buffer)
    return out


def _runner_cmd(tmp, exe, fw, fs, devices, trace):
    """run.mjs's command line for the options run() and serial() share (devices as JSON in tmp)."""
    cmd = [exe, RUNNER, "--firmware", fw]
    if fs:
        cmd += ["--fs", fs]
    if devices is not None:
        path = os.path.join(tmp, "devices.json")
        with open(path, "w") as f:
            json.dump(devices, f)
        cmd += ["--devices", path]
    if trace:
        cmd += ["--trace", trace]
    return cmd


def run(files=(), *, fs=None, firmware_path=None, devices=None, trace=None, main_seconds=0, stream=False, timeout=900):
    """Boot the emulated Pico with filesystem image fs and run files (or its main.py for
    main_seconds emulated s). Returns (exit status, stdout, stderr, stats dict)."""
    exe = node()
    fw = firmware(firmware_path)
    rp2040js()
    with tempfile.TemporaryDirectory() as tmp:
        stats_path = os.path.join(tmp, "stats.json")
        cmd = _runner_cmd(tmp, exe, fw, fs, devices, trace) + ["--stats", stats_path]
        if main_seconds:
            cmd += ["--main", str(main_seconds)]
        cmd += list(files)
        if stream:
            proc = subprocess.run(cmd, stderr=subprocess.PIPE, text=True, timeout=timeout)
            out = ""
        else:
            proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
            out = proc.stdout
        stats = {}
        with contextlib.suppress(OSError, ValueError), open(stats_path) as f:
            stats = json.load(f)
    if stream and proc.stderr:
        sys.stderr.write(proc.stderr)
    return proc.returncode, out, proc.stderr, stats


@contextlib.contextmanager
def flashed(board="pico", robot="default", image_dir=None, extra=()):
    """A littlefs image of the staged firmware (staged into image_dir when given) plus extra, (file
    on the host, path on the board) pairs (the tests' scenario modules): yields its path."""
    with tempfile.TemporaryDirectory() as tmp:
        tree = image_dir or os.path.join(tmp, "stage")
        stage(tree, board, robot)
        for src, dest in extra:
            os.makedirs(os.path.dirname(os.path.join(tree, dest)), exist_ok=True)
            shutil.copy(src, os.path.join(tree, dest))
        yield image(tree, os.path.join(tmp, "fs.img"))


@contextlib.contextmanager
def serial(fs=None, *, save_fs=None, firmware_path=None, devices=None, trace=None, stats=None):
    """The emulated Pico on a pseudo-terminal, as a USB serial port: boots the runner in --serial
    mode with filesystem image fs (None: erased flash, MicroPython formats it), bridges the pty
    master to its stdin/stdout, and yields the slave's path (/dev/pts/N) for mpremote & co. On
    exit the runner stops; with save_fs the board's littlefs region is written there."""
    import select
    import threading
    import tty

    exe = node()
    fw = firmware(firmware_path)
    rp2040js()
    with tempfile.TemporaryDirectory() as tmp:
        cmd = _runner_cmd(tmp, exe, fw, fs, devices, trace) + ["--serial"]
        if save_fs:
            cmd += ["--save-fs", save_fs]
        if stats:
            cmd += ["--stats", stats]
        master, slave = os.openpty()
        tty.setraw(slave)  # no echo, no line editing before a client opens it; kept open: no EIO
        os.set_blocking(master, False)
        proc = subprocess.Popen(cmd, stdin=subprocess.PIPE, stdout=subprocess.PIPE, bufsize=0)
        stop = threading.Event()

        def to_board():
            while not stop.is_set():
                if select.select([master], [], [], 0.05)[0]:
                    try:
                        data = os.read(master, 4096)
                    except OSError:
                        continue
                    try:
                        proc.stdin.write(data)
                    except (BrokenPipeError, ValueError):
                        return

        def from_board():
            out = proc.stdout.fileno()
            while True:
                data = os.read(out, 4096)
                if not data:
                    return
                # Nobody reading the port: the pty buffer fills and the rest is dropped, as a
                # USB CDC device drops output with no host reading it.
                with contextlib.suppress(BlockingIOError):
                    os.write(master, data)

        threads = [threading.Thread(target=t, daemon=True) for t in (to_board, from_board)]
        for t in threads:
            t.start()
        try:
            yield os.ttyname(slave)
        finally:
            stop.set()
            threads[0].join(5)
            with contextlib.suppress(OSError):
                proc.stdin.close()
            try:
                proc.wait(30)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait()
            threads[1].join(5)
            proc.stdout.close()
            os.close(master)
            os.close(slave)


def run_source(source, fs=None, **kw):
    """Run Python source text on the emulated Pico; (status, stdout, stderr, stats)."""
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "script.py")
        with open(path, "w") as f:
            f.write(source)
        return run([path], fs=fs, **kw)


def devices(board_name="pico", distances=None, unplugged=(), power_pins=None, adc=None):
    """The emulated chips run.mjs attaches for a board file: its PCA9685s on its I2C pins (those
    in `unplugged` NACK; power_pins {address: GPIO}: that chip is off while the GPIO is driven
    high, and powers up afresh when it goes low), its five HC-SR04s at distances (0.1 mm,
    drivers.hcsr04 order), and adc (pin, [12-bit code of each conversion, in order]): the voltage on
    that ADC pin, one code a conversion, the last one held."""
    from hexapod import board as boards

    board = boards.load(board_name)
    bus = board["i2c"]
    pins = boards.sonar_pins(board)
    distances = distances or [3000 + 1000 * k for k in range(len(pins))]
    chips = board["pca9685"]["chips"]

    def power(address):
        return {"power_pin": power_pins[address]} if power_pins and address in power_pins else {}

    out = {
        "i2c": {"id": bus["id"], "sda": bus["sda"], "scl": bus["scl"]},
        "pca9685": [
            dict({"address": c["address"], "plugged": c["address"] not in unplugged}, **power(c["address"]))
            for c in chips
        ],
        "sonars": [{"trigger": t, "echo": e, "distance": d} for (t, e), d in zip(pins, distances, strict=True)],
    }
    if adc is not None:
        out["adc"] = {"pin": adc[0], "codes": list(adc[1])}
    return out
