# Runs inside the MicroPython VM: the CircuitPython deploy's heap, from its .py sources, on the fake
# CircuitPython modules (stubs/circuitpython_vm). Prints JSON lines. Reads a JSON object on stdin
# (not argv: the unix VM stops with "uncaught NLR" on an argument longer than 255 characters):
#   mode "run": the rig, then code.py's __main__ (import code, console; main(reader=code.SerialReader()))
#     for "frames" frames, with "commands" [[at_ms, line], ...] typed on the serial line; prints
#     {"base", "free", "after_import", "peak", "end", "frames", ...} (gc.mem_alloc bytes above the
#     rig's, base; free: gc.mem_free() when the deploy starts).
#   mode "modules": imports "modules" one by one in the order given (leaves first), printing for
#     each the bytes allocated while it imported with the collector off, and what stays after a
#     collection (both gc.mem_alloc differences).
#   mode "order": imports code.py (its board-only start) with __import__ wrapped, and prints
#     {"order": the deploy's modules in the order their imports began}. The wrapper allocates: the
#     heap figures of this mode mean nothing.
# Rig: "chips" [[address, osc_hz], ...] on the bus, "sonars" [[trigger, echo, distance], ...].
import gc
import json
import sys

cfg = json.loads(sys.stdin.read())

# The rig first: its code and models are on the heap before the deploy's first byte (the base).
import _cp_vm  # noqa: E402
import _stub_clock as clock  # noqa: E402
import _stub_i2c  # noqa: E402
import _stub_pins  # noqa: E402
import board  # noqa: E402, F401
import busio  # noqa: E402, F401
import digitalio  # noqa: E402, F401
import hcsr04_model  # noqa: E402
import microcontroller  # noqa: E402, F401
import pulseio  # noqa: E402, F401
import supervisor  # noqa: E402, F401
from pca9685_model import PCA9685Model  # noqa: E402

sys.modules["time"] = clock  # CircuitPython's time.sleep/monotonic_ns, on the virtual clock
sys.modules["machine"] = _cp_vm.NoMachine  # CircuitPython has none (the VM has one built in)
clock.reset(0)
_stub_pins.reset()
_stub_i2c.reset()
bus = _stub_i2c.shared_bus(None)
bus.clock_us = clock.now_us
chips = []
for address, osc_hz in cfg["chips"]:
    chips.append(PCA9685Model(address, osc_hz=osc_hz))
    bus.attach(chips[-1])
sonars = [hcsr04_model.HCSR04(t, e, distance=d) for t, e, d in cfg["sonars"]]
for at_ms, line in cfg.get("commands", ()):
    _cp_vm.SERIAL.send(at_ms, line)
peak = [0]


def sample():
    a = gc.mem_alloc()
    if a > peak[0]:
        peak[0] = a


def run():
    sample()
    import code  # noqa: F401  (the deploy's entry, as CircuitPython runs it)

    sample()
    gc.collect()
    after_import = gc.mem_alloc()
    reader = code.SerialReader()
    reader._in = _cp_vm.SERIAL  # the VM's sys.stdin cannot be swapped
    _cp_vm.SERIAL.watch = sample  # polled once a frame, by the console
    r = code.main(frames=cfg["frames"], reader=reader)
    sample()
    loaded = sorted(sys.modules)
    tick = sys.modules["hexapod.tick"]
    kept = [n for n in ("settings", "build", "board_pin") if hasattr(code, n)]  # code.main let them go
    kept += [n for n in ("start", "PollReader") if hasattr(sys.modules["console"], n)]
    kept += ["Robot.__init__"] if tick.Robot.__init__ is not None else []
    gc.collect()
    return {
        "loaded": loaded,
        "after_import": after_import - base,
        "peak": peak[0] - base,
        "end": gc.mem_alloc() - base,
        "frames": r.frames,
        "mode": r.robot.mode,
        "bus_failed": r.bank.failed_frames,
        "sonar_faults": r.sonar_faults,
        "follow": r.follower.mode_name,
        "builders_kept": kept,
    }


def modules():
    rows = []
    for name in cfg["modules"]:
        gc.collect()
        a0 = gc.mem_alloc()
        gc.disable()
        __import__(name)
        a1 = gc.mem_alloc()
        gc.enable()
        gc.collect()
        rows.append([name, a1 - a0, gc.mem_alloc() - a0])
    return {"modules": rows}


def order():
    import builtins

    began = []
    plain = builtins.__import__

    def record(name, *args):
        if name not in sys.modules and name not in began:
            began.append(name)
        return plain(name, *args)

    builtins.__import__ = record  # the VM calls an overriding builtins.__import__ for import statements
    try:
        import code  # noqa: F401
    finally:
        builtins.__import__ = plain
    return {"order": began}


gc.collect()
base = gc.mem_alloc()
free = gc.mem_free()
out = {"run": run, "modules": modules, "order": order}[cfg["mode"]]()
out["base"] = base
out["free"] = free  # what the deploy starts with
print(json.dumps(out))
