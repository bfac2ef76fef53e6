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


# The longest tests and the modules whose tests share one module fixture (so one xdist group, run
# on one worker: their sum), longest first: started first, so that neither worker is left running
# one of them alone at the end (longest processing time first). From `pytest -n 2 --durations=60`
# of the whole suite on 2026-11-28 (2 cores shared with other runs: 580 s wall, 541 s CPU), the
# browser test's from CI; a parametrized test counts once a parameter.
LONGEST = (
    "test_pico_loop.py",  # the `boot` fixture (15 s), the stream and gait-change runs (20 s each), ...
    "test_pico_flash.py::test_flash_the_emulated_pico_over_a_pty_then_boot_it",  # 66 s
    "test_view_sources_browser.py::test_pico_telemetry_reaches_the_page",  # ~60 s in CI
    "test_pico_battery.py::test_the_battery_scenario_on_the_emulated_pico",  # 38 s
    "test_pico.py",  # 19 + 10 + 8 s
    "test_pico_wiring.py::test_the_flashed_files_build_without_the_checks_and_an_edited_one_is_checked",  # 36 s
    "test_console_sequences.py::test_random_command_sequences_never_freeze",  # 2 x 23-30 s
    "test_tick_viper.py::test_viper_paths_equal_plain_code_on_the_emulated_pico",  # 5 x 15-20 s
    "test_virtual_board_room.py::test_wall_left_12_follows_the_wall_world_at_12_cm",  # 20 s, real time
    "test_rescale.py::test_rescale_equals_the_plain_form_on_the_emulated_pico",  # 20 s
    "test_console_fuzz.py::test_the_property_really_runs_ten_thousand_lines",  # 18 s
    "test_view_calibrate_all.py::test_all_18_joints_calibrated_from_the_page_on_the_virtual_board",  # 14 s
    "test_pico_i2c.py",  # 2 x 6-7 s
    "test_pico_cli.py::test_serial_attaches_the_boards_chips_and_sonars_at_the_distances_given",  # 10 s
    "test_pico_faults.py::test_the_fault_log_outlives_a_soft_reset",  # 10 s
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
    for name in ("%s::%s" % (item.path.name, item.originalname), item.path.name):
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


@pytest.fixture(scope="session")
def pico_fs():
    """The staged firmware's littlefs image (pico/default: what a flash puts on the board), made once
    a test process and only read: the emulator loads it into its flash, and what a board writes goes
    elsewhere (save_fs). Session-wide, so the tests that boot it spread over the workers (a module
    fixture would make their module one xdist group)."""
    with pico.flashed() as path:
        yield path


@pytest.fixture
def virtual_board():
    """start(cal_dir) -> (pty path, an open Link): `hexapod virtual-board` for pico/default in the
    MicroPython VM (cal_dir "": no calibration filesystem); every board started is stopped after.
    start(cal_dir, world=W) -> (pty path, link, room): its sonars in world W's room (--world).
    pace: start_virtual_board's ("" real time, or "eager")."""
    from hexapod_host.commands.console import start_virtual_board
    from hexapod_host.serial.link import Link
    from hexapod_host.testing.runtimes import micropython_missing

    if micropython_missing():
        pytest.skip(micropython_missing())
    started = []

    def start(cal_dir, world=None, pace=""):
        proc, path, master, slave = start_virtual_board("pico", "default", cal_dir, world=world, pace=pace)
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
