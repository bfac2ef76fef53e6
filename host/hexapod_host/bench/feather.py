"""`hexapod bench feather`: the CircuitPython deploy's heap, measured in the MicroPython VM.

What runs is what `hexapod flash --board feather_rp2040` puts on the drive (serial.flash.stage:
.py sources, compiled by the board at import) plus the Adafruit libraries circup installs (as
.mpy, as circup does by default: bytecode the board loads without compiling), on the fake
CircuitPython modules of stubs/circuitpython_vm and the chip models: code.py's start, then
COMMANDS on the serial line, FRAMES frames. Nothing of firmware/ is on the VM's path, so a file
the deploy misses fails the run.

Figures (bytes, the VM's 64-bit heap): the smallest -X heapsize from which the run succeeds at
every size up to 24 KB above it (robust_heap), the free heap the deploy had at that size
(free_needed_64), gc.mem_alloc after the imports and at the end, and per module what its import
allocates (collector off) and what stays (modules()). to_32bit() carries the need to a 32-bit
board with the ratio measured on the emulated Pico (PICO_RATIO); the margin is against
FEATHER_FREE, the heap a stock CircuitPython 10 Feather RP2040 has free at its REPL.
"""

import json
import os
import shutil
import subprocess
import sys
import tempfile

from hexapod_host import STUBS, VM_DIR, mpvm
from hexapod_host.serial import flash

BOARD = "feather_rp2040"
ROBOT = "default"
CP_STUBS = os.path.join(os.path.dirname(STUBS), "circuitpython_vm")
SCRIPT = os.path.join(VM_DIR, "feather_heap.py")
FRAMES = 1000
WINDOW = 12  # robust_heap: this many heap sizes 2 KB apart (24 KB) must all succeed
FEATHER_FREE = 171 * 1024  # gc.mem_free() at the REPL, stock CircuitPython 10, Feather RP2040 (USB host on)
# 32-bit heap / 64-bit heap for the same .py imports: the emulated Pico (rp2 MicroPython, 32-bit) against
# the VM (64-bit), pico_ratio() (`python -m hexapod_host.bench.feather ratio`), two runs of 2026-11-27 (24
# and 22 modules over 1 KB): bytes allocated while importing (the compile) 0.80 of the VM's in total both
# times (per module 0.68-1.05 and 0.73-1.05; the five largest 0.75-0.80); bytes that stay 0.71 and 0.73
# (0.54-1.31). The larger total is the one used.
PICO_RATIO = 0.80
# The serial line during the run: stand, follow the left wall at 12 cm, a status, a sonar (the
# reporting commands' module: status is resident since frames22b), the self-test.
COMMANDS = ((100, "stand\n"), (4000, "wall left 12\n"), (14000, "status\n"), (14500, "sonar\n"), (15000, "selftest\n"))
SONAR_MM10 = (8000, 1200, 1200, 8000, 8000)  # front, left pair at the wall's 12 cm, right side open


def rig(board_name=BOARD):
    """The chips and sonars on the board file's bus and pins, as the VM script takes them."""
    from hexapod import board as boards

    board = boards.load(board_name)
    chips = [[c["address"], c["osc_hz"]] for c in board["pca9685"]["chips"]]
    sonars = [[t, e, SONAR_MM10[k]] for k, (t, e) in enumerate(boards.sonar_pins(board))]
    return {"chips": chips, "sonars": sonars}


def _site_module(name):
    """The .py file of an installed module (adafruit_register, adafruit_bus_device.i2c_device)."""
    import importlib.util

    try:
        spec = importlib.util.find_spec(name)
    except ImportError:  # a name imported from a module (from m import Class), not a module
        return None
    return spec.origin if spec and spec.origin and spec.origin.endswith(".py") else None


def lib_files(libs):
    """{path under lib/: source file} of the Adafruit libraries and the adafruit_* modules they import."""
    out, todo = {}, list(libs)
    while todo:
        name = todo.pop()
        src = _site_module(name)
        if src is None:
            continue
        parts = name.split(".")
        rel = "/".join(parts) + ("/__init__.py" if src.endswith("__init__.py") else ".py")
        if rel in out:
            continue
        out[rel] = src
        for k in range(1, len(parts)):  # a package's __init__ runs first
            todo.append(".".join(parts[:k]))
        todo += [n for n in flash._imports(src) if n.startswith("adafruit_")]
    return out


def stage(dest, libs_as="mpy"):
    """The drive's image under dest (flash.stage) with the Adafruit libraries in dest/lib (libs_as
    "mpy": compiled by mpy-cross, as circup installs them; "py": sources). Returns {board path: bytes}."""
    _, image, libs = flash.stage(BOARD, ROBOT, dest)
    sizes = {p: os.path.getsize(os.path.join(dest, p)) for p in image}
    for rel, src in sorted(lib_files(libs).items()):
        out = os.path.join(dest, "lib", rel)
        os.makedirs(os.path.dirname(out), exist_ok=True)
        if libs_as == "py":
            shutil.copyfile(src, out)
        else:
            out = out[:-3] + ".mpy"
            subprocess.run([flash.tool("mpy-cross"), "-o", out, src], check=True, capture_output=True)
        sizes["lib/" + os.path.relpath(out, os.path.join(dest, "lib"))] = os.path.getsize(out)
    return sizes


def vm(dest, cfg, heapsize):
    """The VM script's JSON on the image in dest; MemoryError raised as such, other failures as
    MicroPythonError. A MemoryError the console caught (a command answering `err ...: internal
    error MemoryError ...` while the loop went on) is one too: the run did not do what it was asked."""
    search = (dest, os.path.join(dest, "lib"), CP_STUBS, STUBS)
    try:
        out = mpvm.run(script=SCRIPT, stdin=json.dumps(cfg), heapsize=str(heapsize), search=search)
    except mpvm.MicroPythonError as err:
        if "MemoryError" in str(err):
            raise MemoryError(str(err).strip().splitlines()[-1]) from None
        raise
    lines = out.strip().splitlines()
    caught = [line for line in lines[:-1] if "MemoryError" in line]
    if caught:
        raise MemoryError(caught[0])
    return json.loads(lines[-1])


def run_cfg(frames=FRAMES, commands=COMMANDS):
    return dict(rig(), mode="run", frames=frames, commands=[list(c) for c in commands])


def smallest_heap(dest, cfg, lo=32 * 1024, hi=1024 * 1024, step=1024):
    """(smallest -X heapsize within step bytes at which the run succeeds, its result there): a bisection."""
    best = vm(dest, cfg, hi)  # must pass: else the run is broken, not short of heap
    while hi - lo > step:
        mid = (lo + hi) // 2 // step * step
        try:
            best, hi = vm(dest, cfg, mid), mid
        except MemoryError:
            lo = mid
    return hi, best


def robust_heap(dest, cfg, window=WINDOW, step=2048):
    """(smallest -X heapsize from which window sizes step bytes apart all succeed, its result there).

    Success is not monotonic in the heap size: where the collector runs moves with it, and a run
    that passes at N can fail a few KB above (seen: 4 KB of failures 8 KB above the first pass)."""
    start, _ = smallest_heap(dest, cfg)
    k = 0
    while k < window:
        if _passes(dest, cfg, start + k * step):
            k += 1
        else:
            start, k = start + (k + 1) * step, 0
    return start, vm(dest, cfg, start)


def _passes(dest, cfg, heapsize):
    try:
        vm(dest, cfg, heapsize)
    except MemoryError:
        return False
    return True


def import_order(dest):
    """The deploy's modules, leaves first (as importing code.py and console meets them)."""
    order, seen = [], set()

    def visit(name):
        path = None
        for cand in (name.replace(".", "/") + ".py", name.replace(".", "/") + "/__init__.py"):
            if os.path.isfile(os.path.join(dest, cand)):
                path = os.path.join(dest, cand)
        if path is None or name in seen:
            return
        seen.add(name)
        parts = name.split(".")
        for k in range(1, len(parts)):
            visit(".".join(parts[:k]))
        for n in flash._imports(path):
            visit(n)
        order.append(name)

    for entry in ("code", "console"):
        visit(entry)
    return order


def modules(dest, heapsize="4m"):
    """[[module, bytes allocated importing it (collector off), bytes that stay]] in import order."""
    cfg = dict(rig(), mode="modules", modules=import_order(dest))
    return vm(dest, cfg, heapsize)["modules"]


def to_32bit(bytes_64, ratio=PICO_RATIO):
    return int(bytes_64 * ratio + 0.5)


def measure(libs_as="mpy", per_module=True):
    """The figures `hexapod bench feather` prints (see the module docstring)."""
    with tempfile.TemporaryDirectory() as tmp:
        dest = os.path.join(tmp, "drive")
        sizes = stage(dest, libs_as)
        heap, best = robust_heap(dest, run_cfg())
        deploy = {p: n for p, n in sizes.items() if not p.startswith("lib/")}
        need = best["free"]
        result = {
            "bench": "feather",
            "board": BOARD,
            "libs": libs_as,
            "files": len(deploy),
            "source_bytes": sum(deploy.values()),
            "lib_bytes": sum(n for p, n in sizes.items() if p.startswith("lib/")),
            "frames": best["frames"],
            "heapsize_min_64": heap,
            "free_needed_64": need,
            "after_import_64": best["after_import"],
            "peak_64": best["peak"],
            "end_64": best["end"],
            "ratio_32_64": PICO_RATIO,
            "free_needed_32": to_32bit(need),
            "feather_free": FEATHER_FREE,
            "margin_32": FEATHER_FREE - to_32bit(need),
        }
        if per_module:
            result["modules"] = modules(dest)
    return result


# folder_spread's staging folders, 2 to 40 characters: the drive's folder name alone moves the need by up
# to 9 KB (2026-11-27: 242,336-251,552 B free over six folders, the same drive), so one figure says little.
FOLDERS = ("f2", "tmpabcdefgh", "feather2_base", "feather_folder_26_xxxxxxxx", "feather_folder_40_" + "x" * 22)


def folder_spread(names=FOLDERS, libs_as="mpy"):
    """robust_heap's figures for one staged drive copied into each folder name under one temporary
    folder (minutes: one robust_heap each): {"folders": {name: [heapsize, free heap needed]}, the
    least and most free heap needed (64-bit) and the margin of the most against FEATHER_FREE (32-bit)}."""
    rows = {}
    with tempfile.TemporaryDirectory() as tmp:
        first = os.path.join(tmp, names[0], "drive")
        stage(first, libs_as)
        for name in names:
            dest = os.path.join(tmp, name, "drive")
            if dest != first:
                shutil.copytree(first, dest)
            heap, best = robust_heap(dest, run_cfg())
            rows[name] = [heap, best["free"]]
    most = max(r[1] for r in rows.values())
    return {
        "folders": rows,
        "free_needed_64_least": min(r[1] for r in rows.values()),
        "free_needed_64_most": most,
        "margin_32_worst": FEATHER_FREE - to_32bit(most),
    }


def bench_feather(args):
    return measure(libs_as=getattr(args, "libs", "mpy"))


# Imported by code.py's CircuitPython-only lines, or needing the fake modules: not on a MicroPython board.
NOT_ON_PICO = ("code", "drivers.cp_hcsr04_pulsein")
PER_MODULE = os.path.join(VM_DIR, "heap_per_module.py")


def _heap_lines(text):
    """{module: (allocated, stays)} from heap_per_module.py's lines."""
    out = {}
    for line in text.splitlines():
        parts = line.split()
        if len(parts) == 4 and parts[0] == "heap":
            out[parts[1]] = (int(parts[2]), int(parts[3]))
    return out


def pico_ratio(min_bytes=1024):
    """PICO_RATIO's measurement (minutes: the emulated Pico boots and imports from source): the same
    .py imports on the emulated Pico and in the VM. Returns {"allocated"|"stays": {"total", "min",
    "max"}, "modules": {name: [pico allocated, pico stays, vm allocated, vm stays]}}; modules the VM
    gives under min_bytes are left out of the ratios (fixed costs differ there)."""
    from hexapod_host.pico import emulator

    with tempfile.TemporaryDirectory() as tmp:
        dest = os.path.join(tmp, "drive")
        stage(dest, "py")
        for name in ("boot.py", "code.py"):  # MicroPython would run boot.py; code.py is not imported here
            os.remove(os.path.join(dest, name))
        names = [m for m in import_order(dest) if m not in NOT_ON_PICO]
        script = os.path.join(tmp, "heap_per_module.py")
        with open(PER_MODULE) as f, open(script, "w") as g:
            g.write(f.read().replace("MODULES = []", "MODULES = %r" % names))
        vm_rows = _heap_lines(mpvm.run(script=script, heapsize="4m", search=(dest, os.path.join(dest, "lib"))))
        status, out, err, _ = emulator.run([script], fs=emulator.image(dest, os.path.join(tmp, "fs.img")))
        if status:
            raise RuntimeError("the emulated Pico failed: %s" % (err or out)[-500:])
        pico_rows = _heap_lines(out)
    result = {"modules": {n: list(pico_rows[n] + vm_rows[n]) for n in names if n in pico_rows and n in vm_rows}}
    for k, what in ((0, "allocated"), (1, "stays")):
        rows = [r for r in result["modules"].values() if r[2 + k] >= min_bytes and r[k] > 0]
        ratios = [r[k] / r[2 + k] for r in rows]
        total = sum(r[k] for r in rows) / sum(r[2 + k] for r in rows)
        result[what] = {"total": round(total, 3), "min": round(min(ratios), 3), "max": round(max(ratios), 3)}
    return result


if __name__ == "__main__":
    if sys.argv[1:2] == ["ratio"]:
        json.dump(pico_ratio(), sys.stdout, indent=1)
    elif sys.argv[1:2] == ["folders"]:
        json.dump(folder_spread(), sys.stdout, indent=1)
    else:
        json.dump(measure(*sys.argv[1:2]), sys.stdout, indent=1)
