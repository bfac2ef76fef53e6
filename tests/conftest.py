import os
import sys
import tempfile

import pytest
from _pytest.nodeid import NodeId

import hexapod_host  # noqa: F401  (puts firmware, boards and shims on sys.path)
from hexapod_host.pico import emulator as pico
from hexapod_host.serial import flash

pytest_plugins = ["hexapod_host.testing.runtimes"]


def pytest_configure(config):
    """One folder of mpy-cross outputs for the run (hexapod_host.serial.flash.compile_mpy, keyed by
    binary, arguments and source bytes): the dozens of stagings compile each source once. Made by
    the controlling process, so that its test workers (and what they start) inherit it."""
    if hasattr(config, "workerinput") or os.environ.get(flash.MPY_CACHE_ENV):
        return
    config._mpy_cache = tempfile.TemporaryDirectory(prefix="hexapod-mpy-")
    os.environ[flash.MPY_CACHE_ENV] = config._mpy_cache.name


def pytest_unconfigure(config):
    cache = getattr(config, "_mpy_cache", None)
    if cache is not None:
        os.environ.pop(flash.MPY_CACHE_ENV, None)
        cache.cleanup()


def pytest_sessionstart(session):
    """Under CI the emulated Pico's tests must run, never skip: stop at once, saying what is missing."""
    if os.environ.get("CI") and os.environ.get("CI") != "false":
        reason = pico.missing()
        if reason:
            raise pytest.UsageError("CI runs every Pico test, but the emulated Pico cannot start: " + reason)


# The longest single tests, longest first (minutes each on 2 loaded cores), then the modules whose
# tests take tens of seconds (emulated Pico, Chromium, long VM runs): started first, so that
# neither worker is left running one of them alone at the end. From `pytest -n 2 --durations=0`
# of the whole suite on 2026-11-27 (load 5-30: other helpers' runs): the first two took 749 and
# 740 s there, and the run's wall time was 80 min for 1037 s of this process's own CPU.
LONGEST = (
    "test_rescale.py::test_rescale_equals_the_plain_form_on_the_emulated_pico",
    "test_tick_viper.py::test_viper_paths_equal_plain_code_on_the_emulated_pico",
    "test_tick_ranges.py::test_every_intermediate_of_the_tick_fits_a_small_int",
    "test_pico.py::test_viper_on_thumb_equals_plain_solver_and_cpython",
    "test_pico.py::test_every_module_imports_as_mpy_with_the_heap_left",
    "test_pico_battery.py::test_the_battery_scenario_on_the_emulated_pico",
    "test_console_sequences.py::test_random_command_sequences_never_freeze",
)
SLOW_MODULES = (
    "test_pico",
    "browser",
    "test_rescale",
    "test_tick_viper",
    "test_tick_ranges",
    "test_flash",
    "test_console_sequences",
    "test_replan",
    "test_leg_accuracy",
    "test_servo_guard",
    "test_wall_sim",
)


def _shares_a_module_fixture(item):
    info = getattr(item, "_fixtureinfo", None)
    defs = info.name2fixturedefs.values() if info else ()
    module = item.nodeid.split("::")[0]
    return any(d and d[-1].scope == "module" and d[-1].baseid == module for d in defs)


def _tier(item):
    name = "%s::%s" % (item.path.name, item.originalname)
    if name in LONGEST:
        return (0, LONGEST.index(name))
    if any(word in item.path.name for word in SLOW_MODULES) or item.get_closest_marker("xdist_group"):
        return (1, 0)
    return (2, 0)


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(config, items):
    """Under xdist (-n, `--dist loadgroup` from pyproject.toml): the tests of a module that share
    its module-scoped fixture (an emulated-Pico image, a browser page, one long VM run) are one
    xdist_group, so that fixture is set up on one worker, not on both; and the slow tests go
    first. pytest-randomly has shuffled already (its hook wraps), and the sort is stable: the
    order within a tier is still the seed's."""
    for item in items:
        if _shares_a_module_fixture(item):
            item.add_marker(pytest.mark.xdist_group(item.module.__name__))
            if getattr(config.option, "loadgroup", False):  # an xdist worker under --dist loadgroup
                # xdist 3.8 names the group by appending "@group" to item._nodeid, which pytest 9
                # no longer reads (the node id is item._id): without this every group was spread
                # over both workers (seen: test_gait's `tables` built on each). Done as xdist does it.
                item._id = NodeId.parse("%s@%s" % (item.nodeid, item.module.__name__))
    items.sort(key=_tier)


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


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    """A failed test with a view server or browser still open reports their logs (a socket lost
    under load, a page reloaded): the failure's cause, which its own assertion cannot see."""
    outcome = yield
    report = outcome.get_result()
    vb = sys.modules.get("hexapod_host.view.browser")
    if report.failed and vb is not None:
        why = vb.diagnose()
        if why:
            report.sections.append(("view servers and pages", why))
