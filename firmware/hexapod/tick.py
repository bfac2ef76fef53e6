"""The 50 Hz control tick: walk command -> feet -> body pose -> leg IK -> servo pulses -> frame.

Robot.tick(now_ms) runs one frame and hands 18 pulse widths (us; leg 1 coxa, femur, tibia,
then leg 2 ... leg 6; 0 = no pulse, servo limp) to `frame.write_frame(pulses)`. Any object
with that method will do: the PCA9685 driver, or FrameBuffer below (a dry run / test double).
The list passed belongs to the robot: a sink that keeps it must copy it. A move out of RELAXED
(stand_up, sit_down) soft-starts: the leg groups get their pulses 160 ms apart (WAKE_*), the
first pose held 480 ms, so 18 servos never start in one frame.

The tick reads no clock: the loop that owns one passes time.ticks_ms() (wrapping at 2**30)
and the tick counts every interval longer than the 20 ms budget in `overruns` (the worst in
`worst_interval_ms`). A late tick still advances the motion by exactly one frame: nothing
is skipped, and nothing jumps to catch up. A steady tick allocates no heap memory.

Commands change state between ticks. Bad values raise ValueError (naming the value and the
allowed range); a command the robot cannot carry out now returns a reason code (below) and
changes nothing. A posture move (stand_up, sit_down, relax, set_height) is checked frame by
frame before it starts: one that would pass a point out of reach or a pulse outside its servo's
range is refused (PATH_IK, PATH_SERVO; path_leg, jog_code, jog_excess, jog_servo say where and
why). A frame whose IK or pulse check fails is not sent: the servos keep the last frame,
`faults` counts it and `reason`, `fault_leg`, `fault_code`, `fault_servo`, `fault_excess` say
why (the planner is built never to get there).
"""

import sys
from array import array

from micropython import const

from hexapod.body import FINE_SHIFT, Body
from hexapod.fixmath import cos, isqrt, mul_q15, sin
from hexapod.gait import TICK_MS, TRIPOD, check_cycle_ms, check_gait
from hexapod.leg import OK
from hexapod.posture import POSTURE_STEP, Posture
from hexapod.reach import disc_steps, find_table, table_discs
from hexapod.servo import ServoMap
from hexapod.turns import sweep_command
from hexapod.walk import SERVO_SPEED, SPEED_MAX, STEP_MAX, STOPPED, YAW_RATE_MAX, Walker

# isort: split
# After walk: compiling walk.py from source needs the VM's room in one piece (a 256 KB heap).
from hexapod.gaitswitch import ROOMS
from hexapod.stability import NO_SUPPORT, support_margin

# The viper twins (docs/viper.md): the frame and the pose check compiled by the viper emitter where
# MicroPython has one (hexapod/_tick_viper.py and _body_viper.py, proven equal to _output_plain
# and Body.settled by tests/test_tick_viper.py); CPython and CircuitPython run the plain code.
_output_fast = _settled_fast = None
if sys.implementation.name == "micropython":
    try:
        from hexapod._body_viper import settled as _settled_fast
        from hexapod._tick_viper import output as _output_fast
    except Exception:  # no viper emitter on this build
        _output_fast = _settled_fast = None
_settled = _settled_fast or Body.settled  # the pose check, called as _settled(body)

# Reason codes (leg IK codes 1..9 come through in fault_code with fault_leg).
WALKING_NOW = const(20)
BUSY = const(21)
NOT_STANDING = const(22)
UNREACHABLE = const(23)
FRAME_IK = const(24)
FRAME_SERVO = const(25)
JOG_IK = const(26)  # a jog refused by the leg: jog_code (hexapod.leg code), jog_excess (0.1 mm or cdeg)
JOG_SERVO = const(27)  # a jog or calibration refused by a servo: jog_servo, jog_code (servo code), jog_excess (us)
# 28 is hexapod.walk.SERVO_SPEED.
PATH_IK = const(30)  # a posture move refused: on its way leg path_leg would fail its IK (jog_code, _excess)
PATH_SERVO = const(31)  # a posture move refused: on its way servo jog_servo would leave its range (jog_code, _excess)
CONFIGURING = const(32)  # refused: a gait, cycle, lift, pose or height change is still being checked

RELAXED = const(0)
SITTING = const(1)
MOVING = const(2)
STANDING = const(3)
WALKING = const(4)
JOG = const(5)  # single servos or legs placed by hand (console jogging); each frame re-sends the held pulses
MODE_NAMES = ("relaxed", "sitting", "moving", "standing", "walking", "jog")

_WRAP = const(0x3FFFFFFF)  # time.ticks_ms() wraps at 2**30
# Soft start: a move out of RELAXED switches the servos on a leg group at a time, _WAKE_STAGGER
# frames (160 ms) apart, front pair, middle pair, rear pair, so the supply never sees 18 hobby
# servos start at once (each jumps to its first pulse at full speed, drawing its stall current);
# the first pose is held until the last group has had _WAKE_STAGGER frames to get there.
_WAKE_STAGGER = const(8)
WAKE_FRAMES = const(24)  # 3 groups x _WAKE_STAGGER: frames the first pose is held
WAKE_GROUP = (0, 1, 2, 2, 1, 0)  # each leg's group (legs 1 RF .. 6 LF)
_RHO_MIN = const(50)  # a leg needs a reach disc this wide (0.1 mm) to walk
# A configure asked with wait=False (the console's) runs in the frames' slack: this many of its IK
# solves (hexapod.reach's steps, the posture trial's) after each tick's frame. On an emulated Pico
# a step there costs ~0.6-1.2 ms; a standing frame ~2.4 ms: two keep it near 5 ms. Walking, a frame
# is 3.1-4.1 ms and a walk command asked in it 1.3-1.7 ms more: one step (6.2-6.6 ms with two,
# hexapod pico bench frame --scenario drive, docs/pico.md), and none in the ticks that take a gait
# change on the move (gaitswitch.after_tick's parts, each ~1.5 ms).
# Under runner.Runner.run (defer set), a walking frame's step waits for the frame's commands
# instead: paid after them (pay), and not at all in a frame that ran one, unless the frame before
# skipped its step too (a command a frame would starve the configure): a walk command (~1.1 ms)
# and a step (~0.85 ms) no longer share a walking frame (6.7 ms before).
JOB_STEPS = const(2)
_JOB_STEPS_WALKING = const(1)


def describe(code):
    """A sentence for a reason code, for the edges."""
    return {
        OK: "ok",
        WALKING_NOW: "refused: the robot is walking; stop first",
        BUSY: "refused: a posture or pose move is still running",
        NOT_STANDING: "refused: the robot is not standing; stand up first",
        UNREACHABLE: "refused: that would put a foot out of reach or a joint past its limit",
        FRAME_IK: "frame held: a foot was out of reach or a joint past its limit",
        FRAME_SERVO: "frame held: a pulse was outside its servo's calibrated range",
        JOG_IK: "refused: that foot is out of reach or a joint past its limit",
        JOG_SERVO: "refused: that pulse is outside the servo's calibrated range",
        PATH_IK: "refused: on the way a foot would leave its reach or a joint pass its limit",
        PATH_SERVO: "refused: on the way a pulse would leave its servo's calibrated range",
        SERVO_SPEED: "refused: the servos are too slow for this gait's swing (longer cycle or lower lift)",
        CONFIGURING: "refused: a gait, pose or height change is still being checked; try again shortly",
    }.get(code, "unknown reason %d" % code)


def default_servos(geometry):
    """18 ServoMaps at seed 001's 10 us/degree, each joint's limit range centred on 1500 us."""
    maps = []
    lim = geometry.limits
    for _ in range(6):
        for j in range(3):
            mid = (lim[2 * j] + lim[2 * j + 1]) // 2
            maps.append(ServoMap(centre_us=1500 - mid // 10))
    return maps


class FrameBuffer:
    """A frame sink that keeps a copy of the last frame and counts frames (dry runs, tests)."""

    def __init__(self):
        self.pulses = [0] * 18
        self.frames = 0

    def write_frame(self, pulses):
        out = self.pulses
        for k in range(18):
            out[k] = pulses[k]
        self.frames += 1


class _Feet:
    """Scratch feet (body frame, fine) a posture move is tried on before it is queued."""

    def __init__(self, walker):
        self.fx = array("i", [0] * 6)
        self.fy = array("i", [0] * 6)
        self.fz = array("i", [0] * 6)
        self.nx = walker.nx  # the posture moves read the neutral stance and the ground, never write them
        self.ny = walker.ny
        self.ground = walker.ground


# The posture moves Robot._move plans (each stand or sit has two variants: Posture's `straight`).
_STAND = const(0)
_STAND_STRAIGHT = const(1)
_SIT = const(2)
_SIT_LIFTED = const(3)
_HEIGHT = const(4)
# The configures Robot._steps finishes besides a gait (0..3, hexapod.gait's numbers).
_POSE = const(5)
_PARAMS = const(6)


class Robot:
    """Geometry + servo calibration + frame sink: commands in, one frame out per tick()."""

    def __init__(self, geometry, servos, frame, pulses=None):
        """servos: 18 ServoMaps; frame: has write_frame(pulses); pulses: an optional list of 18
        the caller owns, written every frame (else the robot makes its own)."""
        if pulses is not None and len(pulses) != 18:
            raise ValueError("pulses: need a list of 18, got %d" % len(pulses))
        if len(servos) != 18:
            raise ValueError("servos: need 18 ServoMaps (legs 1..6 x coxa, femur, tibia), got %d" % len(servos))
        if not hasattr(frame, "write_frame"):
            raise ValueError("frame: needs a write_frame(pulses) method")
        self.geometry = geometry
        self.servos = list(servos)
        self.frame = frame
        self.body = Body(geometry)
        self._probe = Body(geometry)  # the target pose, for checks made before moving
        self.walker = Walker(geometry)
        self.posture = Posture()
        self._trial = Posture()  # a posture move tried frame by frame before it is queued
        self._feet = _Feet(self.walker)
        self.rest_z = -(geometry.sit_height - geometry.foot_clearance) << FINE_SHIFT
        self.angles = [0] * 18  # last joint angles sent, cdeg
        self.pulses = [0] * 18 if pulses is None else pulses  # last pulses sent, us
        self._angles = array("i", [0] * 18)  # scratch, array("i"): _tick_viper.output writes them as machine words
        self._pulses = array("i", [0] * 18)
        self._leg = [0, 0, 0]
        self._rho = [0] * 6
        # The posture trial's own scratch: it may run between ticks, which write _angles and _pulses.
        self._trial_angles = array("i", [0] * 18)
        self._trial_pulses = array("i", [0] * 18)
        self._trial_leg = [0, 0, 0]
        self._path_code = OK
        self._job = None  # a configure under way (a generator stepped JOB_STEPS solves a tick)
        self._holds = False  # it needs the robot standing still (a pose or height): walking waits
        self.job_code = OK  # how the last configure ended (set_* with wait=False)
        self.job_steps = 0  # solves done by configures in the frames' slack (a work counter)
        self.defer = False  # a walking tick's step left for pay() (runner.Runner.run sets it)
        self.owed = False  # this frame's walking step is still to be paid
        self._skipped = False  # the last frame's was skipped (a command ran in it)
        self.mode = RELAXED
        self.after = RELAXED  # the mode a running posture move ends in
        self.wake = WAKE_FRAMES  # frames since a move left RELAXED, up to WAKE_FRAMES (soft start)
        self.ticks = 0
        self.overruns = 0
        self.worst_interval_ms = 0
        self.faults = 0
        self.reason = OK
        self.fault_leg = 0
        self.fault_code = OK
        self.fault_servo = 0  # the servo (0..17) of a FRAME_SERVO hold
        self.fault_excess = 0  # how far the held frame missed (0.1 mm, cdeg or us)
        self.path_leg = 0  # the leg (0..5) a PATH_IK / PATH_SERVO refusal is about
        self._last_ms = 0
        self._timed = False
        self.jog_servo = 0  # why the last jog or calibration was refused (JOG_IK, JOG_SERVO)
        self.jog_code = OK
        self.jog_excess = 0
        self.gait = TRIPOD
        # Static stability while a gait change settles (walker.pending or settling): the body centre's
        # distance inside the stance feet's polygon (0.1 mm, hexapod.stability; NO_SUPPORT on fewer
        # than three feet), this tick's and the smallest since the last gait asked for.
        self.margin = NO_SUPPORT
        self.margin_min = NO_SUPPORT
        self._mx = [0] * 6
        self._my = [0] * 6
        self._down = [False] * 6
        self.speed_cap = 0  # walking capped at this planar speed (0.1 mm/s; 0: no cap), cap_speed
        self.yaw_cap = 0  # and this yaw rate (cdeg/s)
        self.asked_vx = 0  # the last walk command as asked, before the cap
        self.asked_vy = 0
        self.asked_yaw = 0
        # Each gait keeps its own cycle time (ms): the robot file's until set_params sets one.
        self.cycles = list(geometry.gait_cycle_ms)
        self.cycle_ms = self.cycles[TRIPOD]
        # The robot file's own settings come from its guard table (robots/NAME_guard.py, made on
        # the host and checked against the live guard), else the guard runs here.
        self.walker.table = self._table = find_table(geometry)
        self._drain(self._discs(self._probe, self.walker.lift))
        self.walker.pose_body = self._probe  # the servo-speed check sees the pose asked for
        self.walker.configure(TRIPOD, self.cycle_ms, self.walker.lift, self.walker.step, self._rho)
        # Until told otherwise (assume_angles), the robot rests on its body, feet at neutral.
        for i in range(6):
            self.walker.fz[i] = self.rest_z

    # -- the tick ----------------------------------------------------------------------

    def tick(self, now_ms):
        """One 20 ms frame at loop time now_ms; returns OK or the reason the frame was held.
        A configure under way (wait=False) then takes JOB_STEPS of its IK solves (walking fewer)."""
        # One function for the frame on purpose: each call a tick makes costs ~15-25 us on a
        # Pico (the frame split in three calls took ~60 us of it: hexapod pico bench frame).
        if self._timed:
            d = (now_ms - self._last_ms) & _WRAP
            if d > TICK_MS:
                self.overruns += 1
                if d > self.worst_interval_ms:
                    self.worst_interval_ms = d
        self._timed = True
        self._last_ms = now_ms
        self.ticks += 1
        m = self.mode
        if m == RELAXED:
            p = self.pulses
            for k in range(18):
                p[k] = 0
            self.frame.write_frame(p)
            code = self.reason = OK
        elif m == JOG:
            self.frame.write_frame(self.pulses)
            code = self.reason = OK
        else:
            if m == MOVING:
                if self.wake < WAKE_FRAMES:
                    self.wake += 1  # the first pose held while the leg groups come on
                elif not self.posture.step(self.walker):
                    self.mode = self.after
            elif m == STANDING or m == WALKING:  # noqa: SIM109 (a tuple test may allocate)
                # A settled pose makes slew() a no-op (its frame is a heap one).
                if not _settled(self.body):
                    self.body.slew()
                if m == WALKING:
                    w = self.walker
                    if w.update() == STOPPED:
                        self.mode = STANDING
                    if w.pending or w.settling:
                        self._margin(w)
            if _output_fast is not None and not _output_fast(self):
                if self.wake < WAKE_FRAMES:
                    self._asleep()
                self.frame.write_frame(self.pulses)
                code = self.reason = OK
            else:
                code = self._output_plain()
        if self._job is not None:
            if m != WALKING:
                self._work(JOB_STEPS)
            elif self.walker.pending < ROOMS:
                if self.defer:
                    self.owed = True
                else:
                    self._work(_JOB_STEPS_WALKING)
        return code

    def pay(self, commanded):
        """The walking step tick() left owed (defer), after the frame's commands: none when this
        frame ran a command (commanded), unless the last frame skipped its step too."""
        self.owed = False
        if commanded and not self._skipped:
            self._skipped = True
            return
        self._skipped = False
        job = self._job
        if job is not None:  # _work(_JOB_STEPS_WALKING) written out: one call fewer in a full frame
            next(job)
            self.job_steps += 1

    def _work(self, n):
        job = self._job
        for _ in range(n):
            next(job)
            self.job_steps += 1
            if self._job is None:
                return

    def _margin(self, w):
        """margin and margin_min for the walker's planned feet (a gait change is settling)."""
        xs = self._mx
        ys = self._my
        down = self._down
        for i in range(6):
            xs[i] = w.fx[i] >> FINE_SHIFT
            ys[i] = w.fy[i] >> FINE_SHIFT
            down[i] = w.su[i] < 0
        m = support_margin(xs, ys, down)
        self.margin = m
        if self.margin_min == NO_SUPPORT or m < self.margin_min:
            self.margin_min = m

    def _output_plain(self):
        w = self.walker
        legs = self.geometry.legs
        a = self._angles
        leg = self._leg
        for i in range(6):
            self.body.to_leg(i, w.fx[i], w.fy[i], w.fz[i], leg, 0)
            code = legs[i].ik(leg[0], leg[1], leg[2], a, 3 * i)
            if code != OK:
                return self._fault(FRAME_IK, i, code, legs[i].excess)
        p = self._pulses
        for k in range(18):
            code = self.servos[k].pulse(a[k], p, k)
            if code != OK:
                self.fault_servo = k
                return self._fault(FRAME_SERVO, k // 3, code, self.servos[k].excess)
        for k in range(18):
            self.angles[k] = a[k]
            self.pulses[k] = p[k]
        if self.wake < WAKE_FRAMES:
            self._asleep()
        self.frame.write_frame(self.pulses)
        self.reason = OK
        return OK

    def _asleep(self):
        """While waking (the soft start), the leg groups not yet on get no pulse."""
        p = self.pulses
        for k in range(18):
            if WAKE_GROUP[k // 3] * _WAKE_STAGGER >= self.wake:
                p[k] = 0

    def _fault(self, reason, leg, code, excess):
        self.faults += 1
        self.reason = reason
        self.fault_leg = leg + 1
        self.fault_code = code
        self.fault_excess = excess
        return reason

    # -- commands (between ticks) ------------------------------------------------------

    def assume_angles(self, angles):
        """Declare where the 18 joints are (cdeg), e.g. read back at power-up; only when relaxed."""
        if self.mode != RELAXED:
            return NOT_STANDING if self.mode != WALKING else WALKING_NOW
        if len(angles) != 18:
            raise ValueError("angles: need 18 values (cdeg), got %d" % len(angles))
        self._feet_from(angles, self.walker)
        return OK

    def _feet_from(self, angles, out):
        """out's feet (fx, fy, fz: body frame, fine) where the 18 joint angles (cdeg) put them."""
        feet = [0] * 18
        for i in range(6):
            self.geometry.legs[i].fk(angles[3 * i], angles[3 * i + 1], angles[3 * i + 2], self._leg, 0)
            self._inside(i, self._leg)
            x = self._leg[0]
            y = self._leg[1]
            c = self.geometry.mount_cos[i]
            s = self.geometry.mount_sin[i]
            feet[3 * i] = self.geometry.mount_x[i] + ((x * c - y * s + 16384) >> 15)
            feet[3 * i + 1] = self.geometry.mount_y[i] + ((x * s + y * c + 16384) >> 15)
            feet[3 * i + 2] = self._leg[2]
        for i in range(6):
            out.fx[i] = feet[3 * i] << FINE_SHIFT
            out.fy[i] = feet[3 * i + 1] << FINE_SHIFT
            out.fz[i] = feet[3 * i + 2] << FINE_SHIFT

    def _inside(self, i, foot):
        """Leg i's foot (leg frame, 0.1 mm) from forward kinematics, moved at most one posture
        frame's travel toward its resting place until its IK solves: angles at a limit or a
        stretched leg round to a point just outside (0.1 mm, 0.01 deg), which no frame could send."""
        lg = self.geometry.legs[i]
        x = foot[0]
        y = foot[1]
        z = foot[2]
        dx = self.geometry.neutral_reach - x
        dz = (self.rest_z >> FINE_SHIFT) - z
        d = isqrt(dx * dx + y * y + dz * dz)
        if d == 0:
            return
        for s in range(0, POSTURE_STEP + 1, 2):
            foot[0] = x + dx * s // d
            foot[1] = y - y * s // d
            foot[2] = z + dz * s // d
            if lg.ik(foot[0], foot[1], foot[2], self._angles, 0) == OK:
                return
        foot[0] = x  # still outside: the posture move's check refuses it, naming the leg
        foot[1] = y
        foot[2] = z

    def _can_move(self):
        if self.mode == WALKING:
            return WALKING_NOW
        if self._holds:
            return CONFIGURING
        if self.mode == MOVING or not _settled(self.body):
            return BUSY
        return OK

    def stand_up(self):
        """From wherever the feet are: clear the ground, go to neutral, raise the body."""
        return self._move(_STAND, _STAND_STRAIGHT, STANDING)

    def sit_down(self):
        """Lower the body onto the ground, lift the feet just clear of it and bring any foot that
        is not at its neutral place (a jogged leg) there."""
        return self._move(_SIT, _SIT_LIFTED, SITTING)

    def _plan(self, posture, feet, plan):
        if plan in (_STAND, _STAND_STRAIGHT):
            posture.stand_up(feet, self.rest_z, plan == _STAND_STRAIGHT)
        elif plan in (_SIT, _SIT_LIFTED):
            posture.sit_down(feet, self.rest_z, plan == _SIT)
        else:
            posture.to_height(feet, feet.ground)

    def _move(self, plan, other, after):
        """Start a posture move ending in mode `after` along plan's path, else along other's,
        else refuse it changing nothing (the reason is other's)."""
        code = self._can_move()
        if code != OK:
            return code
        w = self.walker
        self._start_feet()
        if self._path_clear(plan) != OK:
            plan = other
            self._start_feet()  # the trial moved the scratch feet
            code = self._path_clear(plan)
            if code != OK:
                return code
        if self.mode == JOG:
            self._feet_from(self.angles, w)
        elif self.mode == RELAXED:
            self.wake = 0  # the soft start
        self._plan(self.posture, w, plan)
        self.after = after
        self.mode = MOVING
        return OK

    def _start_feet(self):
        """The scratch feet where a posture move starts: the walker's, or where the jog left them."""
        w = self.walker
        f = self._feet
        if self.mode == JOG:
            self._feet_from(self.angles, f)
        else:
            for i in range(6):
                f.fx[i] = w.fx[i]
                f.fy[i] = w.fy[i]
                f.fz[i] = w.fz[i]
        f.ground = w.ground

    def _path_clear(self, plan):
        """Try the posture move `plan` on the scratch feet (already where the move starts), frame
        by frame as the tick would send it: OK, or PATH_IK / PATH_SERVO for its first bad frame."""
        self._drain(self._path_steps(plan))
        return self._path_code

    def _path_steps(self, plan):
        """_path_clear one leg solve at a time (a generator; its code in _path_code when done)."""
        f = self._feet
        trial = self._trial
        self._plan(trial, f, plan)
        legs = self.geometry.legs
        a = self._trial_angles
        p = self._trial_pulses
        leg = self._trial_leg
        more = True
        self._path_code = OK
        while more:  # every frame of the move, then the pose it ends in (once more: it is held there)
            more = trial.step(f)
            for i in range(6):
                self.body.to_leg(i, f.fx[i], f.fy[i], f.fz[i], leg, 0)
                code = legs[i].ik(leg[0], leg[1], leg[2], a, 3 * i)
                yield
                if code != OK:
                    self.path_leg = i
                    self.jog_code = code
                    self.jog_excess = legs[i].excess
                    trial.clear()
                    self._path_code = PATH_IK
                    return
            for k in range(18):
                code = self.servos[k].pulse(a[k], p, k)
                if code != OK:
                    self.path_leg = k // 3
                    self._servo_refused(k, code, self.servos[k].excess)
                    trial.clear()
                    self._path_code = PATH_SERVO
                    return

    # -- configures: now (wait=True), or JOB_STEPS solves a tick (wait=False) ---------------

    def configuring(self):
        """True while a configure asked with wait=False is under way (its code then in job_code)."""
        return self._job is not None

    def _drain(self, steps):
        if steps is not None:
            for _ in steps:
                pass

    def _discs(self, body, lift):
        """The reach discs under body's pose at lift into _rho: from the guard table (None), else
        a generator that finds them (reach.disc_steps)."""
        w = self.walker
        if self._table is not None and table_discs(self._table, body, w.ground, lift, self._rho):
            return None
        return disc_steps(w, body, lift, self._rho)

    def _start(self, job, holds, wait):
        """Run a configure's generator now (wait: returns its code), or from the next tick on
        (returns OK at once; configuring() until done, then job_code)."""
        self._job = job
        self._holds = holds
        if wait:
            while self._job is not None:
                next(job)
            return self.job_code
        return OK

    def _steps(self, what, feet, path, discs, steps, arg):
        """A configure's generator: the feet where they stand (feet: UNREACHABLE when one cannot
        stay there), the posture trial (path), the reach discs, the walker's configure (steps),
        then what it changes: what is a gait (arg its cycle), _PARAMS (arg the cycle), _POSE (arg
        the pose) or _HEIGHT (arg the ground to go back to when refused)."""
        w = self.walker
        code = OK
        if feet is not None:
            for _ in feet:
                yield
            code = self._path_code
        if code == OK and path is not None:
            for _ in path:
                yield
            code = self._path_code
        if code == OK and discs is not None:
            for _ in discs:
                yield
        if code == OK and what == _PARAMS and self.mode == WALKING and not self._roomy(self._rho):
            code = UNREACHABLE  # that lift would leave a walking leg no room to step
        if code == OK:
            for _ in steps:
                yield
            code = w.configured
        if code != OK:
            if what == _HEIGHT:
                w.ground = arg
        elif what == _POSE:
            self.body.set_target(arg)
        elif what == _HEIGHT:
            if path is not None:
                self.posture.to_height(w, w.ground)
                self.after = STANDING
                self.mode = MOVING
        elif what == _PARAMS:
            self.cycle_ms = arg
            self.cycles[self.gait] = arg
        else:
            self.gait = what
            self.margin_min = NO_SUPPORT  # this change's margins from here on
            self.cycle_ms = arg
            self.cycles[what] = arg
        self._end(code)
        yield

    def _end(self, code):
        self.job_code = code
        self._job = None
        self._holds = False

    def relax(self):
        """Sit down, then let the servos go limp."""
        if self.mode == RELAXED:
            return OK
        code = self.sit_down()
        if code == OK:
            self.after = RELAXED
        return code

    def set_height(self, height, wait=True):
        """Body height above the ground, 0.1 mm, within the robot file's range; moved gradually
        (wait=False: checked over the next frames, job_code says how it ended)."""
        g = self.geometry
        if not isinstance(height, int) or isinstance(height, bool):
            raise ValueError("height: need a whole number (0.1 mm), got %r" % (height,))
        if height < g.body_height_min or height > g.body_height_max:
            raise ValueError("height: %d is outside %d..%d (0.1 mm)" % (height, g.body_height_min, g.body_height_max))
        code = self._can_move()
        if code != OK:
            return code
        if self._job is not None:
            return CONFIGURING
        w = self.walker
        old = w.ground
        w.set_ground(height)
        feet = path = None
        if self.mode == STANDING:
            feet = self._feet_steps(self.body)
            self._start_feet()
            path = self._path_steps(_HEIGHT)
        discs = self._discs(self.body, w.lift)
        steps = w.configure_steps(self.gait, self.cycle_ms, w.lift, w.step, self._rho, False)
        return self._start(self._steps(_HEIGHT, feet, path, discs, steps, old), True, wait)

    def _feet_steps(self, body):
        """Whether every foot, at the walker's ground height, solves under body's pose, one leg a
        step (a generator; _path_code UNREACHABLE when one does not)."""
        w = self.walker
        leg = self._trial_leg
        self._path_code = OK
        for i in range(6):
            body.to_leg(i, w.fx[i], w.fy[i], w.ground, leg, 0)
            code = self.geometry.legs[i].ik(leg[0], leg[1], leg[2], self._trial_angles, 0)
            yield
            if code != OK:
                self._path_code = UNREACHABLE
                return

    def set_pose(self, x=0, y=0, z=0, roll=0, pitch=0, yaw=0, cx=0, cy=0, cz=0, wait=True):
        """Body pose (0.1 mm, cdeg) about centre (cx, cy, cz); only standing still; moved gradually
        (wait=False: checked over the next frames, job_code says how it ended)."""
        pose = [x, y, z, roll, pitch, yaw, cx, cy, cz]
        self._probe.check_pose(pose)
        if self.mode != STANDING:
            return WALKING_NOW if self.mode == WALKING else (BUSY if self.mode == MOVING else NOT_STANDING)
        if self._job is not None:
            return CONFIGURING
        probe = self._probe
        probe.set_target(pose)
        probe.jump()
        w = self.walker
        discs = self._discs(probe, w.lift)
        steps = w.configure_steps(self.gait, self.cycle_ms, w.lift, w.step, self._rho, False)
        return self._start(self._steps(_POSE, self._feet_steps(probe), None, discs, steps, pose), True, wait)

    def set_gait(self, gait, cycle_ms=None, wait=True):
        """Switch gait (gait.TRIPOD ...) at cycle_ms (ms), else at the gait's own cycle time: now
        when stopped; while walking, without stopping (hexapod.walk.Walker._phase_in): the steps
        are first brought inside the new gait's stance discs where they are not, then at a moment
        with every foot down the new gait starts at the slot that suits the feet, slower until each
        leg has lifted once where needed (less than one cycle). margin, margin_min report the
        static stability meanwhile. wait=False: checked over the next frames while the robot
        walks on in its gait, job_code says how it ended."""
        check_gait(gait)
        if cycle_ms is not None:
            check_cycle_ms(cycle_ms)
        if self._job is not None:
            return CONFIGURING
        w = self.walker
        cycle = self.cycles[gait] if cycle_ms is None else cycle_ms
        steps = w.configure_steps(gait, cycle, w.next_lift, w.step, w.next_rho)
        return self._start(self._steps(gait, None, None, None, steps, cycle), False, wait)

    def set_params(self, step_length=None, lift_height=None, cycle_ms=None, wait=True):
        """Step length and lift height (0.1 mm), the present gait's cycle time (ms); each bounded
        (ValueError). wait=False: checked over the next frames, job_code says how it ended."""
        w = self.walker
        step = w.step if step_length is None else step_length
        lift = w.next_lift if lift_height is None else lift_height
        cycle = self.cycle_ms if cycle_ms is None else cycle_ms
        w.check_step(step)
        w.check_lift(lift)
        check_cycle_ms(cycle)
        if self._job is not None:
            return CONFIGURING
        self._probe.set_target(self.body.target)
        self._probe.jump()
        discs = self._discs(self._probe, lift)
        steps = w.configure_steps(self.gait, cycle, lift, step, self._rho)
        return self._start(self._steps(_PARAMS, None, None, discs, steps, cycle), False, wait)

    def walk(self, vx, vy, yaw_rate):
        """Walk at vx, vy (0.1 mm/s) turning at yaw_rate (cdeg/s); scaled down to what reach allows
        (and to the speed cap, cap_speed)."""
        self.walker.check_command(vx, vy, yaw_rate)
        if self.mode != STANDING and self.mode != WALKING:
            return BUSY if self.mode == MOVING else NOT_STANDING
        if self._holds:
            return CONFIGURING  # a pose or height is being checked: the robot stands still till then
        if not _settled(self.body):
            return BUSY
        if vx or vy or yaw_rate:
            w = self.walker
            code = self._room(w.rho, w.srho)
            if code:
                return code
        self.asked_vx = vx
        self.asked_vy = vy
        self.asked_yaw = yaw_rate
        self._command()
        if self.walker.state != STOPPED:
            self.mode = WALKING
        return OK

    def _command(self):
        """The walker's command: the one asked, scaled by one factor (the path keeps its
        curvature) until the planar speed is at most speed_cap and the yaw rate yaw_cap."""
        vx = self.asked_vx
        vy = self.asked_vy
        w = self.asked_yaw
        if self.speed_cap:
            k = 1000
            v = isqrt(vx * vx + vy * vy)  # < 4243 (|vx|, |vy| <= 3000): small integers
            if v > self.speed_cap:
                k = self.speed_cap * 1000 // v
            a = w if w >= 0 else -w
            if a > self.yaw_cap and self.yaw_cap * 1000 // a < k:
                k = self.yaw_cap * 1000 // a
            vx = vx * k // 1000 if vx >= 0 else -(-vx * k // 1000)  # toward 0: never above the cap
            vy = vy * k // 1000 if vy >= 0 else -(-vy * k // 1000)
            w = w * k // 1000 if w >= 0 else -(-w * k // 1000)
        self.walker.command(vx, vy, w, True)

    def cap_speed(self, speed=0, yaw_rate=0):
        """Cap walking at speed (0.1 mm/s, planar) and yaw_rate (cdeg/s), both > 0; cap_speed()
        lifts the cap. A walk under way is re-commanded at once (the walker ramps to it)."""
        for name, v, top in (("speed", speed, SPEED_MAX), ("yaw_rate", yaw_rate, YAW_RATE_MAX)):
            if not isinstance(v, int) or isinstance(v, bool) or v < 0 or v > top:
                raise ValueError("%s: %r, allowed 0..%d (0: no cap)" % (name, v, top))
        if (speed == 0) != (yaw_rate == 0):
            raise ValueError("speed %r, yaw_rate %r: cap both or neither (0, 0)" % (speed, yaw_rate))
        self.speed_cap = speed
        self.yaw_cap = yaw_rate
        if self.mode == WALKING and self.walker.state != STOPPED:
            self._command()

    def _room(self, rho, srho):
        """OK when every leg has room to step, else UNREACHABLE (this pose or lift leaves a leg no
        room) or SERVO_SPEED (this pose or height makes the swing too fast for the servos)."""
        for i in range(6):  # (one loop for both: walk() runs at each command)
            if rho[i] < _RHO_MIN or srho[i] < _RHO_MIN:
                return SERVO_SPEED if self._roomy(rho) else UNREACHABLE
        return OK

    def _roomy(self, rho):
        for i in range(6):  # noqa: SIM110 (walk() runs every tick: no generator)
            if rho[i] < _RHO_MIN:
                return False
        return True

    def walk_heading(self, length, heading, yaw_rate=0):
        """Seed 003's form: step length (0.1 mm) along heading (cdeg): x = L cos, y = L sin."""
        if not isinstance(length, int) or isinstance(length, bool) or length < 0 or length > STEP_MAX:
            raise ValueError("length: %r is outside 0..%d (0.1 mm)" % (length, STEP_MAX))
        if not isinstance(heading, int) or isinstance(heading, bool) or heading < -18000 or heading > 18000:
            raise ValueError("heading: %r is outside -18000..18000 (cdeg)" % (heading,))
        half_ms = self.walker.clock.stance_ticks * TICK_MS >> 1
        # Half a stance moves the body by the step: v = step / (half a stance), here x16.
        v16 = length * 16000 // half_ms
        vx = (mul_q15(v16, cos(heading)) + 8) >> 4
        vy = (mul_q15(v16, sin(heading)) + 8) >> 4
        return self.walk(vx, vy, yaw_rate)

    def walk_sweeps(self, left, right):
        """Seed 000's turn: the command that swings the left and right middle coxas by
        `left` and `right` cdeg per stance (right turn: 4500, 1000); then walk()."""
        sweep_command(self.walker, left, right, self._leg)
        return self.walk(self._leg[0], 0, self._leg[1])

    def stop(self):
        """Finish the steps under way and set every foot down at neutral."""
        self.asked_vx = self.asked_vy = self.asked_yaw = 0
        if self.mode == WALKING:
            self.walker.stop()
        return OK

    # -- jogging and calibration (the console's single-servo moves) ---------------------

    def _servo_refused(self, k, code, excess):
        self.jog_servo = k
        self.jog_code = code
        self.jog_excess = excess
        return JOG_SERVO

    def jog_foot(self, leg, x, y, z):
        """Leg `leg` (0..5)'s foot to (x, y, z), 0.1 mm in its leg frame (mode JOG): hexapod.jog.foot."""
        import hexapod.jog  # (not `from hexapod import jog`: that allocates 32 B a call)

        return hexapod.jog.foot(self, leg, x, y, z)

    def jog_joint(self, leg, joint, cdeg):
        """One servo (leg 0..5, joint 0 coxa 1 femur 2 tibia) to cdeg (mode JOG): hexapod.jog.joint."""
        import hexapod.jog  # (not `from hexapod import jog`: that allocates 32 B a call)

        return hexapod.jog.joint(self, leg, joint, cdeg)

    def jog_pulse(self, leg, joint, pulse_us):
        """One servo to a raw pulse width, us (mode JOG): hexapod.jog.pulse."""
        import hexapod.jog  # (not `from hexapod import jog`: that allocates 32 B a call)

        return hexapod.jog.pulse(self, leg, joint, pulse_us)

    def calibrate(self, k, centre_us, direction, min_us, max_us):
        """Servo k (0..17)'s map (here, not in hexapod.jog: the boot puts a calibration file's rows
        in force with it, a row a call, where that module's import would take a frame): centre_us
        (the pulse at its reference angle, ServoMap.ref_cdeg; 500..2500), direction 1/-1 (mirrored
        about the reference) and min_us < max_us within 500..2500 (ValueError naming the bad one).
        Refused (WALKING_NOW, BUSY, or JOG_SERVO with
        jog_excess) when the servo is driven and its present angle would map outside the new
        range; otherwise the driven servo moves to its new pulse at once: the frame in force goes
        out again now with that one pulse changed, so no chip is left driving the old pulse
        (outside the new range) until a later frame, which may be held."""
        if not isinstance(k, int) or isinstance(k, bool) or k < 0 or k > 17:
            raise ValueError("servo: %r, allowed 0..17" % (k,))
        for name, v in (("centre_us", centre_us), ("min_us", min_us), ("max_us", max_us)):
            if not isinstance(v, int) or isinstance(v, bool) or v < 500 or v > 2500:
                raise ValueError("%s: %r is outside 500..2500 us" % (name, v))
        if min_us >= max_us:
            raise ValueError("range: min_us %d must be below max_us %d" % (min_us, max_us))
        if direction != 1 and direction != -1:
            raise ValueError("direction: %r, allowed 1 or -1" % (direction,))
        code = self._can_move()
        if code != OK:
            return code
        s = self.servos[k]
        p = 0
        if self.pulses[k]:
            p = s.raw_at(self.angles[k], centre_us, direction)
            if p < min_us:
                return self._servo_refused(k, 1, min_us - p)
            if p > max_us:
                return self._servo_refused(k, 2, p - max_us)
        s.direction = direction
        s.centre_us = centre_us
        s.min_us = min_us
        s.max_us = max_us
        if p:
            self.pulses[k] = p
            self.frame.write_frame(self.pulses)
        return OK

    def go_limp(self):
        """At once: every servo limp (a frame of zeros sent now), mode RELAXED; the loop is leaving."""
        self.asked_vx = self.asked_vy = self.asked_yaw = 0
        self.walker.stop()
        self.walker.state = STOPPED
        self.mode = RELAXED
        p = self.pulses
        for k in range(18):
            p[k] = 0
        self.frame.write_frame(p)
