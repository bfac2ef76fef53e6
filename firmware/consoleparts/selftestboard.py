"""selftest's board checks (`calibration`, `reset_cause`, `faults`, `heap`, `supply`): selftest.Checks
imports this module for its first step after the bus checks and lets it go after them (on
CircuitPython, which compiles a module's source at each import, a smaller compile than one module).
"""

import gc

HEAP_LOW = 16384  # bytes free below which the heap check fails
_RESETS = ("PWRON_RESET", "HARD_RESET", "WDT_RESET", "DEEPSLEEP_RESET", "SOFT_RESET")
_RESET_WORDS = ("power_on", "hard", "watchdog", "deepsleep", "soft")


def run(checks, out, battery):
    """The board's checks, each a line: calibration, reset_cause, faults, heap, supply."""
    calibration(checks, out)
    reset(checks, out)
    faults(checks, out)
    heap(checks, out)
    supply(checks, out, battery)


def calibration(checks, out):
    """The calibration file's CRC as it is on the flash (calstore, let go after unless a
    calibration session has it)."""
    import sys

    from hexapod import release

    kept = "calstore" in sys.modules
    try:
        _calibration(checks, out)
    finally:
        if not kept:
            release("calstore")


def _calibration(checks, out):
    store = checks.con.cal_store()
    src = checks.con.cal_source
    if store is None:
        checks._line(out, True, "calibration n/a (no filesystem on this console; in force: %s)" % src)
        return
    try:
        crc = store.check()
    except ValueError as e:
        checks._line(
            out,
            False,
            "calibration %s: the robot file's defaults are in use at boot (in force now: %s): calibrate and "
            "'save' (docs/jog.md)" % (e, src),
        )
        return
    checks._line(out, True, "calibration %s crc %04x (in force: %s)" % (store.path, crc, src))


def reset(checks, out):
    try:
        import machine

        cause = machine.reset_cause()
    except (ImportError, AttributeError):
        checks._line(out, True, "reset_cause n/a (no machine.reset_cause on this port)")
        return
    word = "code_%d" % cause
    for i in range(len(_RESETS)):
        if getattr(machine, _RESETS[i], None) == cause:
            word = _RESET_WORDS[i]
    if word == "watchdog":
        checks._line(
            out,
            False,
            "reset_cause watchdog: the loop stalled past the board file's watchdog_ms and the watchdog reset "
            "the board: a traceback at the REPL shows why (run with watchdog_ms None to see it)",
        )
        return
    checks._line(out, True, "reset_cause " + word)


def faults(checks, out):
    """The fault log (runner.faultlog): a sonar's lost echo is news, the rest is a fault to fix."""
    import console

    from hexapod import faultlog

    log = checks.runner.faultlog
    text = "faults " + console.fault_text(log, checks.runner.bank)
    serious = False
    for i in range(log.count()):
        serious = serious or log.entry(i)[0] != faultlog.SONAR
    if serious:
        text += ": fix the cause (docs/console.md, faults), then `faults clear`"
    checks._line(out, not serious, text)


def heap(checks, out):
    if not hasattr(gc, "mem_free"):
        checks._line(out, True, "heap n/a (no gc.mem_free on this runtime)")
        return
    gc.collect()
    free = gc.mem_free()
    if free < HEAP_LOW:
        checks._line(
            out,
            False,
            "heap free %d bytes, below %d: a line or a walk may fail for memory: flash compiled .mpy "
            "files (hexapod flash does) and remove extra files from the board" % (free, HEAP_LOW),
        )
        return
    checks._line(out, True, "heap free %d bytes" % free)


def supply(checks, out, b):
    """The battery monitor's pack voltage and state (hexapod.battery), when the board has one."""
    if b is None:
        checks._line(out, True, "supply n/a (no battery monitor configured)")
        return
    from hexapod import battery

    text = "supply %s V, %d cells, %s" % (battery.volts(b.level_mv), b.cells, battery.STATE_NAMES[b.state])
    if b.state == battery.OK:
        checks._line(out, True, text)
    else:
        checks._line(out, False, text + ": charge the pack (cut off below %s V)" % battery.volts(b.cutoff_mv))
