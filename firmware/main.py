"""Board entry point (MicroPython). Edit BOARD and ROBOT to match yours (boards/, robots/). The body
is startup.py (flashed compiled: MicroPython compiles this file at every boot, so it stays short)."""

import sys

# The built-in modules the loop's files import, put in sys.modules first: MicroPython looks for a
# file of an extensible built-in's name (array, time, machine, ...) in every sys.path entry at
# each import before it takes the built-in (~4 ms of littlefs lookups on a Pico, 24 times at boot).
# With sys.path empty for a moment it takes the built-in at once. Only on the boards' ports: the
# host's MicroPython VM finds the tests' stub machine, time, ... as files.
if sys.platform in ("rp2", "esp32"):
    _path = sys.path[:]
    sys.path.clear()
    for _name in ("array", "binascii", "machine", "os", "select", "time"):
        try:  # noqa: SIM105 (no contextlib on MicroPython)
            sys.modules[_name] = __import__(_name)
        except ImportError:
            pass  # not in this port's image: imported from the files as before
    sys.path.extend(_path)
    del _path, _name

import time  # noqa: E402

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
