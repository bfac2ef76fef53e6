"""`hexapod view --port` and `--pico` in a real headless Chromium (Selenium): a virtual board's pty
is a board on a serial port from the host's view, and the stand button stands it (counted in the
board's own frames, its trace); the emulated Pico's telemetry reaches the page (its frame counter
rises). No wall-clock bounds: the waits are hang guards. Skips without Chromium, the MicroPython
VM or the Pico emulator; under CI a missing browser fails."""

import re

import pytest

from hexapod_host.pico import emulator
from hexapod_host.view import browser as vb
from tests.test_view_drive_browser import STAND_FRAMES, frames_pass, modes, stand, text

# Hang guards: the emulated Pico boots main.py (~4 emulated s) 10-20 times slower than real time
# on the loaded 2-core machine, and streams a line every other emulated frame.
PICO_SERVE_S = 1200
PICO_LINES_S = 300


def test_port_on_a_virtual_boards_pty_loads_and_the_stand_button_stands_it(tmp_path):
    vb.require()
    from hexapod_host.testing.runtimes import micropython_missing

    if micropython_missing():
        pytest.skip(micropython_missing())
    board = vb.VirtualBoard(tmp_path / "trace.txt")
    try:
        with vb.driving(("--port", board.path)) as (driver, server):
            frames_pass(board, 50)
            assert vb.wait_for(lambda: "(ok stream 25)" in text(driver, "drive-board"))
            assert "hexapod view: port" in driver.page_source
            f0 = stand(driver, board)
            standing = next(m[0] for m in modes(board.trace(), f0) if m[1] == 3)
            assert standing - f0 <= STAND_FRAMES
            assert vb.wait_for(lambda: "robot standing" in text(driver, "status")), text(driver, "status")
            assert vb.page_errors(driver) == []
    finally:
        board.stop()


def page_frame(driver):
    m = re.search(r"frame (\d+)", text(driver, "status"))
    return int(m.group(1)) if m else 0


@pytest.mark.skipif(emulator.missing() is not None, reason=emulator.missing() or "")
def test_pico_telemetry_reaches_the_page():
    vb.require()
    with vb.driving(("--pico",), timeout=PICO_SERVE_S) as (driver, server):
        assert vb.wait_for(lambda: "(ok stream 25)" in text(driver, "drive-board"))
        assert "hexapod view: pico" in driver.page_source
        first = vb.wait_for(lambda: page_frame(driver), timeout=PICO_LINES_S)
        assert first, text(driver, "status")
        # The board's own frame counter, from its telemetry: it rises while the page looks.
        assert vb.wait_for(lambda: page_frame(driver) > first, timeout=PICO_LINES_S), text(driver, "status")
        # The emulated front sonar at pico serial's default wall, 30 cm (its echo timed within 0.2 mm).
        front = r"(?m)^front\s+(299\.[89]|300\.[0-2])\s+ok"
        assert vb.wait_for(lambda: re.search(front, text(driver, "readings")), timeout=PICO_LINES_S), text(
            driver, "readings"
        )
        assert vb.page_errors(driver) == []
    assert "source pico, ok stream 25" in server.output
