"""Board entry point (MicroPython). Edit BOARD and ROBOT to match yours (boards/, robots/). The body
is startup.py (flashed compiled: MicroPython compiles this file at every boot, so it stays short)."""

import time

BOARD = "pico"
ROBOT = "default"
# The robot file first, into a heap the loop's modules have not yet cut up (MemoryError after them).
__import__("robots." + ROBOT)

import startup  # noqa: E402
from startup import SONAR_SAMPLES, STATUS_FRAMES, fault_keeper, watchdog_reset  # noqa: E402, F401


def build(board_name=BOARD, robot_name=ROBOT, clock=time, **kw):
    """startup.build (kw: max_range, samples, bank)."""
    return startup.build(board_name, robot_name, clock, **kw)


def main(frames=-1, clock=time, board_name=BOARD, robot_name=ROBOT, reader=None, boot=None, calibrated=None):
    """Build and startup.run; the Runner, in `runner` from the build on (the REPL's after Ctrl-C)."""
    global runner
    r = runner = build(board_name, robot_name, clock)
    startup.run(r, frames, robot_name, reader, boot, calibrated)
    return r


runner = None

if __name__ == "__main__":
    import gc

    gc.collect()  # the imports' garbage, here where no stale stack pointer keeps it (MemoryError in build)
    import console

    main(reader=console.PollReader())
