"""Wall following (seed 000): side sonars -> distance and angle to the wall -> PID -> yaw rate.

Pure: each frame the loop (runner.Runner) hands update() the loop time, the index of the sonar
whose reading came in this frame and the sonars' distance/status buffers, in the sensor
contract's order (hexapod.sensors: front, left_front, left_rear, right_front, right_rear;
0.1 mm; its status codes); the follower
commands the Robot (Robot.walk, or seed 000's coxa sweeps). It allocates nothing per frame.

Units: lengths 0.1 mm, angles cdeg, speeds 0.1 mm/s, yaw rates cdeg/s, time ms. The set point
is the side sonar's reading, as in the paper. `angle` is positive when the nose points away
from the wall: atan((d_front - d_rear) / baseline) of that side's two sensors, which both read
their perpendicular distance while the robot is within the beam (~15 deg) of parallel.

Control law (docs/wall.md says why): the PID (hexapod.pid, seed 000 eq. 14) holds the wall
distance of a look-ahead point L ahead of the sensor pair,
    e = (set point - d) - L sin(angle),   d = (d_front + d_rear) / 2,
and its output turns the robot away from the wall (positive output = away) while it walks
forward at the set speed. The angle term damps (distance alone oscillates); the angle guard
stops the turn toward (or away from) the wall at ANGLE_GUARD, inside the beam. d and the angle
are estimates, not the raw pair (issue 22 point 5): between samples the walk predicts them (the
walker's heading change turns the angle, its forward travel at that angle moves d) and each pair
sample corrects the prediction by 1/2**EST_SHIFT of the difference. Fed raw, the sonars' 3 mm
noise made the paper's Kp = 25 (2.5 deg/s per mm) turn about 10 deg/s on average, and every turn
costs forward speed (the walker scales a command until its feet fit: docs/wall.md).
Form "crab" (issue 22 point 5) walks the PID's output, on the distance alone, as a sideways speed
and turns only to keep the angle within CRAB_BAND: a sideways step costs the forward speed next to
nothing where a turn costs it at once; on one sonar, past CRAB_ANGLE, or at a wall's end (a pair
sample alone reading the nose 6 degrees away: turned so while the wall reads over set point + 10 mm)
it turns as form "yaw". Crab is the default form (Runner.follow, the board file, the console).

Modes: off, following, corner (the front sonar sees a wall ahead: arc away from the followed
wall), lost (no wall on the side: arc toward where it was, radius = the wall distance), then
searching (a widening spiral toward that side), blocked (something too close in front: stopped
until it clears), stopped (for good, with a reason).

Faults: a side reading is steered on only with status OK, within WALL_GAP of the set point and
not JUMP farther than that sensor's last one (an edge leaving the beam). NO_ECHO, STUCK and
TOO_CLOSE pings are faults (counted per sensor); OUT_OF_RANGE means nothing in range (but from
under 4 cm it means too close: the module holds its echo inside 2 cm). A sensor with MISS_RUN
pings in a row not steered on leaves use (failed when all of them were NO_ECHO/STUCK, else no
wall). One side sensor left: it follows on that sensor's distance (distance_only; `used` names
it), the angle carried on from the last pair by the walker's own heading and let fade; none in
use and not both failed: lost; both failed: stopped. A failed front sonar, or two TOO_CLOSE
side pings in a row, stop the robot. The PID takes a sample when every sensor in use has a
fresh reading (once per round robin): a stale reading is never fed twice.
"""

from micropython import const

from hexapod.fixmath import atan2, mul_q15, sin, to_cdeg
from hexapod.limits import FORMS, check_request
from hexapod.pid import KD, KI, KP, PID
from hexapod.sensors import DEFAULT_MOUNTS, FRONT, LEFT_FRONT, LEFT_REAR, RIGHT_FRONT, RIGHT_REAR, check_mounts
from hexapod.tick import BUSY, MOVING, NOT_STANDING, OK, STANDING, WALKING
from hexapod.turns import sweep_command
from hexapod.walk import STOPPED as WALKER_STOPPED

# The sensor contract's statuses, copied as private constants (folded into the code, no name kept
# on the board; tests/test_viper_twins.py checks each against its source).
_OK = const(0)  # hexapod.sensors.OK
_OUT_OF_RANGE = const(1)  # hexapod.sensors.OUT_OF_RANGE
_NO_ECHO = const(2)  # hexapod.sensors.NO_ECHO
_STUCK = const(3)  # hexapod.sensors.STUCK
_TOO_CLOSE = const(4)  # hexapod.sensors.TOO_CLOSE
_WAIT = const(5)  # hexapod.sensors.WAIT
# What a TOO_CLOSE front ping is taken as.
_MIN_RANGE = const(200)  # hexapod.sensors.MIN_RANGE
_NEAR = const(400)  # from under 4 cm a side sonar going out of range has come too close, 0.1 mm

# Modes.
OFF = const(0)
FOLLOWING = const(1)
CORNER = const(2)
LOST = const(3)
SEARCHING = const(4)
BLOCKED = const(5)
STOPPED = const(6)
MODE_NAMES = ("off", "following", "corner", "lost", "searching", "blocked", "stopped")

# Why the follower stopped, is blocked, or follows on one sensor.
NO_REASON = const(0)
NO_SIDE_SENSOR = const(1)
FRONT_FAILED = const(2)
TOO_CLOSE = const(3)
WALL_NOT_FOUND = const(4)
WALK_REFUSED = const(5)
OBSTACLE = const(6)
DEAD_END = const(7)
REASON_NAMES = (
    "",
    "both side sensors failed",
    "front sensor failed",
    "a side sensor reads under 2 cm",
    "wall not found",
    "the robot refused to walk",
    "obstacle ahead",
    "dead end",
)

# Sensor states.
WAITING = const(0)  # no result yet since follow()
IN_USE = const(1)
NO_WALL = const(2)
FAILED = const(3)
STATE_NAMES = ("waiting", "ok", "no wall", "failed")

# The sensors each side uses, by bit (1: side front, 2: side rear).
USED_NAMES = (
    ("none", "left_front", "left_rear", "left_front+left_rear"),
    ("none", "right_front", "right_rear", "right_front+right_rear"),
)

# Defaults (the simulator tunes them; docs/wall.md explains each).
SPEED = const(800)  # forward speed, 0.1 mm/s
YAW_MAX = const(3000)  # the follower's largest yaw rate (PID output clamp), cdeg/s
I_MAX = const(1000)  # integral clamp, cdeg/s
LOOKAHEAD = const(1000)  # L: the look-ahead point ahead of the sensor pair, 0.1 mm
ANGLE_GUARD = const(800)  # no further turn toward or away from the wall past this angle, cdeg
WALL_GAP = const(1500)  # a side reading beyond set point + this is no wall, 0.1 mm
JUMP = const(300)  # a side reading this much beyond the sensor's last one is an edge, not the wall
MISS_RUN = const(3)  # pings in a row without a steerable reading take a sensor out of use
FRONT_STOP = const(3300)  # stop when something ahead is this close to the body centre, 0.1 mm
FRONT_HYST = const(300)  # ... and go on once it is this much farther
CORNER_RADIUS = const(2500)  # arc radius away from an inside corner, 0.1 mm
CORNER_HYST = const(1000)  # the corner ends when the wall ahead is this much beyond its start
CORNER_TURN = const(27000)  # turning this far in one corner without clearing it: dead end, cdeg
LOST_TURN = const(15000)  # arc toward a lost wall this far, then search, cdeg
SEARCH_GROW = const(500)  # the search spiral's radius grows this fast, 0.1 mm/s
SEARCH_MS = const(30000)  # search this long, then stop, ms
# A pair's sample corrects the walk's prediction of the wall's angle and distance by 1/2**EST_SHIFT of
# the difference: the sonars' noise (sd 3 mm) reaches the PID about 1/4 as large (sd x sqrt(K / (2 - K)),
# K = 1/8), the robot's own turns at once. 1/32 (the first try) let heading slip build into 4-5 mm RMS.
EST_SHIFT = const(3)
# Form crab (issue 22 point 5): the sideways speed is speed * PID output / CRAB_DIV (at the paper's Kp = 25 a
# 1 mm error walks sideways at speed / 36 mm per second: at 48 mm/s it closes in about 0.75 s; 6250, stiffer,
# followed the corrugated wall's bumps out of phase); the robot turns back toward parallel only past
# CRAB_BAND, at CRAB_TURN / 1000 of the excess angle per second, and follows as form yaw on one sonar, past
# CRAB_ANGLE (after a corner) or when a pair's own sample reads the nose _CRAB_EDGE away (the wall's end
# drawing away: an outside corner, a gap); handed over on the angle, it stays yaw while the wall is more than
# _CRAB_NEAR beyond the set point (sliding toward a corner's end cuts it). docs/wall.md has the trials.
CRAB_DIV = const(9000)
CRAB_BAND = const(400)  # cdeg
CRAB_TURN = const(1000)  # yaw rate per angle past the band, 1/s x1000
CRAB_ANGLE = const(1000)  # cdeg
CRAB_SIDE = const(300)  # the sideways speed at most, per mille of the forward speed
_CRAB_EDGE = const(60000)  # 6 degrees, fixmath.ANGLE_UNIT
_CRAB_NEAR = const(100)  # 0.1 mm
_EST_HALF = const(4)  # 2**EST_SHIFT / 2: the correction rounded half up, not floored (no drift)
_COUNT_MAX = const(1000000)  # counters stop here (small ints for ever)
_DEG180 = const(1800000)  # fixmath.ANGLE_UNIT
_DEG360 = const(3600000)
_WRAP = const(0x3FFFFFFF)


def yaw_for_radius(speed, radius):
    """Yaw rate (cdeg/s) that walks a circle of radius (0.1 mm) at speed (0.1 mm/s)."""
    return speed * 5730 // radius  # 18000 / pi = 5729.6 cdeg per radian


class Follower:
    """Follows the left or the right wall on the side sonars by commanding robot (a tick.Robot)."""

    def __init__(self, robot, mounts=DEFAULT_MOUNTS):
        """robot: tick.Robot; mounts: 5 (x, y, heading) (0.1 mm, cdeg) in hexapod.sensors order."""
        check_mounts(mounts)
        self.robot = robot
        self.mounts = tuple(tuple(m) for m in mounts)
        self.pid = PID(KP, KI, KD, YAW_MAX, I_MAX)
        self.mode = OFF
        self.mode_name = MODE_NAMES[OFF]
        self.reason = NO_REASON  # why stopped / blocked (REASON_NAMES)
        self.reason_name = REASON_NAMES[NO_REASON]
        self.side = None  # "left" or "right" while on
        self.setpoint = 0  # 0.1 mm
        self.speed = SPEED  # 0.1 mm/s
        self.form = FORMS[0]
        self.lookahead = LOOKAHEAD  # 0.1 mm
        self.state = [WAITING] * 5  # per sensor, STATE_NAMES
        self.faults = [0] * 5  # NO_ECHO, STUCK and TOO_CLOSE pings per sensor since follow()
        self.fault_total = 0
        self.reading = [-1] * 5  # last steerable reading per sensor, 0.1 mm (-1 none)
        self.used = USED_NAMES[0][0]  # which side sensors steer
        self.distance_only = False  # True while one side sensor is left (no angle)
        self.front = -1  # distance ahead, 0.1 mm (-1: nothing in range)
        self.distance = -1  # last wall distance steered on, 0.1 mm
        self.angle = 0  # last angle to the wall, cdeg, positive = nose away (one sensor: by odometry)
        self.error = 0  # last PID error, 0.1 mm
        self.output = 0  # last PID output after the angle guard, cdeg/s (positive = away)
        self.vx = 0  # last command sent: forward and sideways speed 0.1 mm/s, yaw rate cdeg/s
        self.vy = 0
        self.yaw = 0
        self.updates = 0  # PID updates since follow()
        self.refused = 0  # walk commands the robot refused
        self.walk_code = OK  # the last refusal's reason code (hexapod.tick)
        self.turned = 0  # heading change since the mode began, cdeg
        self._f = LEFT_FRONT
        self._r = LEFT_REAR
        self._away = -1  # yaw sign that turns away from the wall (left wall: clockwise)
        self._base = 1  # baseline, 0.1 mm
        self._wall = 0  # body centre to the wall at the set point, 0.1 mm
        self._stop_at = 0  # front readings that block / start a corner, 0.1 mm
        self._corner_at = 0
        self._used = 0
        self._fresh = 0
        self._miss = [0] * 5
        self._bad = [0] * 5
        self._close = [0] * 5
        self._sent = False
        self._turn = 0  # fixmath.ANGLE_UNIT
        self._adr = 0  # the angle carried on by the walker's heading since the last pair, ANGLE_UNIT
        self._psi = 0
        self._est = False  # the pair's estimate (_adr, _dist) has been started from a sample
        self._dist = 0  # the pair's midpoint distance estimate, 0.1 mm << 4
        self._walked = 0  # forward speed summed over the frames walked since the last sample, 0.1 mm/s
        self._slid = 0  # sideways speed away from the wall summed likewise, 0.1 mm/s (form crab)
        self._crabbing = 0  # form crab, the last sample's law: 1 sideways, 2 turned (the angle), 3 turned (one sonar)
        self._crab_vy = 0  # ... and the command it asked for: sideways speed (0.1 mm/s), yaw rate (cdeg/s)
        self._crab_yaw = 0
        self._held = 0  # the walker's held count at the last frame
        self._t0 = 0
        self._sweep = [0, 0]  # seed 000's full turn: vx (0.1 mm/s), |yaw| (cdeg/s)

    # -- commands ----------------------------------------------------------------------

    def follow(self, side, setpoint, speed=None, form="crab"):
        """Follow the `side` ("left"/"right") wall at `setpoint` (0.1 mm, the side sonar's reading)
        walking at `speed` (0.1 mm/s, default SPEED); form "crab" (the default: sideways to the set
        point), "yaw" (Robot.walk's turn) or "sweeps" (seed 000's coxa sweeps). Returns 0 (following) or a
        hexapod.tick reason code (not standing, busy, unreachable) having changed nothing; bad
        values raise ValueError, changing nothing.
        Called again on the same side and form it changes set point and speed on the fly."""
        check_request(side, setpoint, speed, form)
        robot = self.robot
        if robot.mode != STANDING and robot.mode != WALKING:
            return BUSY if robot.mode == MOVING else NOT_STANDING
        if not robot.body.settled():
            return BUSY
        speed = SPEED if speed is None else speed
        on = self.mode != OFF and self.mode != STOPPED
        if on and side == self.side and form == self.form:
            self.setpoint = setpoint
            self.speed = speed
            self._thresholds()
            self._sent = False  # the next command goes out even if it equals the last one
            return OK
        code = robot.walk(speed, 0, 0)  # straight on until the first sample (the same in both forms)
        if code != OK:
            return code
        if form == "sweeps":
            sweep_command(robot.walker, 4500, 1000, self._sweep)  # seed 000's right turn
            self._sweep[1] = -self._sweep[1]
        self.side = side
        self.setpoint = setpoint
        self.speed = speed
        self.form = form
        left = side == "left"
        self._f = LEFT_FRONT if left else RIGHT_FRONT
        self._r = LEFT_REAR if left else RIGHT_REAR
        self._away = -1 if left else 1
        self._thresholds()
        self._restart()  # after the walk: a walk from a stop starts the walker's heading at 0
        self.vx = speed
        self.vy = self.yaw = 0
        self._sent = True
        return OK

    def off(self):
        """Stop following; the robot finishes its steps and sets its feet down. Returns 0."""
        if self.mode != OFF:
            self.robot.stop()
        self._set_mode(OFF, NO_REASON)
        self._sent = False
        self.vx = self.vy = self.yaw = 0
        return OK

    def set_gains(self, kp, ki, kd):
        """PID gains in milli-units (hexapod.pid: the paper's 25, 0.5, 1 are 25000, 500, 1000);
        ValueError naming the bad one, nothing changed."""
        self.pid.set_gains(kp, ki, kd)

    def _restart(self):
        for k in range(5):
            self.state[k] = WAITING
            self.faults[k] = 0
            self.reading[k] = -1
            self._miss[k] = 0
            self._bad[k] = 0
            self._close[k] = 0
        self.fault_total = 0
        self.updates = 0
        self.refused = 0
        self.walk_code = OK
        self.front = -1
        self.distance = -1
        self.angle = self.error = 0
        self._adr = 0
        self._walked = 0
        self._slid = 0
        self._held = self.robot.walker.held
        self._used = 3
        self.used = USED_NAMES[self._side()][3]
        self.distance_only = False
        self._psi = self.robot.walker.psi
        self.mode = OFF  # a new follow starts afresh whatever the mode was: _set_mode resets the PID, the
        self._set_mode(FOLLOWING, NO_REASON)  # estimate, the law, the output and the fresh readings

    def _side(self):
        return 0 if self._f == LEFT_FRONT else 1

    def _thresholds(self):
        m = self.mounts
        f = m[self._f]
        r = m[self._r]
        self._base = f[0] - r[0]
        side_y = ((f[1] if f[1] > 0 else -f[1]) + (r[1] if r[1] > 0 else -r[1])) >> 1
        self._wall = side_y + self.setpoint
        self._stop_at = FRONT_STOP - m[FRONT][0]
        self._corner_at = self._wall + CORNER_RADIUS - m[FRONT][0]

    # -- the frame ---------------------------------------------------------------------

    def update(self, now_ms, i, dist, status):
        """One frame at loop time now_ms (ms); i: the sonar pinged this frame (-1 none); dist,
        status: the Runner's buffers. Commands the robot when something changed; returns the mode."""
        if self.mode == OFF or self.mode == STOPPED:
            return self.mode
        if i >= 0:
            self._sense(i, dist[i], status[i])
        self._track_turn()
        self._decide(now_ms)
        return self.mode

    def _sense(self, i, d, st):
        if st == _WAIT or (i != FRONT and i != self._f and i != self._r):
            return
        if i != FRONT and st == _OUT_OF_RANGE and self.state[i] == IN_USE and self.reading[i] < _NEAR:
            st = _TOO_CLOSE  # inside 2 cm the module holds its echo: it looks out of range
        fault = st == _NO_ECHO or st == _STUCK or st == _TOO_CLOSE  # noqa: SIM109 (a tuple may allocate)
        if fault and self.faults[i] < _COUNT_MAX:
            self.faults[i] += 1
            self.fault_total += 1
        if i == FRONT:
            self._sense_front(d, st)
            return
        # A reading that jumps away from the last one is the wall's edge leaving the beam (an
        # outside corner, a gap), not the wall: never steered on. Nearer readings always count.
        if st == _OK and d <= self.setpoint + WALL_GAP and (self.state[i] != IN_USE or d - self.reading[i] <= JUMP):
            self.reading[i] = d
            self.state[i] = IN_USE
            self._miss[i] = 0
            self._bad[i] = 0
            self._close[i] = 0
            self._fresh |= 1 if i == self._f else 2
            return
        if self._miss[i] < _COUNT_MAX:
            self._miss[i] += 1
        if st == _NO_ECHO or st == _STUCK:  # noqa: SIM109
            if self._bad[i] < _COUNT_MAX:
                self._bad[i] += 1
        else:
            self._bad[i] = 0
        if st == _TOO_CLOSE:
            if self._close[i] < _COUNT_MAX:
                self._close[i] += 1
        else:
            self._close[i] = 0
        if self._miss[i] >= MISS_RUN:
            self.state[i] = FAILED if self._bad[i] >= MISS_RUN else NO_WALL

    def _sense_front(self, d, st):
        if st == _NO_ECHO or st == _STUCK:  # noqa: SIM109
            if self._bad[FRONT] < _COUNT_MAX:
                self._bad[FRONT] += 1
            if self._bad[FRONT] >= MISS_RUN:
                self.state[FRONT] = FAILED  # the last distance ahead is kept until then
            return
        self._bad[FRONT] = 0
        if st == _OUT_OF_RANGE:
            self.front = -1
            self.state[FRONT] = NO_WALL
        else:
            self.front = d if st == _OK else _MIN_RANGE
            self.state[FRONT] = IN_USE

    def _track_turn(self):
        p = self.robot.walker.psi
        d = p - self._psi
        if d > _DEG180:
            d -= _DEG360
        elif d < -_DEG180:
            d += _DEG360
        self._psi = p
        w = self.robot.walker
        if w.held == self._held:
            if self._walked < _COUNT_MAX:
                self._walked += w.vel[0]
                self._slid += self._away * w.vel[1]  # away from the wall: + (only form crab walks sideways)
        else:
            self._held = w.held
        self._adr += self._away * d  # turning away from the wall opens the angle
        if self._adr > _DEG180:
            self._adr = _DEG180
        elif self._adr < -_DEG180:
            self._adr = -_DEG180
        t = self._turn + d
        if -100000000 < t < 100000000:
            self._turn = t
            self.turned = (t + 50) // 100

    def _decide(self, now):
        f = self._f
        r = self._r
        st = self.state
        if st[FRONT] == FAILED:
            return self._halt(FRONT_FAILED)
        if st[f] == FAILED and st[r] == FAILED:
            return self._halt(NO_SIDE_SENSOR)
        if self._close[f] >= 2 or self._close[r] >= 2:
            return self._halt(TOO_CLOSE)
        ahead = self.front
        if self.mode == BLOCKED:
            if ahead >= 0 and ahead < self._stop_at + FRONT_HYST:
                return
            self._set_mode(FOLLOWING, NO_REASON)
        elif ahead >= 0 and ahead < self._stop_at:
            return self._halt(OBSTACLE, BLOCKED)
        if self.mode == CORNER:
            if ahead >= 0 and ahead < self._corner_at + CORNER_HYST:
                if self._turn > CORNER_TURN * 100 or self._turn < -CORNER_TURN * 100:
                    self._halt(DEAD_END)
                else:
                    self._walk(self.speed, self._away * self._yaw_for(CORNER_RADIUS))
                return
            self._set_mode(FOLLOWING, NO_REASON)
        elif ahead >= 0 and ahead < self._corner_at:
            self._set_mode(CORNER, NO_REASON)
            self._walk(self.speed, self._away * self._yaw_for(CORNER_RADIUS))
            return
        used = 0
        if st[f] == IN_USE or st[f] == WAITING:
            used = 1
        if st[r] == IN_USE or st[r] == WAITING:
            used |= 2
        if used != self._used:
            # Another set of sensors: another measurement; no derivative across the change.
            self._used = used
            self.used = USED_NAMES[self._side()][used]
            self.distance_only = used == 1 or used == 2
            self.pid.reset(True)
            self._est = False
        if used == 0:
            self._lost(now)
            return
        if self.mode != FOLLOWING:
            self._set_mode(FOLLOWING, NO_REASON)
        if self._fresh & used == used:
            self._fresh = 0
            self._steer(now, used)
        elif not self._sent:
            # Not sent yet (refused, or no sample: straight; crab: the last sideways command).
            if self._crabbing == 1:
                self._walk(self.speed, self._crab_yaw, self._crab_vy)
            else:
                self._walk(self.speed, self._away * self.output)

    def _steer(self, now, used):
        rd = self.reading
        if used == 3:
            df = rd[self._f]
            dr = rd[self._r]
            a = atan2(df - dr, self._base)
            d = (df + dr) << 3
            if self._est:
                # The walk's prediction since the last sample (the angle by the walker's heading each
                # frame, the distance by its forward travel at that angle), corrected by 1/2**EST_SHIFT
                # of what the sample says: the PID steers on the wall, not on the sonars' noise.
                s = to_cdeg(self._adr)
                self._dist += mul_q15(self._walked * 8 // 25, sin(s))
                if self._slid:
                    self._dist += mul_q15(self._slid * 8 // 25, sin(s + 9000))  # x cos(angle)
                self._adr += (a - self._adr + _EST_HALF) >> EST_SHIFT
                self._dist += (d - self._dist + _EST_HALF) >> EST_SHIFT
            else:
                self._adr = a
                self._dist = d
                self._est = True
            self.angle = to_cdeg(self._adr)
            self.distance = (self._dist + 8) >> 4
            m = self.distance + mul_q15(self.lookahead, sin(self.angle))  # + L sin(angle)
        else:
            # One sensor: its distance, with the angle of the last pair carried on by the walker's
            # own heading (odometry) and let fade (1/16 an update), so heading slip cannot pile up.
            k = self._f if used == 1 else self._r
            self._adr -= self._adr >> 4
            self.angle = to_cdeg(self._adr)
            s = sin(self.angle)
            x = self.mounts[k][0] - ((self.mounts[self._f][0] + self.mounts[self._r][0]) >> 1)
            self.distance = rd[k] - mul_q15(x, s)  # the pair's midpoint
            m = self.distance + mul_q15(self.lookahead, s)
        self._walked = 0
        self._slid = 0
        if self.form == "crab":
            # Crab on the pair within CRAB_ANGLE of parallel; on one sonar (an edge, a gap, an outside
            # corner), further round (after a corner) or when this sample alone reads the nose _CRAB_EDGE
            # away (the wall's end leaving the front beam: the estimate takes a few samples to follow) it
            # turns as form yaw, and once turned for the angle it stays so while the wall is farther than
            # set point + _CRAB_NEAR: at an outside corner the pair reads far until round it, and crabbing
            # toward the wall's end cut the corner (docs/wall.md). A change of law is a change of
            # measurement: no derivative across it.
            law = 3
            if used == 3:
                law = 2
                if (
                    -CRAB_ANGLE < self.angle < CRAB_ANGLE
                    and a < _CRAB_EDGE
                    and (self._crabbing != 2 or self.distance - self.setpoint <= _CRAB_NEAR)
                ):
                    law = 1
            if (law == 1) != (self._crabbing == 1):
                self.pid.reset(True)
            self._crabbing = law
            if law == 1:
                m = self.distance  # crab holds the wall distance itself (no look-ahead)
        u = self.pid.update(self.setpoint, m, now)
        self.error = self.pid.error
        if self.updates < _COUNT_MAX:
            self.updates += 1
        if self._crabbing == 1:
            self.output = u
            return self._crab(u)
        # Past the guard angle no further turn that way: the pair's beams would lose the wall. On one
        # sonar the angle is odometry, and at an outside corner the rear sonar sees the wall's end
        # drawing away at the guard angle: the turn toward it must go on (corridor world).
        if used == 3 and ((u > 0 and self.angle >= ANGLE_GUARD) or (u < 0 and self.angle <= -ANGLE_GUARD)):
            u = 0
        self.output = u
        self._walk(self.speed, self._away * u)

    def _crab(self, u):
        # Form crab: the PID holds the wall distance itself (no look-ahead) and its output is walked
        # as a sideways speed, speed * u / CRAB_DIV, plus the sideways speed that cancels the heading's
        # drift toward or away from the wall (speed * sin(angle)), at most CRAB_SIDE of the speed: the
        # walker's reach is a disc, so a sideways speed of 10 % of the forward one costs it 0.5 %, where
        # every degree turned costs about 0.07 s (docs/wall.md). The robot turns only to bring the
        # angle back inside CRAB_BAND (the heading slips 1 degree a stride, a start is up to 10 degrees
        # off), so the sonars stay in their beam.
        v = self.speed
        a = self.angle
        side = v * u // CRAB_DIV - mul_q15(v, sin(a))
        lim = v * CRAB_SIDE // 1000
        if side > lim:
            side = lim
        elif side < -lim:
            side = -lim
        yaw = 0
        if a > CRAB_BAND:
            yaw = CRAB_BAND - a
        elif a < -CRAB_BAND:
            yaw = -CRAB_BAND - a
        yaw = yaw * CRAB_TURN // 1000
        self._crab_vy = self._away * side
        self._crab_yaw = self._away * yaw
        self._walk(v, self._crab_yaw, self._crab_vy)

    def _lost(self, now):
        if self.mode != LOST and self.mode != SEARCHING:
            self._set_mode(LOST, NO_REASON)
        toward = -self._away
        if self.mode == LOST:
            if self._turn > LOST_TURN * 100 or self._turn < -LOST_TURN * 100:
                self._set_mode(SEARCHING, NO_REASON)
                self._t0 = now
            else:
                self._walk(self.speed, toward * self._yaw_for(self._wall))
                return
        t = (now - self._t0) & _WRAP
        if t > SEARCH_MS:
            self._halt(WALL_NOT_FOUND)
            return
        self._walk(self.speed, toward * self._yaw_for(self._wall + SEARCH_GROW * (t // 100) // 10))

    def _yaw_for(self, radius):
        w = yaw_for_radius(self.speed, radius)
        return w if w < self.pid.out_max else self.pid.out_max

    def _set_mode(self, mode, reason):
        if mode != self.mode:
            self.mode = mode
            self.mode_name = MODE_NAMES[mode]
            self._turn = 0
            self.turned = 0
            if mode == FOLLOWING:
                self.pid.reset()
                self._est = False
                self._crabbing = 0
                self.output = 0
                self._fresh = 0
                self._sent = False
        self.reason = reason
        self.reason_name = REASON_NAMES[reason]

    def _halt(self, reason, mode=STOPPED):
        self._set_mode(mode, reason)
        self.robot.stop()
        self._sent = False
        self.vx = self.vy = self.yaw = 0

    def _walk(self, vx, yaw, vy=0):
        """Send (vx, vy, yaw) unless it is what was sent last; returns the robot's code."""
        if self.form == "sweeps":
            # Seed 000's form: straight blended with its full turn (left coxas 45, right 10 deg,
            # or mirrored) by the share of the largest yaw rate asked for.
            a = yaw if yaw >= 0 else -yaw
            k = a * 1000 // self.pid.out_max
            if k > 1000:
                k = 1000
            vx = vx + (self._sweep[0] - vx) * k // 1000
            w = self._sweep[1] * k // 1000
            yaw = w if yaw >= 0 else -w
        if self._sent and vx == self.vx and yaw == self.yaw and vy == self.vy:
            return OK
        walker = self.robot.walker
        was_stopped = walker.state == WALKER_STOPPED
        code = self.robot.walk(vx, vy, yaw)
        if code != OK:
            if self.refused < _COUNT_MAX:
                self.refused += 1
            self.walk_code = code
            if code == NOT_STANDING and self.mode != OFF:
                self._halt(WALK_REFUSED)
            return code
        if was_stopped:
            self._psi = walker.psi  # a walk from a stop starts the walker's heading at 0
        self.vx = vx
        self.vy = vy
        self.yaw = yaw
        self._sent = True
        return OK


def status_text(f):
    """The follower's part of the status line (allocates: not for the frame)."""
    if f.mode == OFF:
        return "wall off"
    return "wall %s %s%s d %d a %d e %d u %d front %d used %s faults %d%s" % (
        f.side,
        f.mode_name,
        " (" + f.reason_name + ")" if f.reason else "",
        f.distance,
        f.angle,
        f.error,
        f.output,
        f.front,
        f.used,
        f.fault_total,
        " distance only" if f.distance_only else "",
    )
