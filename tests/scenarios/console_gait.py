"""A gait change checked over frames while the console keeps answering (tests/
test_console_configure.py): the stub board (scenarios.console_rig) with every leg's IK solve
counted, the frame's own six solves left out, and no guard table, so every gait is solved live."""

from scenarios.configure import Solves
from scenarios.console_rig import Board


class Counted(Board):
    """A Board whose robot counts the IK solves a gait check makes (scenarios.configure.Solves)."""

    def __init__(self):
        Board.__init__(self)
        self.solves = Solves(self.robot)
        self.robot._table = self.robot.walker.table = None  # no guard table: every gait solved live

    def counted_frame(self):
        """One frame: the solves it made."""
        self.solves.n = 0
        self.frame()
        return self.solves.n


def status_during_gait_change():
    """Stand, walk, `gait ripple`, then `status` in the next frame; frames until the gait's reply
    (the walk renewed every 40 frames). Returns [stand's reply, walk's reply, [solves, replies,
    checking] of the gait line's frame, [solves, status's first 10 characters, checking, gait] of
    the status line's frame, [most solves in a frame, frames, replies after the gait line], `gait`]."""
    b = Counted()
    rows = []
    b.frames(150)
    rows.append(b.say("stand"))
    b.frames(150)
    rows.append(b.say("walk 40 0 0"))
    before = len(b.replies)
    b.reader.feed(b"gait ripple\n")
    solves = b.counted_frame()
    rows.append([solves, len(b.replies) - before, b.robot.configuring()])
    b.reader.feed(b"status\n")
    solves = b.counted_frame()
    rows.append([solves, b.replies[-1][:10], b.robot.configuring(), b.robot.gait])
    worst = 0
    n = 0
    while not _gait_replied(b.replies[before + 1 :]) and n < 4000:
        solves = b.counted_frame()
        n += 1
        if solves > worst:
            worst = solves
        if n % 40 == 0:
            b.reader.feed(b"walk 40 0 0\n")  # the driver keeps walking (the console's walk timeout is 1 s)
            b.frame()
            n += 1
    rows.append([worst, n, b.replies[before + 1 :]])
    rows.append(b.say("gait"))
    return rows


def _gait_replied(replies):
    return any("gait" in line for line in replies)


def tagged_gait_change():
    """Stand, then `#5 gait ripple`: the replies until its tagged ok or err (at most 4000 frames)."""
    b = Counted()
    b.frames(150)
    b.say("stand")
    b.frames(150)
    before = len(b.replies)
    b.reader.feed(b"#5 gait ripple\n")
    n = 0
    while not _tagged_done(b.replies[before:], "#5 ") and n < 4000:
        b.frame()
        n += 1
    return b.replies[before:]


def _tagged_done(replies, tag):
    return any(x.startswith(tag + "ok") or x.startswith(tag + "err") for x in replies)
