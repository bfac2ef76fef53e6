"""boards/feather_rp2040_micropython.py on the emulated RP2040: `hexapod flash`'s image for a
Feather RP2040 running MicroPython, its emulated PCA9685s on I2C1 (GPIO2/3, the STEMMA QT) and its
HC-SR04s on GPIO6-13, 26 and 27, gives the very bursts the host's stub machine gives for the Pico
(the same robot, the same channel map: only the pins differ)."""

import pytest

from hexapod_host.pico import emulator as pico
from hexapod_host.pico import loop as pico_loop

REASON = pico.missing()
pytestmark = pytest.mark.skipif(REASON is not None, reason=REASON or "")

BOARD = "feather_rp2040_micropython"
FRAMES = 100  # stand up, then tripod walking from frame 60


def test_the_feather_on_micropython_stands_walks_and_reads_its_sonars():
    with pico.flashed(board=BOARD) as fs:
        status, lines, bursts, stats = pico_loop.board(FRAMES, fs, board_name=BOARD)
    assert status == 0, "\n".join(lines)
    _, host_bursts = pico_loop.host(FRAMES)
    assert len(bursts) == 2 * FRAMES and bursts == host_bursts  # bit-identical to the Pico's on the stub
    s = pico_loop.summary(lines)
    print("feather on micropython, emulated:", s)
    assert s["heap_bytes_per_frame"] == 0
    refills, done, nacks = s["sender"]  # the background sender drove I2C1's block (0x40048000)
    assert done == 2 * FRAMES and nacks == 0
    status_line = [line for line in lines if line.startswith("frames ")][-1]
    assert "bus_failed 0 reinit 0 sonar_faults 0" in status_line
    dist = [int(v) for v in status_line.split("dist [")[1].split("]")[0].split(",")]
    assert all(abs(d - e) <= 2 for d, e in zip(dist, pico_loop.DISTANCES, strict=True)), dist
