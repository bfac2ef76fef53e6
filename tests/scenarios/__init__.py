"""Two-runtime scenarios: firmware-side code the tests run on CPython and in the MicroPython VM.

Each module here is imported as `scenarios.<name>` by both runtimes (hexapod_host.testing puts
tests/ on both paths). A scenario function takes plain arguments and returns a plain value
(ints, strings, lists, tuples, dicts); the test calls it through `rt.call` and keeps the asserts.
MicroPython-compatible Python only: no dataclasses, no f-strings, no typing.
"""


def on_board(*names):
    """(host path, board path) of scenario modules, for hexapod_host.pico.emulator.flashed(extra=...)."""
    import os

    here = os.path.dirname(os.path.abspath(__file__))
    return [(os.path.join(here, n), "scenarios/" + n) for n in ("__init__.py",) + names]
