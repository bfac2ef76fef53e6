"""The portable core (integers only, no I/O, no clock)."""

# The firmware's version: `selftest` and `hexapod doctor` report it; keep pyproject.toml's in step
# (tests/test_selftest.py checks).
VERSION = "0.1.0"

# What main.py's start-up and code.py release once the robot's files are read, with the robot's two
# files: the board file's validator, the robot file's and the calibration file's checks, their
# helpers, and what builds from the files as flashed without them (hexapod.wiring). Here, not in
# runner: code.py lets them go before the loop's modules load.
BOOT_ONLY = ("hexapod.board", "hexapod.robotfile", "hexapod.robotcal", "hexapod.check", "hexapod.wiring")


def release(*names):
    """Forget boot-only modules (the board file's validator, the robot file once its geometry is
    built) so the heap their code takes goes back to the loop (7-8 KB on a Pico); a later import
    loads them again."""
    import sys

    if sys.implementation.name == "cpython":
        return  # the host's tests share one process and hold these modules: nothing to win there
    for name in names:
        if name in sys.modules:
            del sys.modules[name]
            package, _, leaf = name.rpartition(".")
            if package in sys.modules and hasattr(sys.modules[package], leaf):
                delattr(sys.modules[package], leaf)
