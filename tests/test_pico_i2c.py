"""The background I2C sender (drivers/_i2c_rp2.py) on the emulated Pico: a chip whose supply a GPIO
switches off mid-run (it NACKs its address, as an unplugged board) and back on (power-on reset:
asleep, MODE1 0x11) gives the status bits and counters the data sheet's behaviour predicts, on
the blocking path and on the sender (there one frame later: a burst's outcome comes with the
next frame), worked out by hand below, not from the driver."""

import json
import os
import tempfile

import pytest

from hexapod_host.pico import emulator as pico

REASON = pico.missing()
pytestmark = pytest.mark.skipif(REASON is not None, reason=REASON or "")

POWER_PIN = 22  # a free GPIO on the pico board file: drives the emulated 0x41's supply
OFF, ON, FRAMES = 22, 30, 40  # chip 0x41 powered off before frame 22, back on before frame 30

SCRIPT = """
import json, sys, time
from machine import I2C, Pin
from drivers import pca9685
from hexapod import board as boards
from hexapod import robotcal
board = boards.load("pico")
table = boards.servo_table(board, robotcal.servo_maps(robotcal.load("default")))
bus = board["i2c"]
i2c = I2C(bus["id"], scl=Pin(bus["scl"]), sda=Pin(bus["sda"]), freq=bus["freq"])
power = Pin(%d, Pin.OUT, value=0)
bank = pca9685.servo_bank(i2c, board["pca9685"], table, background=%r)
pulses = [1500] * 18
out = []
for n in range(%d):
    if n == %d:
        power.value(1)
    if n == %d:
        power.value(0)
    out.append(bank.write_frame(pulses))
    time.sleep_ms(20)
bank.write_frame([1000] * 18)  # two frames back to back: the second waits for the first's bus
bank.write_frame([2000] * 18)
end = bank.sync()
bg = bank._sender
print(json.dumps({"status": out, "sync": end, "failed_frames": bank.failed_frames, "reinits": bank.reinits,
                  "errors": [c.errors for c in bank.chips], "resets": [c.resets_seen for c in bank.chips],
                  "errno": [c.last_errno for c in bank.chips], "stats": list(bg.stats) if bg else None}))
"""


def on_board(background, fs):
    src = SCRIPT % (POWER_PIN, background, FRAMES, OFF, ON)
    with tempfile.TemporaryDirectory() as tmp:
        trace = os.path.join(tmp, "trace.jsonl")
        status, out, err, _ = pico.run_source(
            src, fs=fs, devices=pico.devices(power_pins={0x41: POWER_PIN}), trace=trace
        )
        with open(trace) as f:
            bursts = [(r["chip"], r["counts"]) for r in map(json.loads, f) if "chip" in r]
    assert status == 0, out + err
    got = json.loads(out.strip().splitlines()[-1])
    got["bursts"] = bursts
    return got


@pytest.fixture
def fs(pico_fs):
    """The staged firmware's littlefs image (what a flash puts on the board): conftest's, one a test process."""
    return pico_fs


def expected(background):
    """Per-frame status bits by hand. retries=2: a NACKed burst is tried 3 times, then FAILED (2);
    check_every=10: MODE1 is read back on a chip's 10th flush since the last read; a chip powered
    up again is asleep with MODE1 0x11, which that read finds: init again, REINIT (4). Blocking:
    both chips read MODE1 on frames 9, 19, 29, 39; frames 22..29 fail (frame 29's read fails too:
    3 more errors), frame 39 finds the reset. Sender: 0x41's reads are 5 frames apart from 0x40's
    (frames 4, 14, 24, 34), and a burst's outcome shows one frame later: frames 23..30 fail (frame
    24's read in the dark adds 3 errors), frame 34 finds the reset."""
    status = [0] * FRAMES
    late = 1 if background else 0
    for n in range(OFF + late, ON + late):
        status[n] = 2
    status[34 if background else 39] = 4
    return status


@pytest.mark.parametrize("background", [False, True])
def test_a_chip_powered_off_and_on_mid_run(background, fs):
    got = on_board(background, fs)
    assert (got["stats"] is not None) == background  # the sender is what the board really used
    assert got["status"] == expected(background)
    # 8 failed frames of 3 tries each, and one MODE1 read in the dark (3 tries): 27 errors.
    assert got["failed_frames"] == ON - OFF and got["reinits"] == 1
    assert got["errors"] == [0, 3 * (ON - OFF) + 3] and got["resets"] == [0, 1]
    assert got["sync"] == 0  # the last frame's bursts went through
    # The two frames written back to back both arrived, in order: 1000 and 2000 us are
    # round(t * 25 MHz / 122) = 205 and 410 counts at PRE_SCALE 121 (data sheet eq. 1).
    last = [(0x40, 205), (0x41, 205), (0x40, 410), (0x41, 410)]
    assert [(a, c[:9]) for a, c in got["bursts"][-4:]] == [(a, [n] * 9) for a, n in last]
    if background:
        refills, done, nacks = got["stats"]
        assert done == 2 * (FRAMES + 2) - (ON - OFF)  # every burst but the failed ones
        assert nacks == 3 * (ON - OFF)  # the address NACKs the sender saw (the reads are blocking)
        assert got["errno"] == [0, 5]  # EIO, what machine.I2C raises for a NACK on silicon
