"""`hexapod ik` and `hexapod fk`: one leg's kinematics at the edge, in mm and degrees."""

import io
import os
import sys

from hexapod.leg import ANGLE_MAX, COXA_MAX, DEFAULT_LIMITS, LINK_MAX, LINK_MIN, OFFSET_MAX, Leg
from hexapod.units import OutOfRange, format_fixed, parse_fixed, shown
from hexapod_host import mpvm
from hexapod_host.commands.cli import UsageError
from hexapod_host.vm import kin

KIN_SCRIPT = os.path.join(os.path.dirname(os.path.abspath(kin.__file__)), "kin.py")

# Seed 004's leg (Table 3: a1 = 3, d1 = 3.2, a2 = 8.5, a3 = 12.5 cm) is the default.
DEFAULTS = {"coxa": "30", "femur": "85", "tibia": "125", "femur_offset": "32"}


def _add_leg_options(p):
    g = p.add_argument_group("leg geometry (mm) and joint limits (degrees)")
    g.add_argument("--coxa", default=DEFAULTS["coxa"], help="coxa length, mm (default 30)")
    g.add_argument("--femur", default=DEFAULTS["femur"], help="femur length, mm (default 85)")
    g.add_argument("--tibia", default=DEFAULTS["tibia"], help="tibia length, mm (default 125)")
    g.add_argument(
        "--femur-offset", default=DEFAULTS["femur_offset"], help="femur joint height above the coxa origin, mm"
    )
    g.add_argument(
        "--limits",
        nargs=6,
        metavar=("CMIN", "CMAX", "FMIN", "FMAX", "TMIN", "TMAX"),
        help="joint limits in degrees (default -90 90 -90 90 -180 0)",
    )
    p.add_argument("--json", action="store_true", help="print JSON")
    p.add_argument(
        "--runtime",
        choices=("cpython", "micropython"),
        default="cpython",
        help="run the firmware code here or inside the MicroPython VM (identical output)",
    )


# name, what it does, its values (metavar) and their help
COMMANDS = (
    (
        "ik",
        "joint angles (degrees) of a foot position (mm, leg frame)",
        "X Y Z",
        "foot position, mm (each within +-3000)",
    ),
    ("fk", "foot position (mm, leg frame) of joint angles (degrees)", "T1 T2 T3", "coxa, femur, tibia, degrees"),
)


def register(sub):
    domain = " Input domain: |x|, |y|, |z| <= 3000 mm; angles within +-360 degrees; plain decimals only."
    for name, what, metavar, values in COMMANDS:
        p = sub.add_parser(name, help=what, description=what[0].upper() + what[1:] + "." + domain + EXIT_RULE)
        p.add_argument("values", nargs="*", metavar=metavar, help=values)
        p.add_argument(
            "--batch", action="store_true", help="read '%s' lines from stdin, one answer per line" % metavar.lower()
        )
        _add_leg_options(p)
        p.set_defaults(func=run_ik if name == "ik" else run_fk)


EXIT_RULE = (
    " Exit status: 0 all solved, 1 some refused (unreachable or beyond a limit), 2 bad input"
    " (a batch: 2 if any line was bad, else 1 if any was refused), 3 internal error."
)


def _fixed(name, text, places, lo, hi, unit):
    try:
        value = parse_fixed(text, places, max(-lo, hi))
    except OutOfRange:
        value = None  # past both bounds' magnitude, however many digits: the range message below
    except ValueError as err:
        raise UsageError("--%s: %s" % (name, err)) from None
    if value is None or value < lo or value > hi:
        scale = 10**places
        raise UsageError(
            "--%s: %s %s is outside the allowed %g..%g %s"
            % (name, shown(text)[1:-1], unit, lo / scale, hi / scale, unit)
        )
    return value


def geometry_words(args):
    """The leg options as the kin engine's integer words; UsageError names a bad one."""
    g = [
        _fixed("coxa", args.coxa, 1, 0, COXA_MAX, "mm"),
        _fixed("femur", args.femur, 1, LINK_MIN, LINK_MAX, "mm"),
        _fixed("tibia", args.tibia, 1, LINK_MIN, LINK_MAX, "mm"),
        _fixed("femur-offset", args.femur_offset, 1, -OFFSET_MAX, OFFSET_MAX, "mm"),
    ]
    if args.limits is None:
        g += list(DEFAULT_LIMITS)
    else:
        g += [_fixed("limits", w, 2, -ANGLE_MAX, ANGLE_MAX, "deg") for w in args.limits]
        for k, joint in ((0, "coxa"), (2, "femur"), (4, "tibia")):
            if g[4 + k] > g[5 + k]:
                raise UsageError(
                    "--limits: %s min %s deg is above its max %s deg"
                    % (joint, format_fixed(g[4 + k], 2), format_fixed(g[5 + k], 2))
                )
    try:
        Leg(coxa=g[0], femur=g[1], tibia=g[2], femur_offset=g[3], limits=g[4:])
    except ValueError as err:
        raise UsageError(str(err)) from None
    return [str(v) for v in g]


def _word_bytes(word):
    """A command-line word back as the bytes the user typed (non-UTF-8 ones arrive surrogate-escaped)."""
    if "\0" in word:
        raise UsageError("%s: contains a NUL character" % shown(word))
    try:
        return word.encode("utf-8", "surrogateescape")
    except UnicodeEncodeError:  # a lone surrogate no shell can send: stays invalid UTF-8
        return word.encode("utf-8", "surrogatepass")


def _run(kind, args):
    try:
        return _solve(kind, args)
    except UsageError as err:
        if args.json:  # the engine's own errors do the same: a JSON reader always gets an object
            sys.stdout.write('{"error": %s}\n' % kin.json_text(str(err)))
        raise


def _solve(kind, args):
    if args.batch and args.values:
        raise UsageError("--batch reads stdin; drop the values %s" % " ".join(shown(w) for w in args.values[:3]))
    mode = kind + "-batch" if args.batch else kind
    argv = [mode, "1" if args.json else "0"] + geometry_words(args)
    if args.batch:
        stdin = sys.stdin.buffer
    else:
        stdin = io.BytesIO(b"".join(_word_bytes(w) + b"\0" for w in args.values))
    if args.runtime == "cpython":
        return kin.run(argv, stdin, sys.stdout, sys.stderr)
    status, out, err = mpvm.run_script_status(KIN_SCRIPT, argv, stdin.read())
    if not kin.STATUS_BASE <= status <= kin.STATUS_BASE + kin.INTERNAL:
        raise RuntimeError("the MicroPython VM exited %d: %s" % (status, err.strip()[-300:]))
    for k in range(0, len(out), 8192):  # in pieces: one huge write to a closed pipe may fail silently
        sys.stdout.write(out[k : k + 8192])
    sys.stderr.write(err)
    return status - kin.STATUS_BASE


def run_ik(args):
    return _run("ik", args)


def run_fk(args):
    return _run("fk", args)


def run_in_process(argv_words, stdin=b""):
    """Test helper: the engine's (status, stdout, stderr) on CPython for given words and stdin bytes."""
    out, err = io.StringIO(), io.StringIO()
    status = kin.run(argv_words, io.BytesIO(stdin), out, err)
    return status, out.getvalue(), err.getvalue()
