"""main.py with the console: the calibration notice at boot, Ctrl-C relaxes (or holds) the
servos and leaves `runner` for the REPL, the watchdog is fed every frame; the board file's
console settings are checked at load."""

import ast

import pytest

from tests.console_rig import clean_stubs  # noqa: F401 (autouse fixture)

SCENARIO = "scenarios.console_main:"


@pytest.mark.parametrize("on_exit", ["relax", "hold"])
def test_ctrl_c_relaxes_or_holds_and_leaves_the_runner(rt, on_exit):
    src = "from scenarios.console_main import ctrl_c\nctrl_c(%r)\n" % (on_exit,)
    out = rt.run(src).splitlines()
    assert out[0] == "cal: no hexapod_cal.txt; the robot file's calibration is in use"
    # boot="stand", calibrated=True: the host run vouches for the calibration the file would give
    assert out[1] == "boot: standing up (the board file's boot setting is stand, the servos are calibrated)"
    assert out[2].startswith("ok leg 1 angles ")  # the console answered while the loop ran
    assert out[3] == "stopped: servos %s; runner.run() resumes" % ("relaxed" if on_exit == "relax" else "held")
    same, frames, widths, mode, expired, timeout = ast.literal_eval(out[4])
    assert same and frames > 5 and not expired and timeout == 4000
    if on_exit == "relax":
        assert widths == [0] * 18 and mode == 0
    else:
        assert 0 not in widths and mode != 0  # every servo still holds its last pulse


def test_watchdog_starves_when_the_loop_stops(rt):
    assert rt.call(SCENARIO + "watchdog") == [False, True]


@pytest.mark.parametrize(
    "key, value, message",
    [
        ("watchdog_ms", 500, "board 'pico': watchdog_ms: 500, allowed 4000..8000 ms (or None: no watchdog)"),
        ("watchdog_ms", 3999, "board 'pico': watchdog_ms: 3999, allowed 4000..8000 ms (or None: no watchdog)"),
        ("watchdog_ms", 8001, "board 'pico': watchdog_ms: 8001, allowed 4000..8000 ms (or None: no watchdog)"),
        ("watchdog_ms", 9000, "board 'pico': watchdog_ms: 9000, allowed 4000..8000 ms (or None: no watchdog)"),
        ("watchdog_ms", "2s", "board 'pico': watchdog_ms: '2s', allowed 4000..8000 ms (or None: no watchdog)"),
        ("on_exit", "freeze", "board 'pico': on_exit: 'freeze', allowed 'relax' or 'hold'"),
        ("walk_timeout_ms", 100, "board 'pico': walk_timeout_ms: 100, allowed 200..10000 ms"),
    ],
)
def test_console_settings_are_checked_at_load(key, value, message):
    import copy

    import boards.pico
    from hexapod import board

    b = copy.deepcopy(boards.pico.BOARD)
    b[key] = value
    with pytest.raises(ValueError) as e:
        board.validate(b)
    assert str(e.value) == message
    # and the range ends are accepted
    ends = {"watchdog_ms": (4000, 8000, None), "walk_timeout_ms": (200, 10000, None), "on_exit": ("hold", "relax")}
    for ok in ends[key]:
        b[key] = ok
        board.validate(b)


def test_console_bench_rows(mp):
    import json
    import os

    from hexapod_host import mpvm
    from hexapod_host.bench.tick import CONSOLE_HEAP, CONSOLE_SCRIPT

    assert os.path.exists(CONSOLE_SCRIPT)
    result = json.loads(mpvm.run(script=CONSOLE_SCRIPT, heapsize=CONSOLE_HEAP, args=("3",)).strip().splitlines()[-1])
    rows = {r["line"]: r for r in result["frames"]}
    assert rows["(idle)"]["heap_bytes"] == 0  # the idle console frame allocates nothing
    assert rows["x" * 24]["heap_bytes"] == 0  # an over-long line's reply is a constant
    assert all(0 < r["median_us"] <= r["max_us"] for r in result["frames"] if r["line"] != "(idle)")
    assert {"get 2", "status", "foot 2 130 5 -80", "nudge 2 0.5 0 0", "trim 2 femur 5"} <= set(rows)


def test_poll_reader_on_an_open_line_with_nothing_waiting_allocates_nothing(mp):
    """MicroPython's reader itself (select.poll on stdin, kept open and silent): 0 bytes a frame;
    then a line written to it is answered."""
    import os
    import subprocess

    from hexapod_host import mpvm
    from hexapod_host.testing.runtimes import TESTS

    src = "from scenarios.console_main import poll_reader\npoll_reader()\n"
    proc = subprocess.Popen(
        [mpvm.executable(), "-X", "heapsize=4m", "-c", src],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        env=dict(os.environ, MICROPYPATH=os.pathsep.join((mpvm.search_path(), TESTS))),
    )
    try:
        first = proc.stdout.readline()
        assert first == b"0\n"
        proc.stdin.write(b"get 6\n")
        proc.stdin.flush()
        assert proc.stdout.readline().startswith(b"ok leg 6 angles ")
        assert proc.wait(30) == 0
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
