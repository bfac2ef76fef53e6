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


@pytest.fixture
def virtual_board():
    """start(cal_dir) -> (pty path, an open Link): `hexapod virtual-board` for pico/default in the
    MicroPython VM (cal_dir "": no calibration filesystem); every board started is stopped after.
    start(cal_dir, world=W) -> (pty path, link, room): its sonars in world W's room (--world)."""
    from hexapod_host.commands.console import start_virtual_board
    from hexapod_host.serial.link import Link
    from hexapod_host.testing.runtimes import micropython_missing

    if micropython_missing():
        pytest.skip(micropython_missing())
    started = []

    def start(cal_dir, world=None):
        proc, path, master, slave = start_virtual_board("pico", "default", cal_dir, world=world)
        link = Link.open(path, timeout=10)
        started.append((proc, master, slave, link))
        link.request("help")  # the VM is up
        return (path, link) if world is None else (path, link, proc.room)

    yield start
    for proc, master, slave, link in started:
        link.close()
        proc.terminate()
        proc.wait(10)
        os.close(master)
        os.close(slave)
