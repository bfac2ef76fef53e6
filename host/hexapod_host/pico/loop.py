"""The whole loop (vm/loop_frames.py: main.build, stand up, tripod walking) on the emulated Pico
with its emulated PCA9685s and HC-SR04s, and the same script on the host's stub machine; both
give the PCA9685 bursts as (address, 16 channel counts) and the script's output."""

import json
import os
import tempfile

from hexapod_host import VM_DIR
from hexapod_host.pico import emulator as pico
from hexapod_host.testing.runtimes import CPythonRuntime

SCRIPT = os.path.join(VM_DIR, "loop_frames.py")
DISTANCES = (3000, 4000, 5000, 6000, 7000)  # 0.1 mm, drivers.hcsr04 order

# The stub machine as main.build finds it: the board file's chips on bus 0 and sonars on its pins.
# Each chip records its LED counts at every STOP that followed an LED register write.
HOST_SETUP = """
import sys
import _stub_clock as clock
import stub_board

BOARD = stub_board.reset("pico")
BURSTS = []


def recorder(m):
    stop = m.on_stop
    write_reg = m._write_reg
    led = [0]

    def _write_reg(p, v):
        if 6 <= p <= 0x45:
            led[0] += 1
        write_reg(p, v)

    def on_stop():
        stop()
        if led[0]:
            led[0] = 0
            BURSTS.append((m.address, counts(m.regs)))

    m.on_stop = on_stop
    m._write_reg = _write_reg


def counts(r):
    # (OFF - ON) mod 4096 per channel; -1 full off, 4096 full on (as host/pico/run.mjs decodes)
    out = []
    for ch in range(16):
        b = 6 + 4 * ch
        on = r[b] | (r[b + 1] & 15) << 8
        off = r[b + 2] | (r[b + 3] & 15) << 8
        out.append(-1 if r[b + 3] & 16 else 4096 if r[b + 1] & 16 else (off - on) & 4095)
    return out


bus, chips = stub_board.pca9685_models(BOARD, attach=False)
for m in chips.values():
    recorder(m)
    bus.attach(m)
SONAR = stub_board.sonar_models(BOARD, %r)
sys.argv[:] = ["host", "%d", "%s"]
"""


def _script():
    with open(SCRIPT) as f:
        return f.read()


def host(frames, scenario="default"):
    """(output lines, bursts) of the loop on the stub machine (CPython)."""
    out = CPythonRuntime().run(HOST_SETUP % (DISTANCES, frames, scenario) + _script() + "\nprint('BURSTS', BURSTS)\n")
    lines = out.splitlines()
    bursts = [(a, list(c)) for a, c in eval(lines[-1][len("BURSTS ") :])]  # noqa: S307 (our own repr)
    return lines[:-1], bursts


def board(frames, fs, scenario="default", board_name="pico"):
    """(status, output lines, bursts, stats) of the loop on the emulated Pico (fs staged for
    board_name, whose pins the emulated chips are wired to)."""
    with tempfile.TemporaryDirectory() as tmp:
        script = os.path.join(tmp, "loop_frames.py")
        with open(script, "w") as f:
            f.write("import sys\nsys.argv[:] = ['pico', '%d', '%s']\n" % (frames, scenario) + _script())
        trace = os.path.join(tmp, "trace.jsonl")
        status, out, err, stats = pico.run(
            [script], fs=fs, devices=pico.devices(board_name, distances=list(DISTANCES)), trace=trace
        )
        with open(trace) as f:
            records = [json.loads(line) for line in f]
    bursts = [(r["chip"], r["counts"]) for r in records if "chip" in r]
    stats["echo_us"] = sorted({r["echo_us"] for r in records if "ping" in r})
    return status, (out + err).splitlines(), bursts, stats


def summary(lines):
    """The loop script's JSON line."""
    return json.loads([line for line in lines if line.startswith("{")][-1])


def boot_main(seconds, fs, times=None):
    """(status, output, bursts) of the image's own main.py, unmodified, for `seconds` emulated
    seconds from power-up (no calibration file: it boots relaxed, every channel full-off); times,
    a list, gets each burst's emulated time (us since power-up)."""
    with tempfile.TemporaryDirectory() as tmp:
        trace = os.path.join(tmp, "trace.jsonl")
        status, out, err, _ = pico.run(
            fs=fs, devices=pico.devices(distances=list(DISTANCES)), trace=trace, main_seconds=seconds
        )
        with open(trace) as f:
            records = [json.loads(line) for line in f if '"chip"' in line]
    if times is not None:
        times.extend(r["t"] for r in records)
    return status, out + err, [(r["chip"], r["counts"]) for r in records]


def host_main(frames):
    """(output, bursts) of main.main(frames) on the stub machine (CPython)."""
    run_main = "import main\nmain.main(%d, clock=clock)\nprint('BURSTS', BURSTS)\n" % frames
    lines = CPythonRuntime().run(HOST_SETUP % (DISTANCES, frames, "default") + run_main).splitlines()
    return lines[:-1], [(a, list(c)) for a, c in eval(lines[-1][len("BURSTS ") :])]  # noqa: S307
