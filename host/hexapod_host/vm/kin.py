# The `hexapod ik` / `hexapod fk` engine. Runs unchanged on CPython (imported by the CLI) and
# inside the MicroPython VM (run as a script), so both print byte-identical text.
#
#   kin.py MODE JSON COXA FEMUR TIBIA OFFSET L1 .. L6 [VALUE ...]
# MODE is ik, fk or ik-batch; JSON is 0 or 1; lengths in 0.1 mm, limits in cdeg; VALUEs are
# the user's mm / degree words. ik-batch reads "x y z" lines (mm) from stdin.
import sys

from hexapod.leg import OK, Leg, describe
from hexapod.units import format_fixed, parse_fixed

NAMES = {"ik": ("x", "y", "z"), "fk": ("theta1", "theta2", "theta3")}


def parse_three(words, names, places):
    """Three decimal words into scaled integers; ValueError names the bad one."""
    if len(words) != 3:
        raise ValueError("need 3 numbers (%s), got %d" % (" ".join(names), len(words)))
    vals = [0, 0, 0]
    for k in range(3):
        try:
            vals[k] = parse_fixed(words[k], places)
        except ValueError as err:
            raise ValueError("%s: %s" % (names[k], err)) from None
    return vals


def angles_text(out):
    return "%s %s %s" % (format_fixed(out[0], 2), format_fixed(out[1], 2), format_fixed(out[2], 2))


def solve_line(leg, mode, words, as_json, out):
    """One solve: (True, text) when the leg reaches it, (False, text) when refused."""
    if mode == "fk":
        t = parse_three(words, NAMES["fk"], 2)
        code = leg.accept(t[0], t[1], t[2], out, 0)
        if code == OK:
            leg.fk(t[0], t[1], t[2], out, 3)
            if as_json:
                return True, '{"x_mm": %s, "y_mm": %s, "z_mm": %s}' % (
                    format_fixed(out[3], 1),
                    format_fixed(out[4], 1),
                    format_fixed(out[5], 1),
                )
            return True, "%s %s %s" % (format_fixed(out[3], 1), format_fixed(out[4], 1), format_fixed(out[5], 1))
    else:
        p = parse_three(words, NAMES["ik"], 1)
        code = leg.ik(p[0], p[1], p[2], out, 0)
        if code == OK:
            if as_json:
                return True, '{"reachable": true, "theta1_deg": %s, "theta2_deg": %s, "theta3_deg": %s}' % (
                    format_fixed(out[0], 2),
                    format_fixed(out[1], 2),
                    format_fixed(out[2], 2),
                )
            return True, angles_text(out)
    reason = describe(code, leg.excess)
    if as_json:
        return False, '{"reachable": false, "reason": "%s"}' % reason
    return False, "unreachable: " + reason


def run(argv, stdin, stdout, stderr):
    """Exit status: 0 done, 1 refused (unreachable / beyond a limit), 2 bad input."""
    mode = argv[0]
    as_json = argv[1] == "1"
    g = [int(w) for w in argv[2:12]]
    leg = Leg(coxa=g[0], femur=g[1], tibia=g[2], femur_offset=g[3], limits=g[4:10])
    out = [0] * 6
    if mode != "ik-batch":
        try:
            ok, text = solve_line(leg, mode, argv[12:], as_json, out)
        except ValueError as err:
            stderr.write("hexapod: error: %s\n" % err)
            return 2
        stdout.write(text + "\n")
        return 0 if ok else 1
    status = 0
    n = 0
    for line in stdin:
        n += 1
        try:
            text = solve_line(leg, "ik", line.split(), as_json, out)[1]
        except ValueError as err:
            stderr.write("hexapod: line %d: %s\n" % (n, err))
            text = "error: line %d: %s" % (n, err)
            status = 2
        stdout.write(text + "\n")
    return status


if __name__ == "__main__":
    sys.exit(run(sys.argv[1:], sys.stdin, sys.stdout, sys.stderr))
