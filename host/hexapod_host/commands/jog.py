"""`hexapod jog --port PORT`: move one leg's foot and single servos from the keyboard, calibrate, save.

docs/jog.md; the protocol is docs/console.md.
"""

import os
import sys

from hexapod_host.commands import checks
from hexapod_host.commands.cli import UsageError


def register(sub):
    p = sub.add_parser("jog", help="jog legs and servos from the keyboard, calibrate, save (docs/jog.md)")
    p.add_argument("--port", required=True, help="the board's serial port (e.g. /dev/ttyACM0), or a virtual board's")
    p.add_argument("--timeout", type=float, default=2.0, help="seconds to wait for each reply (default 2)")
    p.add_argument(
        "--guided",
        action="store_true",
        help="start in the guided calibration of all 18 servos (docs/calibration.md; G in the tool)",
    )
    p.add_argument(
        "--progress",
        default=os.path.expanduser("~/.hexapod_guided.json"),
        help="where the guided calibration keeps the servos done, to resume (default ~/.hexapod_guided.json)",
    )
    p.set_defaults(func=run)


def run(args):
    from hexapod_host.serial import jog, jog_tui
    from hexapod_host.serial.link import Link, LinkError, PortBusy

    checks.port(args.port)
    try:
        link = Link.open(args.port, args.timeout)
        link.request("get 1")  # a board that does not answer is found before the screen opens
    except PortBusy as err:
        raise UsageError(str(err)) from None
    except LinkError as err:
        print("hexapod jog: error: %s" % err)
        return 1
    if not sys.stdin.isatty():
        link.close()
        raise UsageError("hexapod jog needs a terminal; for scripts use hexapod send")
    tool = jog.Jog(link, LinkError, progress=args.progress)
    try:
        jog_tui.run(tool, args.port, args.guided)
    finally:
        link.close()
    if not tool.view.connected:
        print("hexapod jog: %s" % tool.view.message)
        return 1
    return 0
