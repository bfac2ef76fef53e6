"""`hexapod doctor --port PORT [--json]`: the board's `selftest` through the serial link, as a report a
maker can paste into an issue (docs/cli.md, docs/console.md). Exit 0 when every check passed, 1 when
one failed or the board could not be reached, 2 on bad options."""

import json
import sys

from hexapod_host.commands.cli import UsageError, version
from hexapod_host.serial.link import TIMEOUT_S, Link, LinkError, PortBusy

# Checks whose name has a second word (the chip's address, the sonar's or servo's name).
_TWO_WORDS = ("pca9685", "sonar", "servo")


def register(sub):
    p = sub.add_parser("doctor", help="run the board's selftest and print a report to paste into an issue")
    p.add_argument("--port", required=True, help="serial port (hexapod ports lists them), or a virtual board's pty")
    p.add_argument("--json", action="store_true", help="the report as one JSON object")
    p.add_argument("--timeout", type=float, default=TIMEOUT_S, help="seconds to wait for each reply line (default 2)")
    p.set_defaults(func=doctor)


def board_line(text):
    """(board, robot) from selftest's first line, `ok board NAME robot ROBOT` (docs/console.md),
    the robot '?' when the line names none; None for any other line."""
    words = text.split()
    if words[:2] != ["ok", "board"] or len(words) < 3:
        return None
    return words[2], words[4] if len(words) > 4 and words[3] == "robot" else "?"


def parse(lines):
    """The report's data from selftest's reply lines (the end line last): a dict."""
    checks = []
    facts = {"board": "?", "robot": "?", "firmware": "?", "i2c": []}
    for text in lines[:-1]:
        ok = text.startswith("ok ")
        rest = text[3:] if ok else text[4:]
        words = rest.split()
        if not words:
            continue
        n = 2 if words[0] in _TWO_WORDS and len(words) > 1 else 1
        name = " ".join(words[:n]).rstrip(":")
        detail = rest[len(" ".join(words[:n])) :].strip()
        hint = ""
        if not ok and ": " in detail:
            detail, hint = detail.split(": ", 1)
        elif not ok and detail.startswith(":"):
            detail, hint = "", detail[1:].strip()
        checks.append({"check": name, "ok": ok, "detail": detail, "hint": hint, "line": text})
        if name == "board" and ok:
            facts["board"], facts["robot"] = board_line(text) or ("?", "?")
        elif name == "version":
            facts["firmware"] = words[1] if len(words) > 1 else "?"
        elif name == "i2c" and len(words) > 2 and words[1] == "found":
            # 'i2c found 0x40 0x41', 'i2c found 0x40, missing 0x41: ...', 'i2c found 0x40 0x70 (not in ...)'
            found = rest.split(",")[0].split("(")[0].split(":")[0].split()[2:]
            facts["i2c"] = [w for w in found if w.startswith("0x")]
    failed = [c for c in checks if not c["ok"]]
    end = lines[-1]
    return dict(facts, checks=checks, failed=len(failed), end=end, passed=end.startswith("ok ") and not failed)


def report(data, port, host):
    """The plain-text report (a list of lines)."""
    out = [
        "hexapod doctor report",
        "port:     %s" % port,
        "host:     hexapod %s, Python %s" % (host, sys.version.split()[0]),
        "board:    %s (robot %s)" % (data["board"], data["robot"]),
        "firmware: %s" % data["firmware"],
        "i2c:      %s" % (" ".join(data["i2c"]) or "nothing found"),
        "result:   %d checks, %d failed (%s)" % (len(data["checks"]), data["failed"], data["end"]),
    ]
    if data["failed"]:
        out.append("")
        out.append("failed checks:")
        for c in data["checks"]:
            if not c["ok"]:
                what = c["check"] + (" " + c["detail"] if c["detail"] else "")
                out.append("  %s" % what)
                if c["hint"]:
                    out.append("      hint: %s" % c["hint"])
    out.append("")
    out.append("every line of the board's reply:")
    for c in data["checks"]:
        out.append("  " + c["line"])
    out.append("  " + data["end"])
    return out


def doctor(args):
    if not args.timeout > 0:
        raise UsageError("--timeout %s: allowed a positive number of seconds" % args.timeout)
    try:
        with Link.open(args.port, timeout=args.timeout) as link:
            lines = link.request_lines("selftest")
    except PortBusy as e:
        raise UsageError(str(e)) from None
    except LinkError as e:
        print("hexapod: error: %s" % e, file=sys.stderr)
        return 1
    if len(lines) == 1 and lines[0].startswith("err unknown command"):
        print(
            "hexapod: error: the firmware on %s has no selftest (older than this host's): flash it (hexapod flash)"
            % args.port,
            file=sys.stderr,
        )
        return 1
    data = parse(lines)
    if args.json:
        print(json.dumps(dict(data, port=args.port, host=version()), indent=1))
    else:
        print("\n".join(report(data, args.port, version())))
    return 0 if data["passed"] else 1
