"""Driving from the page: the keys, the stick and the buttons as console lines, the deadman, and
which tab may drive (docs/view.md, "Driving").

- Keys: W/S forward/back, A/D strafe left/right, Q/E turn left/right, held together they add up;
  space stops. The stick: up/down forward/back, left/right turns. A gamepad (the page reads the
  browser's Gamepad API and reports it, gamepad()): left stick forward/back and strafe, right
  stick or the triggers turn, the east face button stops; after a stop it drives again only once
  centred.
- Deadman: the console's `walk` expires on its own (the board file's walk_timeout_ms, 1000 ms by
  default: the loop stops the robot). While a key, the stick or the gamepad is held the page
  renews the walk every RENEW_S; when the last one is let go (the gamepad centred or
  disconnected, or its reports stop coming), the window loses focus (no keyup would come) or
  the tab goes away, `stop` goes out at once.
- One driver: the first tab that opens the page owns the drive; every other tab is view-only
  (its drive widgets disabled, and its events refused here too: a disabled widget is only a
  picture). The owner's tab closing or losing its connection frees the drive (and stops the
  robot); the next tab to open or reconnect takes it.

Driver is plain Python (no UI): the page calls it with the NiceGUI client's id; tests call it
with any id. The source must have `drivable` true and command(line) -> tag, reply(tag).
"""

import math

import robots.default
from hexapod import geometry

SPEED_MM_S = 80.0  # a key's walking speed: two thirds of the tripod's 120 mm/s
TURN_DPS = 20.0  # a key's turn rate, deg/s
RENEW_S = 0.25  # the walk is renewed this often while held: 4 times within the board's 1000 ms
KEYS = {  # key -> (vx, vy, wz) as fractions of SPEED_MM_S, SPEED_MM_S, TURN_DPS
    "w": (1, 0, 0),
    "s": (-1, 0, 0),
    "a": (0, 1, 0),
    "d": (0, -1, 0),
    "q": (0, 0, 1),
    "e": (0, 0, -1),
}
BUTTONS = ("stand", "sit", "relax", "stop", "wall off")
# The gamepad (the browser's Gamepad API, standard mapping): left stick forward/back and strafe,
# right stick's x or the triggers (LT left, RT right) turn, the east face button (B, circle) stops.
PAD_DEADZONE = 0.15  # a stick within this of centre is centred (worn sticks rest off zero)
PAD_STALE = 12  # renewals (RENEW_S apart: 3 s) with no report from an off-centre pad: the page went quiet
WALL_CM = (4.0, 50.0)  # the console's set point range


class NotOwner(Exception):
    """A tab that does not own the drive tried to drive."""


class Driver:
    def __init__(self, source):
        self.source = source
        self.drivable = bool(getattr(source, "drivable", False))
        # The robot file's body height range (mm): the console's `height` takes nothing else.
        self.heights_mm = robot_heights_mm()
        self.owner = None  # the client id that may drive
        self.keys = set()  # keys held
        self.stick = None  # (x, y) in -1..1 while the stick is held
        self.pad = None  # (vx, vy, wz) as fractions of full while the gamepad is off-centre
        self.pad_latched = False  # after a stop the pad drives again only once centred
        self._pad_age = 0  # renewals since the pad's last report
        self._pad_stop = False  # the stop button was down at the last report
        self.walk = None  # the walk line in force (renewed while held)
        self.sent = []  # (tag, line), newest last: the page shows the last few with their replies

    # -- who drives ----------------------------------------------------------------------

    def claim(self, client, connected=True):
        """Take the drive for client if it is free and client is connected; True when client owns
        it. A tab whose socket is gone (a reload, a lost network) keeps its panel's timer until the
        server forgets it (server.RECONNECT_S later): it must not take back the drive its
        disconnect let go, or the reloaded page, a new client, stays view-only meanwhile."""
        if connected and self.drivable and self.owner is None:
            self.owner = client
        return self.owner == client

    def release(self, client):
        """The client's tab went away: if it drove, let go of everything (stop) and free the drive."""
        if client == self.owner:
            self.owner = None
            self._let_go()

    def check(self, client):
        """NotOwner unless client may drive: the jog panel asks before it changes anything."""
        self._check(client)

    def _check(self, client):
        if not self.drivable:
            raise NotOwner("this source cannot be driven")
        if client != self.owner:
            raise NotOwner("another tab drives; this one is view-only")

    # -- commands ------------------------------------------------------------------------

    def _send(self, line):
        tag = self.source.command(line)
        self.sent.append((tag, line))
        del self.sent[:-20]
        return tag

    def command(self, client, line):
        """A button's line (stand, sit, relax, gait NAME, wall SIDE CM, wall off, stop)."""
        self._check(client)
        if line.split()[0] in ("stop", "relax", "sit", "stand"):
            self._drop_all()
            self.walk = None
        return self._send(line)

    def wall(self, client, side, cm):
        """Wall following on (side 'left'/'right', set point cm) or off (side None)."""
        self._check(client)
        if side is None:
            return self._send("wall off")
        if side not in ("left", "right"):
            raise ValueError("side %r: allowed left, right" % (side,))
        if cm is None or not WALL_CM[0] <= cm <= WALL_CM[1]:
            raise ValueError("set point %r cm: allowed %g..%g" % (cm, *WALL_CM))
        return self._send("wall %s %.2f" % (side, cm))

    def height(self, client, mm):
        """The body's standing height, mm (standing: the feet move there once the board has
        checked it; else the next stand goes there)."""
        self._check(client)
        lo, hi = self.heights_mm
        if isinstance(mm, bool) or not isinstance(mm, (int, float)) or not lo <= mm <= hi:
            raise ValueError("height %r mm: allowed %g..%g (the robot file's range)" % (mm, lo, hi))
        return self._send("height %.1f" % mm)

    def key(self, client, name, down):
        """A key went down or up (W A S D Q E, space); repeats of a held key change nothing."""
        self._check(client)
        name = name.lower()
        if name == " ":
            if down:
                self._drop_all()
                self._stop()
            return
        if name not in KEYS:
            return
        if down:
            self.keys.add(name)
        else:
            self.keys.discard(name)
        self._update()

    def stick_move(self, client, x, y):
        """The stick at (x, y), each -1..1 (x right, y up); None: let go."""
        self._check(client)
        self.stick = None if x is None else (max(-1.0, min(1.0, x)), max(-1.0, min(1.0, y)))
        self._update()

    def gamepad(self, client, state):
        """The page's report of its first gamepad: None when there is none (disconnected), else
        {"axes": [left x, left y, right x, right y] (-1..1, y down), "lt", "rt" (0..1), "stop"
        (0..1)}. The page reports on every change and every RENEW_S while off-centre."""
        self._check(client)
        pad = _pad_velocity(state)
        self._pad_age = 0
        pressed = state is not None and state["stop"] >= 0.5
        was, self._pad_stop = self._pad_stop, pressed
        if pressed:  # as space: stop at once (on the press, not again while held)
            self._drop_all()
            self.pad_latched = True
            if not was:
                self._stop()
            return
        if pad is None:
            self.pad_latched = False
        elif self.pad_latched:
            return
        self.pad = pad
        self._update()

    def let_go(self, client):
        """The page lost the keyboard (its window lost focus): a key held then sends no keyup, so
        everything held is let go (stop when walking)."""
        self._check(client)
        self._let_go()

    def renew(self):
        """The page's timer, every RENEW_S: the walk again while something is held. A gamepad the
        page stopped reporting (a frozen tab) is let go after PAD_STALE renewals."""
        if self.pad is not None:
            self._pad_age += 1
            if self._pad_age > PAD_STALE:
                self.pad = None
                self._update()
                return
        if self.walk is not None and self.held():
            self._send(self.walk)

    def held(self):
        return bool(self.keys) or self.stick is not None or self.pad is not None

    def velocity(self):
        """(vx mm/s, vy mm/s, wz deg/s) of what is held: the keys' sum plus the stick."""
        vx = vy = wz = 0.0
        for k in self.keys:
            fx, fy, fw = KEYS[k]
            vx, vy, wz = vx + fx * SPEED_MM_S, vy + fy * SPEED_MM_S, wz + fw * TURN_DPS
        if self.stick is not None:
            x, y = self.stick
            vx, wz = vx + y * SPEED_MM_S, wz - x * TURN_DPS  # right on the stick turns right (wz < 0)
        if self.pad is not None:
            fx, fy, fw = self.pad
            vx, vy, wz = vx + fx * SPEED_MM_S, vy + fy * SPEED_MM_S, wz + fw * TURN_DPS
        return round(vx, 1), round(vy, 1), round(wz, 2)

    def _update(self):
        v = self.velocity()
        if not self.held():
            self._let_go()
            return
        line = "walk %g %g %g" % v
        if line != self.walk:
            self.walk = line
            self._send(line)

    def _let_go(self):
        self._drop_all()
        if self.walk is not None:
            self._stop()

    def _drop_all(self):
        """A stop: nothing held any more, and a pad still off-centre waits until it is centred."""
        self.keys.clear()
        self.stick = None
        if self.pad is not None:
            self.pad_latched = True
        self.pad = None

    def _stop(self):
        self.walk = None
        self._send("stop")


def _axis(v):
    """A stick's axis past the dead zone, rescaled to 0..1 from its edge: no jump at the edge."""
    m = abs(v)
    if m <= PAD_DEADZONE:
        return 0.0
    return math.copysign(min(1.0, (m - PAD_DEADZONE) / (1.0 - PAD_DEADZONE)), v)


def _pad_velocity(state):
    """A gamepad report (Driver.gamepad) as (vx, vy, wz) fractions, None when centred or absent;
    ValueError naming what is wrong with a report that does not have that shape."""
    if state is None:
        return None
    if not isinstance(state, dict) or set(state) != {"axes", "lt", "rt", "stop"}:
        raise ValueError("gamepad report %r: allowed None or {axes, lt, rt, stop}" % (state,))
    axes, values = state["axes"], [state["lt"], state["rt"], state["stop"]]
    if not isinstance(axes, list) or len(axes) != 4 or not all(_number(v, -1.0) for v in axes):
        raise ValueError("gamepad axes %r: allowed 4 numbers -1..1" % (axes,))
    if not all(_number(v, 0.0) for v in values):
        raise ValueError("gamepad lt, rt, stop %r: allowed numbers 0..1" % (values,))
    lx, ly, rx, _ = (_axis(v) for v in axes)
    turn = max(-1.0, min(1.0, -rx + _axis(state["lt"]) - _axis(state["rt"])))  # right turns right (wz < 0)
    v = (-ly, -lx, turn)  # stick up (y < 0) forward, left (x < 0) strafes left (vy > 0)
    return None if v == (0.0, 0.0, 0.0) else tuple(x + 0.0 for x in v)  # + 0.0: no -0.0


def _number(v, lo):
    return isinstance(v, (int, float)) and not isinstance(v, bool) and lo <= v <= 1.0


def robot_heights_mm():
    """(lowest, highest) body height robots/default.py allows, mm (the robot the view draws)."""
    g = geometry.load(robots.default)
    return (g.body_height_min / 10, g.body_height_max / 10)
