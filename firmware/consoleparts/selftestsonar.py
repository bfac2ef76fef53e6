"""selftest's sonar checks (`sonar <name>`, one line each, with a wiring hint when it failed):
selftest.Checks imports this module for its last step and lets it go after (on CircuitPython,
which compiles a module's source at each import, a smaller compile than one module).
"""

from hexapod import sensors
from hexapod.units import format_fixed

_GROUND = "common ground with the Pico?"  # consoleparts.selftestbus has its own copy


def run(checks, out):
    """One line per sonar: what it measured while the test watched, or why it did not."""
    r = checks.runner
    w = checks.watch
    pins = getattr(r, "sonar_pins", None)
    for k in range(len(w.status)):
        st = w.status[k]
        name = "sonar " + sensors.SENSOR_NAMES[k]
        if st == sensors.OK:
            checks._line(out, True, "%s ok %s mm" % (name, format_fixed(w.distance[k], 1)))
            continue
        word = sensors.STATUS_NAMES[st] if 0 <= st < len(sensors.STATUS_NAMES) else "wait"
        wires = "trigger on pin %s, echo on pin %s" % pins[k] if pins else "its trigger and echo pins"
        if st == sensors.NO_ECHO:
            why = "the echo never rose: module on 5 V? %s? the echo's 1k/2k divider in place? %s" % (wires, _GROUND)
        elif st == sensors.STUCK:
            why = "the echo was high before the trigger: echo shorted high, or the divider's ground leg open"
            why += " (%s)" % wires
        elif st == sensors.OUT_OF_RANGE:
            why = (
                "nothing within %s mm: point it at a wall 10-50 cm away (a soft or slanted target "
                % (format_fixed(r.sonars.ring.sensors[k].max_range, 1),)
                + "returns no echo)"
            )
        elif st == sensors.TOO_CLOSE:
            why = "closer than 20.0 mm: something on the transducers, or a bent one hearing its own burst"
        else:
            why = "no result while the test watched (%d frames): is the loop's round robin running?" % checks.frames
        checks._line(out, False, "%s %s: %s" % (name, word, why))
