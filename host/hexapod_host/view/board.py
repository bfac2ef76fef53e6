"""A board on a console line as a view source: `hexapod view --virtual` (the virtual board),
`--pico` (the emulated Pico) and `--port` (a board on a serial port). The board streams its
telemetry (`stream on 25`: a `~T` line every other frame, /work/notes/telemetry-spec.md) and the
source turns the newest line into the snapshot every source gives (source.py): the pulses
through the board's servo maps inverted and the robot file's FK (source.pose, the wall
simulator's path), the sonars, the follower, the counters. It can be driven: command(line)
sends a console line tagged, reply(tag) is its answer.

The servo maps are the board's own (boardcal.py: its `cal` lines read when the page connects and
followed after every calibration command), so a trimmed or flipped servo is drawn at the angle
the board drove it to. There is no room: the body starts at the origin (x, y, yaw 0) and is
moved by the feet of every telemetry line (inroom.Odometry, dead reckoning); its height is the
coxa plane's above the lowest foot."""

from hexapod import board as boards
from hexapod import follow, gait, sensors, tick
from hexapod_host.commands.doctor import board_line
from hexapod_host.view.boardcal import BoardCal, cal_lines
from hexapod_host.view.inroom import Odometry
from hexapod_host.view.source import Source, pose
from hexapod_host.wall.room import BODY_HALF, Body, grounded

STREAM_HZ = 25  # the most the stream gives: a line every other frame
FRAME_S = 0.02
# A limp servo sends no pulse: its joint is drawn at its reference angle (cdeg; coxa and femur 0,
# tibia -90: docs/console.md's `cal`), the leg hanging straight down from the knee.
REST_CDEG = (0, 0, -9000)
SIDES = (None, "left", "right")  # telemetry's follow_side 0, 1, 2


def _mm(v):
    """0.1 mm (hexapod.sensors' raw unit) -> mm; None stays None."""
    return None if v is None else v / 10


class BoardSource(Source):
    """The newest telemetry of a board behind a BoardLink (started). on_close: called by close()
    after the link is closed (the virtual board's process to stop)."""

    name = "virtual"
    drivable = True

    def __init__(self, link, board="pico", name=None, on_close=None, hz=STREAM_HZ, reply_s=10.0):
        self.link = link
        if name:
            self.name = name
        self.on_close = on_close
        self.hz = hz
        self.restarts = 0  # power-ups seen since the page connected (a reset, a brownout, plugged in)
        self._boots = link.boots  # a power-up line from here on: the board (re)started after this
        self._stream_tag = None  # `stream on` asked again after a power-up, its reply awaited
        self.setpoint_mm = None
        self._wall_tags = []
        # reply_s: a hang guard (the emulated Pico answers in wall-clock seconds, not a frame)
        stream = link.request("stream on %d" % hz, reply_s)
        self.stream_reply = stream or "no reply to 'stream on %d'" % hz
        # What the board says it is (its selftest's first line), and the board file it is drawn
        # with: its own when this host has it, else `board`.
        self.said, self.board = None, board
        self.said_why = "the board answered nothing"
        if stream is not None:
            self._ask_board(reply_s)
        self.body = Body(self.board)
        self._rest = self._rest_pose()
        # Where the feet have carried the body since the page connected (inroom.Odometry, the
        # wall simulator's mover on every telemetry line, in the link's thread): a dead reckoning
        # from the pulses sent, on a floor with no room (a slipping foot is not seen).
        walker = Body(self.board)
        walker.maps = self.body.maps  # the board's own maps, as BoardCal updates them
        self.odometry = Odometry(walker)
        self._at = (0.0, 0.0, 0.0)  # x, y mm, yaw rad
        self._odometry_frame = -1
        link.on_telemetry = self._moved
        self.cal = BoardCal(link, self.body)
        if stream is None:
            self.cal.why = "the board answered nothing"  # not 18 more hang guards long
        else:
            self.cal.read_all(reply_s)

    def _moved(self, t):
        """One telemetry line's feet into the odometry (the link's thread)."""
        legs = pose(self.odometry.body, t["pulses"])
        if legs is None or t["frame"] <= self._odometry_frame:  # limp, or the board started over
            self.odometry.lose()
        if legs is not None:
            self._at = self.odometry.step(legs["legs"], t["frame"])
        self._odometry_frame = t["frame"]

    def _ask_board(self, reply_s):
        """The board's own name and robot: `selftest`'s first line, `ok board NAME robot ROBOT`
        (docs/console.md; what `hexapod doctor` reports). Its other lines come later and are not
        waited for (the sonars' take 6 frames); selftest moves nothing."""
        first = self.link.request("selftest", reply_s, first=True)
        self.said = board_line(first) if first else None
        if self.said is None:
            self.said_why = "'selftest' answered %r" % first if first else "no reply to 'selftest'"
            return
        try:
            boards.load(self.said[0])
        except ValueError:
            return  # a board file this host does not have: drawn with `board`'s
        self.board = self.said[0]

    def board_text(self):
        """The page's board label: what the board said it is, or why it is not known."""
        if self.said is None:
            return "board unknown (%s)" % self.said_why
        drawn = "" if self.said[0] == self.board else ", drawn with boards/%s.py" % self.board
        return "board %s, robot %s%s" % (*self.said, drawn)

    def _rest_pose(self):
        angles = list(REST_CDEG) * 6
        legs = self.body.leg_points(angles)
        return {
            "pulses": [0] * 18,
            "angles": angles,
            "legs": [[list(p) for p in leg] for leg in legs],
            "stance": grounded([leg[3] for leg in legs]),
        }

    def describe(self):
        b = self.body
        return {
            "source": self.name,
            "board": self.board,  # the board file the pulses are drawn through (a replay's too)
            "board_said": self.board_text(),
            "sensors": [[x, y, h] for x, y, h in b.sensors],
            "body_half": list(BODY_HALF),
            "brackets": [list(seg) for seg in b.outline[4:]],
            "frame_s": FRAME_S,
            "odometry": "dead reckoning from the feet of every telemetry line",
        }

    def step(self):
        """The link's thread takes lines in as they arrive. A board that powered up again (its
        `boot:` line: reset, brownout, watchdog, or plugged in after the page was served) has no
        stream and its calibration file's maps: ask both again, without waiting (the page's loop)."""
        boots = self.link.boots
        if boots != self._boots:
            self._boots = boots
            self.restarts += 1
            self.stream_reply = "stream asked again after the board's power-up line"
            self._stream_tag = self.link.send("stream on %d" % self.hz)
            for line in cal_lines():
                self.cal.watch(line, self.link.send(line))
        if self._stream_tag is not None:
            r = self.link.reply(self._stream_tag)
            if r is not None and r != "working":
                self.stream_reply = "%s (again, after power-up %d)" % (r, self.restarts)
                self._stream_tag = None

    def command(self, line):
        """Send one console line to the board now; its tag, for reply(tag)."""
        tag = self.link.send(line)
        self.cal.watch(line, tag)
        if line.split()[:1] == ["wall"]:
            self._wall_tags.append(tag)
        return tag

    def reply(self, tag):
        return self.link.reply(tag)

    def _setpoint(self):
        """The set point of the last `wall` command the board took (telemetry does not carry it)."""
        for tag in list(self._wall_tags):
            r = self.link.reply(tag)
            if r is None or r == "working":
                continue
            self._wall_tags.remove(tag)
            words = r.split()
            if words[:2] == ["ok", "wall"]:
                self.setpoint_mm = float(words[4]) * 10 if len(words) >= 5 and words[3] == "setpoint" else None
        return self.setpoint_mm

    def snapshot(self):
        t = self.link.telemetry
        setpoint = self._setpoint()
        self.cal.follow()
        extra = {
            "board": self.board_text(),
            "stream": self.stream_reply,
            "servo_maps": self.cal.source,
            "telemetry_lines": self.link.telemetry_lines,
            "malformed": self.link.malformed,
            "lost": self.link.lost,
            "notice": self.link.notices[-1] if self.link.notices else "",
        }
        if t is None:
            return {
                "frame": 0,
                "time_s": 0.0,
                **self._rest,
                "body": {"x": 0.0, "y": 0.0, "z": -min(leg[3][2] for leg in self._rest["legs"]), "yaw": 0.0},
                "distances": [None] * 5,
                "sonar_status": ["wait"] * 5,
                "mode": "-",
                "follow": {"mode": "off", "side": None, "setpoint_mm": setpoint, "error_mm": 0.0, "output_dps": 0.0},
                "counters": {},
                "extra": {**extra, "gait": "-", "phase": 0, "walk": [0, 0, 0], "battery_mv": None},
            }
        legs = pose(self.body, t["pulses"]) or self._rest
        x, y, yaw = self._at
        side = SIDES[t["follow_side"]]
        return {
            "frame": t["frame"],
            "time_s": round(t["frame"] * FRAME_S, 3),
            **legs,
            "body": {"x": x, "y": y, "z": -min(leg[3][2] for leg in legs["legs"]), "yaw": yaw},
            "distances": [_mm(v) for v in t["distances"]],
            "sonar_status": [sensors.STATUS_NAMES[s] for s in t["sonar_status"]],
            "mode": tick.MODE_NAMES[t["mode"]],
            "follow": {
                "mode": follow.MODE_NAMES[t["follow_mode"]],
                "side": side,
                "setpoint_mm": setpoint if side else None,
                "error_mm": t["wall_error"] / 10,  # the follower's 0.1 mm
                "output_dps": t["wall_out"] / 100,  # its cdeg/s
            },
            "counters": {
                "frames": t["frame"],
                "held": t["held"],
                "overruns": t["overruns"],
                "bus_failed": t["bus_failed"],
                "sonar_faults": t["sonar_faults"],
            },
            "extra": {
                **extra,
                "gait": gait.NAMES[t["gait"]],
                "phase": t["phase"],
                "walk": [t["vx"] / 10, t["vy"] / 10, t["yaw"] / 100],  # mm/s, mm/s, deg/s
                "battery_mv": t["battery_mv"],
                # the firmware's own frame time, us (None from firmware before it: telemetry.parse)
                "frame_us": t.get("frame_us"),
                "frame_us_max": t.get("frame_us_max"),
            },
        }

    def close(self):
        self.link.close()
        if self.on_close is not None:
            self.on_close()
