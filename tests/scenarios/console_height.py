"""The console's `height` (tests/test_console_height.py) on the console bench
(scenarios.console_rig): standing, the feet move to the new height; sitting, the next stand goes
there; walking, the height waits for the walk."""

from scenarios.console_rig import Board

from hexapod import tick


def _until(b, done, most):
    """Frames until done() (at most `most`): how many ran."""
    n = 0
    while not done() and n < most:
        b.frame()
        n += 1
    return n


def _feet_z(b):
    """The six feet's z (mm, leg frame) from `get L`."""
    return [b.say("get %d" % (leg + 1)).split()[-1] for leg in range(6)]


def standing():
    """Stand, `height 70`, frames until the reply and STANDING, the feet; `height` asks;
    then `height 95.5`: [[reply lines after the height line], asked, feet z, [replies], feet z]."""
    b = Board()
    b.stand()
    rows = []
    for h in ("70", "95.5"):
        before = len(b.replies)
        b.reader.feed(("height %s\n" % h).encode())
        _until(b, lambda n=before: len(b.replies) > n and b.robot.mode == tick.STANDING, 5000)
        rows.append(b.replies[before:])
        rows.append(_feet_z(b))
        rows.append(b.say("height"))
    return rows


def sitting():
    """Sitting: `height 90.0` (reply), the feet z before and after `stand`."""
    b = Board()
    b.stand()
    b.say("sit")
    _until(b, lambda: b.robot.mode == tick.SITTING, 5000)
    before = len(b.replies)
    b.reader.feed(b"height 90\n")
    _until(b, lambda: len(b.replies) > before, 5000)
    rows = [b.replies[before:], _feet_z(b)]
    b.stand()
    rows.append(_feet_z(b))
    return rows
