"""`hexapod pico serial`, `hexapod pico run FILE...` and `hexapod pico bench ik|tick|frame --json`: the firmware on an
emulated Raspberry Pi Pico (hexapod_host.pico.emulator). Times are emulated us at 125 MHz, a lower bound
on silicon (zero-wait flash, approximate cycle costs)."""

import json
import os
import signal
import sys
import tempfile
import time

from hexapod_host import VM_DIR
from hexapod_host.commands import checks
from hexapod_host.commands.cli import UsageError
from hexapod_host.pico import emulator as pico


def _script(path, argv, tmp):
    """path's text with sys.argv set first (the raw REPL has none), written under tmp."""
    with open(path) as f:
        text = f.read()
    out = os.path.join(tmp, os.path.basename(path))
    with open(out, "w") as f:
        f.write("import sys\nsys.argv[:] = %r\n" % (["pico"] + [str(a) for a in argv]) + text)
    return out


def _with_standing():
    """The board's flash plus the host's stand-up helper (stubs/micropython/standing.py), for the
    bench scripts that stand a robot up: an image of its own, so the loop and boot figures still
    come from exactly what `hexapod flash` puts on a board."""
    import standing

    return pico.flashed(extra=[(standing.__file__, "standing.py")])


def _board(files, fs, **kw):
    """Run files on the emulated Pico; their JSON lines, or UsageError with the board's words."""
    status, out, err, stats = pico.run(files, fs=fs, **kw)
    if status != 0:
        raise UsageError("the emulated Pico failed (exit %d):\n%s%s" % (status, out, err))
    return [json.loads(line) for line in out.splitlines() if line.startswith("{")], stats


# The benches' counts: (least, most, default), each end run on the emulated board 2026-11-24. The
# most keeps a run within ~2 min of emulation and the scripts' tables inside the board's heap
# (2,000 frames ran out of it in the loop script's summary).
COUNTS = {"rounds": (1, 200, 20), "ticks": (1, 2000, 200), "frames": (2, 2000, 500)}


def _counts(args):
    """--rounds, --ticks, --frames checked (UsageError naming the allowed range) or their defaults."""
    for name, (lo, hi, default) in COUNTS.items():
        v = getattr(args, name)
        if v is None:
            setattr(args, name, default)
        elif not lo <= v <= hi:
            raise UsageError("--%s %d: allowed %d..%d" % (name, v, lo, hi))


def bench_ik(args, fs, tmp):
    """The VM's IK bench (vm/bench_ik.py) on the board: viper, float and plain-bytecode solves."""
    rows, _ = _board([_script(os.path.join(VM_DIR, "bench_ik.py"), (args.rounds, 1), tmp)], fs)
    return rows[-1]


def bench_tick(args, fs, tmp):
    """The VM's tick bench (vm/bench_tick.py) on the board: every gait, then the wall follower."""
    script = os.path.join(VM_DIR, "bench_tick.py")
    ticks = args.ticks
    with _with_standing() as bench_fs:
        gaits, _ = _board([_script(script, ("", ticks, 1, "gaits", 20000), tmp)], bench_fs)
        wall, _ = _board([_script(script, ("", ticks, 1, "wall", 20000), tmp)], bench_fs)
    return {
        "bench": "tick",
        "gaits": gaits,
        "worst_max_over_median": max(g["max_over_median"] for g in gaits),
        "heap_bytes_per_tick": max(g["heap_bytes_per_tick"] for g in gaits),
        "wall_follow": wall[-1],
        "budget_us": 20000,
    }


# The frame's parts on the board, timed apart over walking frames 20 ms apart (as the loop's): the
# ping (round robin: the last slot's echo collected from its IRQ timestamps, this slot's fired), the
# tick with its two bursts, and the two bursts alone (the same pulses again, once the tick's are out).
# With the background sender (drivers/_i2c_rp2.py) the bursts' CPU time and the bus differ: also
# when the bus is done (from the bursts' start) and the CPU its refill IRQs take meanwhile (a
# counting loop over the next 3 ms against the same loop with the bus quiet).
PARTS = """
import time, gc, main
from array import array
r = main.build()
import standing  # after the build: code loaded before the core's would move it (its figures)
asked = r.robot.stand_up()
t = time.ticks_ms()
t += 20 * standing.until_standing(r.robot, lambda n: r.robot.tick(t + 20 * (n + 1)), None, asked)
r.robot.walk(1200, 0, 0)
N = 50
ping = array("i", [0] * N)
tick = array("i", [0] * N)
burst = array("i", [0] * N)
done = array("i", [0] * N)
spin = array("i", [0] * N)
pulses = r.robot.pulses
bg = r.bank._sender if hasattr(r.bank, "_sender") else None
end = array("i", [0])
def count(t0):
    k = 0
    end[0] = -1
    while True:
        d = time.ticks_diff(time.ticks_us(), t0)
        if d >= 3000:
            return k
        busy = bg is not None and bg._st[3]  # evaluated on every pass, busy or not: the same loop
        if end[0] < 0 and not busy:
            end[0] = d
        k += 1
gc.collect()
gc.disable()
start = time.ticks_us()
for n in range(N):
    t += 20
    time.sleep_us(time.ticks_diff(time.ticks_add(start, 20000 * n), time.ticks_us()))
    t0 = time.ticks_us()
    r.sonars.ring.tick(r.distances, r.sonar_status)
    t1 = time.ticks_us()
    r.robot.tick(t)
    t2 = time.ticks_us()
    r.bank.sync()
    t2b = time.ticks_us()
    r.bank.write_frame(pulses)
    t3 = time.ticks_us()
    spin[n] = count(t3)
    r.bank.sync()
    ping[n] = time.ticks_diff(t1, t0)
    tick[n] = time.ticks_diff(t2, t1)
    burst[n] = time.ticks_diff(t3, t2b)
    done[n] = time.ticks_diff(t3, t2b) + max(0, end[0])
quiet = count(time.ticks_us())
gc.enable()
def med(a):
    b = sorted(a)
    return {"median_us": b[len(b) // 2], "max_us": b[-1]}
import json
b = med(burst)
tk = med(tick)
irq = med(array("i", [3000 - 3000 * s // quiet for s in spin]))
print(json.dumps({"ping": med(ping), "tick_with_bursts": tk, "two_bursts": b, "i2c_hz": r.board["i2c"]["freq"],
                  "bus_done_after": med(done), "refill_irq_cpu_in_3ms": irq,
                  "background": bg is not None, "refills": bg.stats[0] if bg is not None else 0}))
"""


def bench_frame(args, fs, tmp):
    """The whole frame (ping, tick, both bursts) of main.build's loop on the board with emulated
    chips: the loop script's figures over `frames`, its bursts checked against the stub machine's,
    and the parts timed apart."""
    from hexapod_host.pico import loop as pico_loop

    frames = args.frames
    scenario = args.scenario or "default"
    status, lines, bursts, stats = pico_loop.board(frames, fs, scenario)
    if status != 0:
        raise UsageError("the emulated Pico failed:\n" + "\n".join(lines))
    _, host_bursts = pico_loop.host(frames, scenario)
    result = pico_loop.summary(lines)
    result["bench"] = "frame"
    result["status_line"] = [line for line in lines if line.startswith("frames ")][-1]
    result["bursts_equal_host"] = bursts == host_bursts
    result["bursts"] = len(bursts)
    result["emulated_s"] = round(stats.get("emu_s", 0), 3)
    result["host_s"] = stats.get("host_s")
    if scenario == "drive":
        # The drive's frames include its commands; the parts are the default scenario's. Power-up
        # to main.py's first frame (bench boot) goes with it: both are what a driver waits for.
        result["boot_to_first_frame_ms"] = _boot(fs)["first_burst_ms"]
        return result
    if scenario == "stream":
        from hexapod_host.serial import telemetry

        # Every line the board wrote parses (ValueError naming the field otherwise); the parts
        # below are the default scenario's (no console in them), kept so both give the same keys.
        result["telemetry_lines"] = len([telemetry.parse(line) for line in lines if telemetry.is_telemetry(line)])
    devices = pico.devices(distances=list(pico_loop.DISTANCES))
    with _with_standing() as parts_fs:
        parts, _ = _board([_write(tmp, "parts.py", PARTS)], parts_fs, devices=devices)
    result["parts"] = parts[-1]
    return result


def bench_boot(args, fs, tmp):
    """Power-up to main.py's first PCA9685 burst (imports, the board and robot files, the servo
    guard's IK solves at the first configure), main.py unmodified, on the emulated clock: without a
    calibration file, then with one (with_cal_file)."""

    result = _boot(fs)
    result["bench"] = "boot"
    # The same boot with a calibration file on the board (the robot file's rows, trim 0), as every
    # calibrated robot boots: the file's decode and its rows put in force come before the first frame.
    cal = _cal_file(tmp)
    with pico.flashed(extra=[(cal, os.path.basename(cal))]) as cal_fs:
        result["with_cal_file"] = _boot(cal_fs)
    return result


def _cal_file(tmp):
    """A valid calibration file (calstore's format) of robots/default_cal.py's rows, trim 0."""
    import calstore
    import consolecal

    from hexapod import robotcal

    rows = [(0, m.direction, m.min_us, m.max_us) for m in robotcal.servo_maps(robotcal.load("default"))]
    return _write(tmp, calstore.FILE, consolecal.encode(rows))


def _boot(fs):
    """main.py from power-up for 6 emulated s: its first burst and frame period."""
    from hexapod_host.pico import loop as pico_loop

    times = []
    status, out, bursts = pico_loop.boot_main(6, fs, times)
    if status != 0 or not bursts:
        raise UsageError("the emulated Pico did not reach its first frame in 6 s:\n" + out)
    frames = [t for t in times[::2]]
    return {
        "first_burst_s": round(times[0] / 1e6, 4),
        "first_burst_ms": round(times[0] / 1e3, 1),
        "frame_period_ms": round((frames[-1] - frames[0]) / (len(frames) - 1) / 1000, 3),
        "frames_in_6s": len(frames),
    }


def _write(tmp, name, text):
    path = os.path.join(tmp, name)
    with open(path, "w") as f:
        f.write(text)
    return path


BENCHES = {"ik": bench_ik, "tick": bench_tick, "frame": bench_frame, "boot": bench_boot}


def register(sub):
    p = sub.add_parser("pico", help="the firmware on an emulated Raspberry Pi Pico (rp2040js, Node.js >= 18)")
    what = p.add_subparsers(dest="pico_command", metavar="run|bench|serial", required=True)
    r = what.add_parser("run", help="flash the firmware into an emulated Pico and run FILE... on it")
    r.add_argument("files", nargs="+", metavar="FILE", help="Python files run one after another (raw REPL)")
    r.add_argument("--image", metavar="DIR", help="keep the staged files in DIR (and the littlefs image DIR.img)")
    r.add_argument(
        "--firmware",
        metavar="FILE",
        help="MicroPython RPI_PICO .uf2/.bin (default: $PICO_FIRMWARE, else make pico-firmware's build)",
    )
    _sonar_option(r)
    r.set_defaults(func=run_files)
    b = what.add_parser("bench", help="benchmarks on the emulated Pico (JSON out): " + ", ".join(sorted(BENCHES)))
    b.add_argument("name", help="which benchmark: " + ", ".join(sorted(BENCHES)))
    b.add_argument("--json", action="store_true", help="print one JSON object (the default form)")
    b.add_argument("--firmware", metavar="FILE", help="MicroPython RPI_PICO .uf2/.bin")
    b.add_argument("--rounds", type=int, help="ik: six-leg solves per case, 1..200 (default 20)")
    b.add_argument("--ticks", type=int, help="tick: ticks per gait, 1..2000 (default 200)")
    b.add_argument("--frames", type=int, help="frame: 20 ms frames of the whole loop, 2..2000 (default 500: 10 s)")
    b.add_argument(
        "--scenario",
        choices=("default", "drive", "stream"),
        help="frame: default (stand, walk, turn, crab, back, stop), drive (walk commands 5 times a second, "
        "gait changes while walking, height and pose changes; adds boot_to_first_frame_ms) or stream (the "
        "default with the console's telemetry at 25 Hz; adds telemetry_lines, each parsed)",
    )
    b.set_defaults(func=run_bench)
    s = what.add_parser("serial", help="the emulated Pico as a serial port (a pty; prints its path first)")
    s.add_argument("--fs", metavar="IMG", help="littlefs image to boot with (default: erased flash)")
    s.add_argument("--save-fs", metavar="OUT", help="write the board's filesystem here when stopped")
    s.add_argument("--firmware", metavar="FILE", help="MicroPython RPI_PICO .uf2/.bin")
    _sonar_option(s)
    s.set_defaults(func=run_serial)


# The HC-SR04's range (datasheet: 2 cm - 4 m); the default: walls 30-70 cm away, one per sensor, as on
# the virtual board.
SONAR_CM = (2, 400)
SONAR_DEFAULT_CM = (30, 40, 50, 60, 70)


def _sonar_option(p):
    p.add_argument(
        "--sonar-cm",
        nargs="+",
        metavar="CM",
        help="what the emulated HC-SR04s see, cm, %d..%d: one value for all five or five in drivers.hcsr04 "
        "order (default %s)" % (SONAR_CM + (" ".join(map(str, SONAR_DEFAULT_CM)),)),
    )


def _devices(args):
    """The board's emulated chips (its PCA9685s, its five HC-SR04s at --sonar-cm), as main.build expects
    them; UsageError names a bad distance."""
    from hexapod import board as boards

    n = len(boards.sonar_pins(boards.load("pico")))
    words = args.sonar_cm or [str(v) for v in SONAR_DEFAULT_CM]
    if len(words) not in (1, n):
        raise UsageError("--sonar-cm: %d values; allowed 1 (for every sonar) or %d (one each)" % (len(words), n))
    cm = []
    for w in words:
        try:
            v = float(w)
        except ValueError:
            raise UsageError("--sonar-cm: %r is not a number (cm)" % w) from None
        if not SONAR_CM[0] <= v <= SONAR_CM[1]:  # also refuses nan
            raise UsageError("--sonar-cm: %s is outside %d..%d cm (the HC-SR04's range)" % (w, *SONAR_CM))
        cm.append(v)
    return pico.devices("pico", distances=[round(v * 100) for v in (cm * n if len(cm) == 1 else cm)])


def _check(args):
    if args.firmware:
        os.environ["PICO_FIRMWARE"] = args.firmware
    try:
        pico.node()
        pico.firmware()
    except pico.PicoError as err:
        raise UsageError(str(err)) from None


def run_files(args):
    """Stage, pack, boot, run the files; the board's output streams here; its status is ours."""
    _check(args)
    for f in args.files:
        if not os.path.isfile(f):
            raise UsageError("no such file: %s" % f)
    if args.image:
        checks.out_dir("--image", args.image, empty=True)
        checks.out_file("--image", args.image.rstrip("/") + ".img")
    devices = _devices(args)
    with tempfile.TemporaryDirectory() as tmp:
        tree = args.image or os.path.join(tmp, "stage")
        pico.stage(tree)
        fs = pico.image(tree, (args.image.rstrip("/") + ".img") if args.image else os.path.join(tmp, "fs.img"))
        status, _, _, _ = pico.run(args.files, fs=fs, stream=True, devices=devices)
    return status


def run_bench(args):
    if args.name not in BENCHES:
        raise UsageError("no Pico benchmark %r; there are: %s" % (args.name, ", ".join(sorted(BENCHES))))
    _counts(args)
    _check(args)
    with tempfile.TemporaryDirectory() as tmp, pico.flashed() as fs:
        result = BENCHES[args.name](args, fs, tmp)
    result["runtime"] = "micropython rp2 (emulated RPI_PICO)"
    result["clock"] = pico.CLOCK
    result["lower_bound"] = "zero-wait flash, approximate cycle costs: silicon is as fast or slower"
    result["firmware"] = os.path.basename(pico.firmware())
    print(json.dumps(result, sort_keys=True) if args.json else json.dumps(result, sort_keys=True, indent=2))
    sys.stdout.flush()
    return 0


def run_serial(args):
    """The emulated Pico on a pty until Ctrl-C or SIGTERM: `hexapod flash --board pico --port PTY`."""
    _check(args)
    if args.fs and not os.path.isfile(args.fs):
        raise UsageError("--fs %r: no such file" % args.fs)
    if args.save_fs:
        checks.out_file("--save-fs", args.save_fs)
    devices = _devices(args)

    def stop(signum, frame):
        raise KeyboardInterrupt

    old = signal.signal(signal.SIGTERM, stop)
    try:
        with pico.serial(args.fs, save_fs=args.save_fs, devices=devices) as path:
            print(path, flush=True)
            print(
                "emulated Pico on %s (its two PCA9685s and five HC-SR04s at %s cm attached); try: hexapod flash "
                "--board pico --port %s; Ctrl-C stops"
                % (path, " ".join("%g" % (s["distance"] / 100) for s in devices["sonars"]), path),
                file=sys.stderr,
                flush=True,
            )
            while True:
                time.sleep(3600)
    except KeyboardInterrupt:
        pass
    finally:
        signal.signal(signal.SIGTERM, old)
    if args.save_fs:
        print("filesystem saved to %s" % args.save_fs, file=sys.stderr)
    return 0
