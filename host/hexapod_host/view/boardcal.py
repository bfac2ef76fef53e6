"""The servo maps a board holds, read from the board (`cal L J`, docs/console.md), so the view
inverts the pulses it streams through the maps the board drove them with: its trims, flipped
directions and ranges, not the robot file's rows.

A `cal` line says the servo's pulse at its reference angle (centre_us + trim), its direction
and range; the pulse per degree is not on the line: the robot file's (us_per_degree, 10 us a
degree for seed 001's servos), the one thing the console cannot change.

BoardCal reads the 18 lines once when the page connects (read_all), then follows every line the
page sends (watch): the reply to `cal`, `trim`, `dir` and `range` is the servo's cal line, taken
in as it arrives; after `save`, `load` and `defaults` the 18 lines are asked again (follow). A
servo whose line never came keeps the robot file's map, and `source` says so.
"""

import threading

from hexapod.servo import ServoMap
from hexapod_host.serial.guided import centidegrees
from hexapod_host.serial.jog import CAL_FIELDS, JOINTS, fields

ROW_COMMANDS = ("cal", "trim", "dir", "range")  # answered with the servo's cal line
ALL_COMMANDS = ("save", "load", "defaults")  # the 18 maps may have changed: read them again
PENDING_KEPT = 100  # tags waiting for a reply; a reply older than BoardLink keeps never comes


def cal_lines():
    """The 18 `cal L J` lines, leg/joint order (index (leg - 1) * 3 + joint)."""
    return ["cal %d %s" % (k // 3 + 1, JOINTS[k % 3]) for k in range(18)]


def servo_map(reply, us_per_degree=1000):
    """(servo index 0..17, ServoMap) of a `cal` reply ('ok leg L joint J centre_us C ref_deg R
    trim T dir D min_us A max_us B'), or None when the reply is not a whole cal line. The map's
    pulse at ref_deg is C + T (us), its direction D, its range A..B; us_per_degree in 0.01 us."""
    if not reply.startswith("ok leg ") or " centre_us " not in reply:
        return None
    f = fields(reply, CAL_FIELDS)
    try:
        if any(len(f.get(name, ())) != 1 for name in CAL_FIELDS):
            return None
        leg, joint = int(f["leg"][0]), f["joint"][0]
        if not 1 <= leg <= 6 or joint not in JOINTS:
            return None
        c, t, d, lo, hi = (int(f[name][0]) for name in ("centre_us", "trim", "dir", "min_us", "max_us"))
        m = ServoMap(
            centre_us=c + t,
            direction=d,
            us_per_degree=us_per_degree,
            min_us=lo,
            max_us=hi,
            ref_cdeg=centidegrees(f["ref_deg"][0]),
        )
    except ValueError:
        return None
    return 3 * (leg - 1) + JOINTS.index(joint), m


class BoardCal:
    """The board's 18 servo maps, kept in body.maps (a hexapod_host.wall.room.Body): what
    source.pose inverts the pulses through. link: a started BoardLink."""

    def __init__(self, link, body):
        self.link = link
        self.body = body
        self.read = [False] * 18  # servo k's map came from the board
        self.why = "not read yet"  # the last reason a servo kept the robot file's map
        self._pending = {}  # tag -> "row" (a cal line comes back) or "all" (read the 18 again)
        self._lock = threading.Lock()

    @property
    def source(self):
        """Where the maps came from, for the page: 'board' or 'robot file ...' with why."""
        n = sum(self.read)
        if n == 18:
            return "board"
        if n == 0:
            return "robot file (%s)" % self.why
        return "board for %d servos, robot file for %d (%s)" % (n, 18 - n, self.why)

    def take(self, reply):
        """A cal line into its servo's map; True when it was one."""
        got = servo_map(reply or "", self.body.maps[0].us_per_degree)
        if got is None:
            return False
        k, m = got
        self.body.maps[k] = m
        self.read[k] = True
        return True

    def read_all(self, timeout):
        """Ask the 18 lines one after another, waiting for each (before the page is served). The
        first line not answered with a cal line stops the reading: a board that does not know
        `cal` is not asked 17 more times, each a hang guard long."""
        for line in cal_lines():
            reply = self.link.request(line, timeout)
            if not self.take(reply):
                self.why = "no reply to %r" % line if reply is None else "%r answered %r" % (line, reply)
                return False
        return True

    def watch(self, line, tag):
        """Every line the page sends, with its tag: replies that change the maps are followed."""
        word = line.split()[:1]
        kind = "row" if word and word[0] in ROW_COMMANDS else "all" if word and word[0] in ALL_COMMANDS else None
        if kind is None:
            return
        with self._lock:
            self._pending[tag] = kind
            while len(self._pending) > PENDING_KEPT:
                self._pending.pop(next(iter(self._pending)))

    def follow(self):
        """Take in the replies that came (the page calls it before each snapshot): never waits."""
        with self._lock:
            done = [(tag, kind, self.link.reply(tag)) for tag, kind in self._pending.items()]
            done = [(tag, kind, r) for tag, kind, r in done if r is not None and r != "working"]
            for tag, _, _ in done:
                del self._pending[tag]
        for _, kind, reply in done:
            if kind == "row":
                self.take(reply)
            elif reply.startswith("ok"):
                for line in cal_lines():  # sent now, taken in as their replies come
                    self.watch(line, self.link.send(line))
