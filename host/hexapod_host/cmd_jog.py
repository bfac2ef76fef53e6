"""`hexapod jog --port PORT`: move one leg's foot and single servos from the keyboard, calibrate, save.

docs/jog.md; the protocol is docs/console.md.
"""

import os
import sys

from hexapod_host.cli import UsageError

BAUD = 115200


class LinkError(Exception):
    """The port went away or the board did not answer."""


class SerialLink:
    """One console line out, its reply line back (lines that start with neither ok nor err are skipped)."""

    def __init__(self, port, timeout=2.0):
        import serial

        self.port_name = port
        self.timeout = timeout
        try:
            self.port = serial.Serial(port, BAUD, timeout=timeout)
        except (serial.SerialException, OSError) as err:
            raise LinkError("cannot open %s: %s" % (port, err)) from None
        self.serial = serial

    def request(self, line):
        try:
            self.port.write((line + "\n").encode())
            while True:
                raw = self.port.readline()
                if not raw:
                    raise LinkError("the board on %s did not answer within %.1f s" % (self.port_name, self.timeout))
                text = raw.decode(errors="replace").strip()
                if text.startswith(("ok", "err")):
                    return text
        except (self.serial.SerialException, OSError) as err:
            raise LinkError("%s disconnected (%s)" % (self.port_name, err)) from None

    def close(self):
        self.port.close()


def register(sub):
    p = sub.add_parser("jog", help="jog legs and servos from the keyboard, calibrate, save (docs/jog.md)")
    p.add_argument("--port", required=True, help="the board's serial port (e.g. /dev/ttyACM0), or a virtual board's")
    p.add_argument("--timeout", type=float, default=2.0, help="seconds to wait for each reply (default 2)")
    p.set_defaults(func=run)


def run(args):
    from hexapod_host import jog, jog_tui

    if os.sep in args.port and not os.path.exists(args.port):
        raise UsageError("no such port %r (hexapod ports lists them)" % args.port)
    try:
        link = SerialLink(args.port, args.timeout)
        link.request("get 1")  # a board that does not answer is found before the screen opens
    except LinkError as err:
        print("hexapod jog: error: %s" % err)
        return 1
    if not sys.stdin.isatty():
        link.close()
        raise UsageError("hexapod jog needs a terminal; for scripts use hexapod send")
    tool = jog.Jog(link, LinkError)
    try:
        jog_tui.run(tool, args.port)
    finally:
        link.close()
    if not tool.view.connected:
        print("hexapod jog: %s" % tool.view.message)
        return 1
    return 0
