import os

import pytest

import hexapod_host  # noqa: F401  (puts firmware, boards and shims on sys.path)
from hexapod_host.pico import emulator as pico

pytest_plugins = ["hexapod_host.testing.runtimes"]


def pytest_sessionstart(session):
    """Under CI the emulated Pico's tests must run, never skip: stop at once, saying what is missing."""
    if os.environ.get("CI") and os.environ.get("CI") != "false":
        reason = pico.missing()
        if reason:
            raise pytest.UsageError("CI runs every Pico test, but the emulated Pico cannot start: " + reason)
