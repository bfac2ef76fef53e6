"""The walk: velocity commands -> six body-frame feet per tick, through a gait and a state machine.

Units: vx, vy in 0.1 mm/s (body frame: x forward, y left), yaw rate in cdeg/s (positive
turns left, counter-clockwise from above); step length and lift height in 0.1 mm; feet
in body.FINE units (0.1 mm << 4). One update() is one 20 ms tick and allocates nothing.

Stance feet stay fixed on the ground: the walker integrates the body's planar motion
(exactly, with remainder carries) in a ground frame and reads each stance foot back into
the body frame, so a foot moves back in a straight line (an arc when turning) at constant
speed. A swing lifts the foot from where it left the ground to its touch-down target along
trajectory.swing_shape (seed 003 eq. 12-14 with a smooth touch-down); the target is where
the foot must land to pass its neutral point at mid-stance (re-aimed every tick; after a
command change the foot strays at most REPLAN_STEP a tick from the new plan's own move).

Reach: every foot lives in a disc of radius rho[i] around its neutral point, found by leg
IK (hexapod.reach) at ground and lift height. Commands are scaled down so half a
stance stays inside the smaller of rho and the step length; a swing target is clamped to
the disc, and a tick that would push a stance foot out of it, or out of the band of
distances from its coxa where its next swing keeps its whole servo budget (hexapod.budget),
holds the body still instead. So the planner never asks for a foot the leg cannot reach.

States: STOPPED (feet at neutral), STARTING (ramping up from a stop), WALKING, STOPPING
(the command is zero: every leg finishes its step and lands at neutral, then STOPPED).
Gait, cycle time and lift height changes asked for while walking: hexapod.gaitswitch.
"""

import sys
from array import array

from micropython import const

from hexapod import gaitswitch
from hexapod.body import FINE, FINE_SHIFT, Body
from hexapod.budget import gain_steps, in_budget, off_band, swing_budget
from hexapod.fixmath import ONE, cos, isqrt, mul_q15, sin
from hexapod.gait import TICK_MS, TRIPOD, GaitClock, actual_cycle_ms, check_cycle_ms, check_gait, swing_stance_ticks
from hexapod.limits import (  # largest |vx|, |vy| (0.1 mm/s) and |yaw rate| (cdeg/s) accepted
    SPEED_MAX,
    YAW_RATE_MAX,
    is_whole,
)
from hexapod.reach import servo_steps, table_servo
from hexapod.trajectory import swing_shape, swing_stroke

# The viper twins (docs/viper.md): the tick's walker steps compiled by the viper emitter where
# MicroPython has one (hexapod/_walk_viper.py, proven equal to _ramp and _lift_all, _move_body,
# _aim_swings, _swings and _rescale by tests/test_tick_viper.py and tests/test_rescale.py), and
# fixmath's sine as machine code (hexapod/_fixmath_viper.py, tests/test_rescale.py): a new
# command's aims are four sines. CPython and CircuitPython run the plain code.
_swings_fast = _move_fast = _begin_fast = _aim_fast = _rescale_fast = None
if sys.implementation.name == "micropython":
    try:
        from hexapod._fixmath_viper import sin  # noqa: F811
        from hexapod._walk_viper import aim as _aim_fast
        from hexapod._walk_viper import begin as _begin_fast
        from hexapod._walk_viper import move as _move_fast
        from hexapod._walk_viper import rescale as _rescale_fast
        from hexapod._walk_viper import swings as _swings_fast
    except Exception:  # no viper emitter on this build
        _swings_fast = _move_fast = _begin_fast = _aim_fast = _rescale_fast = None

STOPPED = const(0)
STARTING = const(1)
WALKING = const(2)
STOPPING = const(3)
STATE_NAMES = ("stopped", "starting", "walking", "stopping")
OK = const(0)
SERVO_SPEED = const(28)  # configure: even a step of nothing would turn a joint too fast
LIFT_SHARE_PERMILLE = const(900)  # most of the servo budget a swing without a step may use

_STEP_MIN = const(50)  # step length (half a stride: seed 003's x amplitude), 0.1 mm
STEP_MAX = const(600)
_LIFT_MIN = const(100)  # lift height, 0.1 mm
_LIFT_MAX = const(600)
SPEED_STEP = const(40)  # most vx or vy changes per tick, 0.1 mm/s (200 mm/s^2)
YAW_STEP = const(100)  # most the yaw rate changes per tick, cdeg/s
_HALF_TURN = const(9000)  # half a stance never turns more than this, cdeg
_DEG360 = const(3600000)  # in fixmath.ANGLE_UNIT
STANCE_SLACK = const(16)  # a stance foot may end this far past the scaled step (rounding), 0.1 mm
REPLAN_STEP = const(64)  # most a re-aimed swing foot strays from its plan's move a tick, per axis, fine (0.4 mm)
_REANCHOR = const(4194304)  # ground-frame fine units before the origin is moved to the body


class Walker:
    """Gait engine and walk state machine for one Geometry (feet in the body frame)."""

    def __init__(self, geometry):
        # The per-leg state and the tick's small vectors are array("i"): hexapod/_walk_viper.py reads
        # and writes them as machine words (ptr32); the plain code indexes them as lists.
        self.geometry = geometry
        self.clock = GaitClock(TRIPOD, 1000)
        self.step = 300
        self.lift = 300
        self.ground = -geometry.body_height << FINE_SHIFT  # foot z on the ground, fine
        self.nx = _words(6)  # neutral feet, body frame, fine
        self.ny = _words(6)
        self.rho = _words(6)  # reach disc radius around each neutral foot, 0.1 mm
        self.srho = [STEP_MAX] * 6  # largest half stance the servos' speed allows, 0.1 mm
        self.next_srho = [STEP_MAX] * 6
        # The step the command is scaled to (reach, step, servo speed) + STANCE_SLACK, 0.1 mm: where a
        # gait change plans its slow-down (hexapod.gaitswitch). The stance hold itself is at the reach
        # disc and the ease band (hexapod.budget.off_band; docs/physics.md, issue 22).
        self.stance_rho = _words(6)
        # The swing's servo budget (planner): each leg's largest "swing speed" |C + D g| (0.1 mm), C
        # the ground's move under the foot over one swing, D the stroke T - S - C, g stroke_gain: the
        # steady swing the guard passed (half a stance srho) at its peak tick. A swing whose lift-off
        # is further out than a steady one lands short instead of turning a joint too fast.
        self.swing_max = _words(6)
        # The stance hold's ease band (budget.swing_budget, off_band), then the command (cmd) at each
        # leg's last lift-off, vx a leg, then vy, yaw (budget.turned). One array: a new attribute on the
        # walker made every tick ~21 us slower on the emulated Pico (its attribute lookups; measured).
        self.band = _words(42)
        self.stroke_gain = 0  # w x the stroke's largest fraction in one tick, Q15
        self.servo_peak = 0  # largest joint change (cdeg/tick) of a swing without a step, last configure
        self.configured = OK  # the last configure's code (configure_steps leaves it here)
        self._caps = [0] * 6  # the servo guard's scratch: how far it looks, its radii and peak
        self._srho = [0] * 6
        self._peak = [0]
        self.guard_buf = [0] * 9  # reach.disc_steps' and servo_steps' scratch (a foot, two ticks' angles)
        self.guard_tmp = [0, 0]
        self.table = None  # the robot file's guard table (hexapod.reach.find_table), set by the Robot
        self.pose_body = None  # the Body whose pose the servo-speed check uses (else level)
        self.fx = _words(6)  # current feet, body frame, fine
        self.fy = _words(6)
        self.fz = _words(6)
        self.px = _words(6)  # stance feet in the ground frame, fine
        self.py = _words(6)
        self.sx = _words(6)  # where each swing left the ground, body frame, fine
        self.sy = _words(6)
        self.su = _words(6, -1)  # ticks into the swing, -1 in stance
        self.done = _words(6)  # STOPPING: leg has landed at neutral since the command hit zero
        self.ax = _words(6)  # this tick's stance feet, before the reach check
        self.ay = _words(6)
        self.bx = 0  # body in the ground frame, fine, plus remainder carries
        self.by = 0
        self.cx = 0
        self.cy = 0
        self.psi = 0  # body heading in the ground frame, fixmath.ANGLE_UNIT
        self.req_vx = 0  # the command as asked, before scaling
        self.req_vy = 0
        self.req_yaw = 0
        self.cmd = _words(3)  # scaled target (vx, vy, yaw rate)
        self.vel = _words(3)  # ramped velocity actually walked
        self.scale_permille = 1000  # how much of the last command the reach allowed
        self.state = STOPPED
        self.phase = 0
        self.held = 0  # ticks the body was held still to keep a stance foot in reach
        self.pending = 0  # 1 while a gait/cycle/lift change waits for all feet down, then its parts (gaitswitch)
        gaitswitch.init(self)  # goal (the ramp's target), slow, settling, fitting and scratch
        self.next_gait = TRIPOD
        self.next_cycle_ms = 1000
        self.next_lift = 300
        self.next_rho = [0] * 6
        self.next_gain = 0  # budget.gain_steps' for the pending change's swing, made by its configure job
        self._shape = [0, 0]
        self._stroke = [0, 0]  # swing_stroke's (stroke, carry) fractions
        self._plan = [0, 0]  # where the swing's plan puts a foot, fine
        # The stance's ground motion over one swing at the command: x, y shift (fine), turn (Q15 rad).
        self._carry = _words(3)
        self._cv = [0, 0, 0, 0]  # this swing's carries at lift-off (x, y) and touch-down (x, y), fine
        self._aim = _words(6)  # cos, sin of half the stance turn, half-stance shift x, y
        self._aim_key = array("i", [0, 0, 0, -1])  # the (vx, vy, w, stance ticks) _aim was made for
        self._xy = _words(2)
        for i in range(6):
            geometry.neutral_xy(i, self._xy)
            self.nx[i] = self._xy[0] << FINE_SHIFT
            self.ny[i] = self._xy[1] << FINE_SHIFT
        self.feet_to_neutral()
        swing_budget(self)

    # -- settings (off the tick) -------------------------------------------------------

    def feet_to_neutral(self):
        """Put the planned feet at the neutral stance on the ground (no motion is made)."""
        for i in range(6):
            self.fx[i] = self.nx[i]
            self.fy[i] = self.ny[i]
            self.fz[i] = self.ground
            self.su[i] = -1

    def set_ground(self, height):
        """Body height above the ground, 0.1 mm (the caller moves the feet there)."""
        self.ground = -height << FINE_SHIFT

    def check_step(self, step):
        if not isinstance(step, int) or isinstance(step, bool) or step < _STEP_MIN or step > STEP_MAX:
            raise ValueError("step_length: %r is outside %d..%d (0.1 mm, half a stride)" % (step, _STEP_MIN, STEP_MAX))

    def check_lift(self, lift):
        if not isinstance(lift, int) or isinstance(lift, bool) or lift < _LIFT_MIN or lift > _LIFT_MAX:
            raise ValueError("lift_height: %r is outside %d..%d (0.1 mm)" % (lift, _LIFT_MIN, _LIFT_MAX))

    def configure(self, gait, cycle_ms, lift, step, rho, strict=True):
        """Gait, cycle time (ms), lift and step (0.1 mm) with their reach discs; checked, then
        taken now when stopped, else at the next moment with every foot on the ground.

        Returns OK, or SERVO_SPEED (and changes nothing) when the robot file's servos could
        not lift and lower a foot in this gait's swing at this cycle time and lift within 90 %
        of their budget (geometry.servo_step). Not strict (a new pose or height): taken all
        the same with no room to step (srho 0), so that walking is refused until it changes."""
        for _ in self.configure_steps(gait, cycle_ms, lift, step, rho, strict):
            pass
        return self.configured

    def configure_steps(self, gait, cycle_ms, lift, step, rho, strict=True):
        """configure one IK solve at a time: the settings are checked now (ValueError), then a
        generator that yields after each of the servo guard's solves (reach.servo_steps) and
        takes the settings when exhausted, leaving configure's code in `configured`. rho is
        read when the guard starts (a caller may fill it first), the pose (pose_body) now."""
        check_gait(gait)
        check_cycle_ms(cycle_ms)
        self.check_lift(lift)
        self.check_step(step)
        guard = None
        limit = self.geometry.servo_step
        ticks = swing_stance_ticks(gait, cycle_ms, [0, 0])
        if limit:
            body = self.pose_body if self.pose_body is not None else Body(self.geometry)
            guard = servo_steps(self, body, ticks[0], ticks[1], lift, limit, self._caps, self._srho, self._peak)
        # (made here, with its scratch: a job's ticks after its first allocate nothing)
        gain = gain_steps(self, ticks[0], ticks)
        return self._configure(guard, gain, gait, cycle_ms, lift, step, rho, strict)

    def _configure(self, guard, gain, gait, cycle_ms, lift, step, rho, strict):
        # The guard's answer and the stroke gain from the robot file's table (hexapod.reach.table_servo),
        # else the guard's solves and the gain's steps.
        t = self.table
        if guard is None or t is None or not table_servo(t, self, gait, cycle_ms, lift, step, rho):
            if guard is not None:
                # No need to look past what the reach and the step allow already.
                for i in range(6):
                    self._caps[i] = rho[i] if rho[i] < step else step
                for _ in guard:
                    yield
            for _ in gain:
                yield
        self.configured = self.take(gait, cycle_ms, lift, step, rho, strict, guard is not None)

    def take(self, gait, cycle_ms, lift, step, rho, strict, guarded):
        """configure's last part, with the servo guard's radii and peak (guarded) in _srho, _peak."""
        if guarded:
            limit = self.geometry.servo_step
            peak = self._peak[0]
            self.servo_peak = peak
            # The lift alone may use 90 % of the budget: shorter swings accelerate the joints
            # harder than the servos follow within 80 % of stall (docs/physics.md).
            over = peak > limit * LIFT_SHARE_PERMILLE // 1000
            if over and strict:
                return SERVO_SPEED
            for i in range(6):
                self.next_srho[i] = 0 if over else self._srho[i]
        self.step = step
        self.next_gait = gait
        self.next_cycle_ms = cycle_ms
        self.next_lift = lift
        for i in range(6):
            self.next_rho[i] = rho[i]
        same = gait == self.clock.gait and self.clock.cycle_ms == actual_cycle_ms(gait, cycle_ms) and lift == self.lift
        for i in range(6):
            if rho[i] != self.rho[i] or self.next_srho[i] != self.srho[i]:
                same = False
        if self.state == STOPPED:
            self._apply()
        elif same:
            # Nothing the feet would notice: no need to wait (step applies now); a change already
            # taken still phases in (gaitswitch.after_tick).
            if self.pending < gaitswitch.ROOMS:
                self.pending = 0
            self.fitting = 0
            self._rescale()
        else:
            gaitswitch.begin(self)
        return OK

    def _apply(self):
        gaitswitch.reset(self)
        self.clock.set(self.next_gait, self.next_cycle_ms)
        self.lift = self.next_lift
        for i in range(6):
            self.rho[i] = self.next_rho[i]
            self.srho[i] = self.next_srho[i]
        self.phase = 0
        self.stroke_gain = self.next_gain
        self._rescale()
        if self.state == STOPPED:
            self.pending = 0
            swing_budget(self, self.stroke_gain)
        else:
            # On the move the swing budget, the rooms and the phase come over the next two ticks
            # (gaitswitch.after_tick), no foot lifting meanwhile.
            self.pending = gaitswitch.ROOMS

    # -- commands ----------------------------------------------------------------------

    def check_command(self, vx, vy, yaw_rate):
        """ValueError naming the first of vx, vy (0.1 mm/s), yaw_rate (cdeg/s) out of range."""
        # Written out (no loop over a tuple, is_whole inlined) so that a valid command allocates
        # nothing and costs few calls; `type(v) is int` (not a bool) and the limits in locals: 206 ->
        # ~100 us a command on the emulated Pico.
        top = SPEED_MAX
        if type(vx) is not int or vx < -top or vx > top:
            _bad("vx", vx, top, "0.1 mm/s")
        if type(vy) is not int or vy < -top or vy > top:
            _bad("vy", vy, top, "0.1 mm/s")
        top = YAW_RATE_MAX
        if type(yaw_rate) is not int or yaw_rate < -top or yaw_rate > top:
            _bad("yaw_rate", yaw_rate, top, "cdeg/s")

    def command(self, vx, vy, yaw_rate, checked=False):
        """Walk at (vx, vy, yaw rate), scaled down to what the reach and step length allow
        (checked: the caller has just passed them through check_command)."""
        if not checked:
            self.check_command(vx, vy, yaw_rate)
        self.req_vx = vx
        self.req_vy = vy
        self.req_yaw = yaw_rate
        gaitswitch.scale(self)
        moving = self.cmd[0] or self.cmd[1] or self.cmd[2]
        if moving:
            if self.state == STOPPED:
                self._start()
            elif self.state == STOPPING:
                self.state = WALKING
        elif self.state == STARTING or self.state == WALKING:
            self._stopping()

    def stop(self):
        """Zero the command: finish the steps and land every foot at neutral."""
        self.command(0, 0, 0)

    def _start(self):
        self.state = STARTING
        self.bx = self.by = self.cx = self.cy = self.psi = 0
        for i in range(6):
            self.px[i] = self.fx[i]
            self.py[i] = self.fy[i]
            self.su[i] = -1

    def _stopping(self):
        self.state = STOPPING
        for i in range(6):
            self.done[i] = 0

    def _rescale(self):
        # The command is scaled by k/1000 until every leg's half stance (its touch-down point's
        # distance from neutral) fits its disc and, on three feet, no stance foot reaches too far
        # out; each try sets the next k from the worst shortfall. One function on purpose: calls
        # are costly on a board, and a root is taken only for a foot that is over (compared as
        # squares: isqrt(d2) > lim when d2 > lim * (lim + 2)). hexapod/_walk_viper.py's rescale is the
        # same in viper; tests/test_rescale.py proves both equal to the plain one-helper-per-leg
        # form on many random commands and reach discs.
        if _rescale_fast is not None:
            _rescale_fast(self)
            gaitswitch.goal(self)
            return
        vx = self.req_vx
        vy = self.req_vy
        w = self.req_yaw
        clock = self.clock
        half_ms = clock.stance_ticks * TICK_MS >> 1
        # Half a stance may not turn past 90 degrees (the disc test needs a monotone turn).
        turn = w * half_ms // 1000
        k = 1000
        if turn > _HALF_TURN or turn < -_HALF_TURN:
            k = _HALF_TURN * 1000 // (turn if turn > 0 else -turn)
        g = self.geometry
        # On three feet (a tripod), a foot far out loads its femur (a longer lever): the excess
        # over stance_out_max from the coxa axis scales the command back too.
        out_max = g.stance_out_max if clock.stance_ticks * 2 <= clock.cycle_ticks else 0
        reach = g.neutral_reach
        far = (out_max + reach + 1) * (out_max + reach + 1)
        nx = self.nx
        ny = self.ny
        mx = g.mount_x
        my = g.mount_y
        rho = self.rho
        srho = self.srho
        step = self.step
        lims = self.stance_rho  # first each leg's limit on a half stance, at the end its stance disc
        for i in range(6):
            lim = rho[i] if rho[i] < step else step
            if srho[i] < lim:
                lim = srho[i]  # the servos' speed: a longer step needs a faster swing
            lims[i] = lim
        a = self._aim
        xy = self._xy  # scratch: left as the plain form leaves it (the last leg's touch-down point)
        tx = xy[0]
        ty = xy[1]
        while k > 0:
            self.aim_for(vx * k // 1000, vy * k // 1000, w * k // 1000)
            c = a[0]
            s = a[1]
            ox = a[2]
            oy = a[3]
            worst = -1
            for i in range(6):
                # target(i): the touch-down point, fine (mul_q15 written out; one product for a
                # factor below 2**15, the feet of any robot within 204 mm of the body's centre)
                x = nx[i]
                m = x if x >= 0 else -x
                if m < 32768:
                    xc = (m * c + 16384) >> 15
                    xs = (m * s + 16384) >> 15
                else:
                    xc = (m >> 15) * c + (((m & 32767) * c + 16384) >> 15)
                    xs = (m >> 15) * s + (((m & 32767) * s + 16384) >> 15)
                if x < 0:
                    xc = -xc
                    xs = -xs
                y = ny[i]
                m = y if y >= 0 else -y
                if m < 32768:
                    yc = (m * c + 16384) >> 15
                    ys = (m * s + 16384) >> 15
                else:
                    yc = (m >> 15) * c + (((m & 32767) * c + 16384) >> 15)
                    ys = (m >> 15) * s + (((m & 32767) * s + 16384) >> 15)
                if y < 0:
                    yc = -yc
                    ys = -ys
                tx = xc - ys + ox
                ty = xs + yc + oy
                m = (tx - x) >> FINE_SHIFT
                d2 = m * m
                m = (ty - y) >> FINE_SHIFT
                d2 += m * m
                lim = lims[i]
                if lim < 0 or d2 > lim * (lim + 2):
                    # The shortfall sets the next try; rounding can leave it a hair short.
                    m = k * lim // isqrt(d2)
                    if worst < 0 or m < worst:
                        worst = m
                if out_max > 0:
                    # The touch-down point or its mirror through neutral (lift-off), from the coxa axis.
                    x = (x >> FINE_SHIFT << 1) - mx[i]
                    y = (y >> FINE_SHIFT << 1) - my[i]
                    xc = (tx >> FINE_SHIFT) - mx[i]
                    yc = (ty >> FINE_SHIFT) - my[i]
                    d2 = xc * xc + yc * yc
                    xc = x - xc - mx[i]
                    yc = y - yc - my[i]
                    if xc * xc + yc * yc > d2:
                        d2 = xc * xc + yc * yc
                    if d2 >= far:
                        m = k * out_max // (isqrt(d2) - reach)
                        if worst < 0 or m < worst:
                            worst = m
            if worst < 0:
                break
            k = worst - 1 if worst >= k else worst
        xy[0] = tx
        xy[1] = ty
        if k < 0:
            k = 0
        gaitswitch.stance_discs(self, lims)
        self.scale_permille = k
        self.cmd[0] = vx * k // 1000
        self.cmd[1] = vy * k // 1000
        self.cmd[2] = w * k // 1000
        gaitswitch.goal(self)

    def aim_for(self, vx, vy, w):
        """Half a stance of body motion at (vx, vy, w): the turn and the shift, into _aim."""
        # The tick asks for the same command each frame: _aim is made again only when it changes.
        # (Small on purpose: a MicroPython bytecode function of more than 11 locals + stack slots
        # takes its frame from the heap on every call; the same holds for the helpers below.)
        key = self._aim_key
        st = self.clock.stance_ticks
        if key[0] != vx or key[1] != vy or key[2] != w or key[3] != st:
            key[0] = vx
            key[1] = vy
            key[2] = w
            key[3] = st
            self._aim_at(vx, vy, w)

    def _aim_at(self, vx, vy, w):
        # Few names on purpose (h: half a stance, ms; t: its turn, cdeg; then the cosine and sine
        # of half the turn): within 11 locals + stack slots the frame stays off the heap.
        h = self.clock.stance_ticks * TICK_MS >> 1
        t = w * h // 1000
        a = self._aim
        # The shift is the chord of the arc: the straight move turned by half the turn.
        vx = vx * h * FINE // 1000
        vy = vy * h * FINE // 1000
        if t == 0:  # no turn: sin(9000) is ONE and sin(0) 0, the same values without four sines
            a[0] = ONE
            a[1] = 0
            a[2] = mul_q15(vx, ONE)
            a[3] = mul_q15(vy, ONE)
            return
        a[0] = sin(t + 9000)  # cos(t)
        a[1] = sin(t)
        h = sin((t >> 1) + 9000)
        t = sin(t >> 1)
        a[2] = mul_q15(vx, h) - mul_q15(vy, t)
        a[3] = mul_q15(vx, t) + mul_q15(vy, h)

    def target(self, i, out):
        """Leg i's touch-down point (body frame, fine) for the motion in _aim, into out[0:2]."""
        a = self._aim
        nx = self.nx[i]
        ny = self.ny[i]
        out[0] = mul_q15(nx, a[0]) - mul_q15(ny, a[1]) + a[2]
        out[1] = mul_q15(nx, a[1]) + mul_q15(ny, a[0]) + a[3]
        return out

    def _carry_for(self, vx, vy, w, ticks):
        """How the ground moves under the body in `ticks` ticks at (vx, vy, w): into _carry."""
        ms = ticks * TICK_MS
        k = self._carry
        k[0] = -(vx * ms * FINE // 1000)
        k[1] = -(vy * ms * FINE // 1000)
        # The turn in Q15 radians: cdeg * pi / 18000 * 2**15 = cdeg * 5.71935.
        k[2] = (w * ms // 1000) * 5719 // 1000

    def carry_at(self, x, y, out, j):
        """The ground's move (fine) under body point (x, y) (fine) over one swing, into out[j:j+2]."""
        k = self._carry
        # A turn w moves a ground point at p by -w x p = (w y, -w x); p in 0.1 mm keeps it small.
        out[j] = k[0] + (((y >> FINE_SHIFT) * k[2]) >> 11)
        out[j + 1] = k[1] - (((x >> FINE_SHIFT) * k[2]) >> 11)
        return out

    # -- the tick ----------------------------------------------------------------------

    def update(self):
        """Advance one tick: ramp the velocity, move the body, move the swings, step the clock."""
        if self.state == STOPPED:
            return self.state
        if _begin_fast is None:
            self._ramp()
            due = -1
        else:
            due = _begin_fast(self)  # the ramp; 1 when still, 2 << i for each leg due to lift
        v = self.vel
        g = self.goal
        if self.state == STARTING and v[0] == g[0] and v[1] == g[1] and v[2] == g[2]:
            self.state = WALKING
        still = not (v[0] or v[1] or v[2])
        # Lift first: a foot leaving the ground this tick is not carried by the body's move,
        # so every stance lasts exactly stance_ticks moves (what the touch-down aim assumes).
        if due < 0:
            self._lift_all(still)
            self._move_body()
            self._aim_swings()
        else:
            if due > 1:
                self._lift_due(due, still)
            _move_fast(self)
            _aim_fast(self)
        airborne = self._swing_all(still)
        self.phase += 1
        if self.phase >= self.clock.cycle_ticks:
            self.phase = 0
        if self.settling or self.pending:
            gaitswitch.after_tick(self, airborne)
        if self.state == STOPPING and still and not airborne:
            for i in range(6):
                if not self.done[i]:
                    return self.state
            self.state = STOPPED
            self.phase = 0
            if self.pending >= gaitswitch.ROOMS:
                # Taken: stopped, it starts at phase 0 as a change taken standing, with its budget.
                self.pending = 0
                swing_budget(self, self.stroke_gain)
        return self.state

    def _lift_all(self, still):
        # clock.swing_tick(i, phase) == 0, written out: phase and every start lie in 0..cycle-1.
        su = self.su
        start = self.clock.start
        phase = self.phase
        for i in range(6):
            if su[i] < 0 and phase == start[i]:
                self._maybe_lift(i, still)

    def _lift_due(self, due, still):
        for i in range(6):
            if due >> (i + 1) & 1:
                self._maybe_lift(i, still)

    def _aim_swings(self):
        # Swings aim for the commanded velocity, not the ramp's: the feet land ready for it.
        c = self.cmd
        self.aim_for(c[0], c[1], c[2])
        self._carry_for(c[0], c[1], c[2], self.clock.swing_ticks)

    def _swing_all(self, still):
        """Move every swing foot one tick; returns how many are still in the air."""
        w = self.clock.swing_ticks
        if _swings_fast is not None:
            return _swings_fast(self, 0, 6, w, still)
        return self._swings(0, 6, w, still)

    def _swings(self, lo, hi, w, still):
        """_swing_all's plain code over legs lo..hi-1 (hexapod/_walk_viper.py's swings is the same in viper)."""
        su = self.su
        airborne = 0
        for i in range(lo, hi):
            if su[i] >= 0:
                self._swing(i, w, still)
                if su[i] >= 0:
                    airborne += 1
        return airborne

    def _ramp(self):
        c = self.goal
        v = self.vel
        for k in range(3):
            step = YAW_STEP if k == 2 else SPEED_STEP
            d = c[k] - v[k]
            if d > step:
                d = step
            elif d < -step:
                d = -step
            v[k] += d

    def _maybe_lift(self, i, still):
        if still < 0:
            # The body holds this tick for leg i's stance foot (_move_body and its viper twin): counted,
            # and the foot lifts now, before its turn, when the walker stands on five feet (the wave,
            # stance > 2 swings: four stay down) and neither neighbour is in the air or due to lift
            # within a swing (no two neighbours up); the body moves on without it from the next tick.
            # The clock is kept: the foot lands before its turn and steps again, or lands a little
            # after it and stands that much longer (docs/physics.md, issue 22).
            self.held += 1
            c = self.clock
            if c.stance_ticks <= 2 * c.swing_ticks:
                return
            for n in range(i + 1, i + 6, 4):  # the neighbours i + 1 and i - 1
                n %= 6
                if self.su[n] >= 0 or (c.start[n] - self.phase) % c.cycle_ticks <= c.swing_ticks:
                    return
            still = 0
        if self.pending and not self.fitting:
            return
        if self.state == STOPPING and still:
            if self.done[i]:
                return
            # A foot already at neutral stays down: it has finished its step.
            if self.fx[i] == self.nx[i] and self.fy[i] == self.ny[i]:
                self.done[i] = 1
                return
        self._early &= ~(1 << i)
        c = self.cmd
        self.band[i + 24] = c[0]  # the command this swing began for (budget.turned)
        self.band[i + 30] = c[1]
        self.band[i + 36] = c[2]
        self.su[i] = 0
        self.sx[i] = self.fx[i]
        self.sy[i] = self.fy[i]

    def _swing(self, i, w, still):
        u = self._swing_step(i, w)
        if u >= w:
            # Lands where the swing put it: on _xy unless a late re-aim left it short.
            self.su[i] = -1
            self.fz[i] = self.ground
            self._to_ground(i)
            if self.state == STOPPING and still and self.fx[i] == self.nx[i] and self.fy[i] == self.ny[i]:
                self.done[i] = 1
        else:
            self.su[i] = u

    def _swing_step(self, i, w):
        """Leg i's swing foot at its next tick u of w into fx, fy, fz[i], its touch-down point
        into _xy; returns u (hexapod/_walk_viper.py's swings is the same in viper).

        The foot follows the swing planned to the touch-down point the command asks for now; when
        the command changed since the last tick, the plan jumps, and the foot moves only as the
        new plan does plus at most REPLAN_STEP a tick toward it (none on the first and last two
        ticks: those move like the stance), so a late re-aim never yanks a joint."""
        u = self.su[i] + 1
        t = self._xy
        self.target(i, t)
        # Keep the touch-down point inside the reach disc, whatever the ramp is doing.
        self._in_reach(i, t)
        sh = swing_shape(u, w, self._shape)
        cv = self._cv
        self.carry_at(self.sx[i], self.sy[i], cv, 0)
        self.carry_at(t[0], t[1], cv, 2)
        if in_budget(self, i, t, cv):
            self.carry_at(t[0], t[1], cv, 2)
        p = self._plan
        self._swing_at(i, u - 1, w, p)
        rx = p[0] - self.fx[i]  # how far the plan moved since the last tick, fine (0 when steady)
        ry = p[1] - self.fy[i]
        self._swing_at(i, u, w, p)
        if rx or ry:
            st = self._stroke[0]
            if 0 < st < ONE:
                rx -= REPLAN_STEP if rx > REPLAN_STEP else -REPLAN_STEP if rx < -REPLAN_STEP else rx
                ry -= REPLAN_STEP if ry > REPLAN_STEP else -REPLAN_STEP if ry < -REPLAN_STEP else ry
            p[0] -= rx
            p[1] -= ry
            self._in_reach(i, p)
        self.fx[i] = p[0]
        self.fy[i] = p[1]
        self.fz[i] = self.ground + mul_q15(self.lift << FINE_SHIFT, sh[1])
        return u

    def _swing_at(self, i, u, w, p):
        """Where the swing planned from leg i's lift-off to _xy (carries in _cv) puts the foot at
        tick u of w, inside the reach disc: into p[0:2], fine."""
        cv = self._cv
        t = self._xy
        sx = self.sx[i]
        sy = self.sy[i]
        st = swing_stroke(u, w, self._stroke)
        # The carry turns from lift-off's to touch-down's as the stroke goes (they differ
        # when turning); x = S + C u / w + (T - S - C) stroke.
        cx = cv[0] + mul_q15(cv[2] - cv[0], st[0])
        cy = cv[1] + mul_q15(cv[3] - cv[1], st[0])
        p[0] = sx + mul_q15(cx, st[1]) + mul_q15(t[0] - sx - cx, st[0])
        p[1] = sy + mul_q15(cy, st[1]) + mul_q15(t[1] - sy - cy, st[0])
        # Leaving and meeting the ground at the stance's speed carries the foot a little past
        # both ends of the swing: keep it inside the reach disc.
        self._in_reach(i, p)

    def _in_reach(self, i, p):
        """Pull the point p[0:2] (fine) onto leg i's reach disc when it lies outside, in place."""
        dx = (p[0] - self.nx[i]) >> FINE_SHIFT
        dy = (p[1] - self.ny[i]) >> FINE_SHIFT
        e2 = dx * dx + dy * dy
        r = self.rho[i]
        if e2 > r * r:
            e = isqrt(e2)
            p[0] = self.nx[i] + (dx * r // e << FINE_SHIFT)
            p[1] = self.ny[i] + (dy * r // e << FINE_SHIFT)

    def _to_ground(self, i):
        """Pin leg i's foot where it is now, in the ground frame."""
        cd = (self.psi + 50) // 100
        c = cos(cd)
        s = sin(cd)
        x = self.fx[i]
        y = self.fy[i]
        self.px[i] = self.bx + mul_q15(x, c) - mul_q15(y, s)
        self.py[i] = self.by + mul_q15(x, s) + mul_q15(y, c)

    def _stance(self, bx, by, cd):
        """The stance feet read back into the body frame with the body at (bx, by) (fine) turned
        cd (cdeg), into ax, ay; 1 + the first leg whose foot that would carry out of its reach disc
        (and further from neutral than it is) or of its ease band (budget.off_band), else 0
        (hexapod/_walk_viper.py's stance is the same in viper)."""
        c = cos(cd)
        s = sin(cd)
        for i in range(6):
            if self.su[i] >= 0:
                continue
            x = self.px[i] - bx
            y = self.py[i] - by
            ax = mul_q15(x, c) + mul_q15(y, s)
            ay = mul_q15(y, c) - mul_q15(x, s)
            dx = (ax - self.nx[i]) >> FINE_SHIFT
            dy = (ay - self.ny[i]) >> FINE_SHIFT
            r = self.rho[i]
            if dx * dx + dy * dy > r * r:
                ox = (self.fx[i] - self.nx[i]) >> FINE_SHIFT
                oy = (self.fy[i] - self.ny[i]) >> FINE_SHIFT
                if dx * dx + dy * dy > ox * ox + oy * oy:
                    return i + 1
            self.ax[i] = ax
            self.ay[i] = ay
            if off_band(self, i):
                return i + 1
        return 0

    def _move_body(self):
        v = self.vel
        dpsi = v[2] << 1  # cdeg/s over 20 ms, in ANGLE_UNIT (1e-4 degree)
        cd = (self.psi + (dpsi >> 1) + 50) // 100
        c = cos(cd)
        s = sin(cd)
        # Body velocity in the ground frame (0.1 mm/s), then this tick's move in fine units;
        # the carries keep the remainders so the long-run speed is exact.
        gx = mul_q15(v[0], c) - mul_q15(v[1], s)
        gy = mul_q15(v[0], s) + mul_q15(v[1], c)
        n = gx * FINE * TICK_MS + self.cx
        mx = n // 1000
        cx = n - mx * 1000
        n = gy * FINE * TICK_MS + self.cy
        my = n // 1000
        cy = n - my * 1000
        psi = self.psi + dpsi
        if psi >= _DEG360:
            psi -= _DEG360
        elif psi < 0:
            psi += _DEG360
        if not (mx or my or dpsi):
            self.cx = cx
            self.cy = cy
            return  # standing still: stance feet keep their exact places (no read-back rounding)
        bx = self.bx + mx
        by = self.by + my
        cd = (psi + 50) // 100
        i = self._stance(bx, by, cd)
        if i:
            self._maybe_lift(i - 1, -1)  # this move would carry that stance foot out of reach or its band: hold
            return
        self.bx = bx
        self.by = by
        self.cx = cx
        self.cy = cy
        self.psi = psi
        for i in range(6):
            if self.su[i] < 0:
                self.fx[i] = self.ax[i]
                self.fy[i] = self.ay[i]
        if bx > _REANCHOR or bx < -_REANCHOR or by > _REANCHOR or by < -_REANCHOR:
            for i in range(6):
                self.px[i] -= bx
                self.py[i] -= by
            self.bx = 0
            self.by = 0


def _words(n, v=0):
    """n machine words (array("i")), each v."""
    return array("i", [v] * n)


def _bad(name, v, lim, unit):
    if not is_whole(v):
        raise ValueError("%s: need a whole number (%s), got %r" % (name, unit, v))
    raise ValueError("%s: %d %s is outside -%d..%d" % (name, v, unit, lim, lim))
