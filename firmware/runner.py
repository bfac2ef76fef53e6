"""The robot's control loop with its drivers handed in: a robot geometry, the servo calibration,
a servo bank (drivers.pca9685.ServoBank or the CircuitPython one), its sensors and a clock (the
`time` module on MicroPython; the virtual clock in tests). main.py builds one on a board.

Each step is one 50 Hz frame: each sensor's share of the frame (hexapod.sensors' frame sensor:
the sonars' round-robin slot first, then any other sensor handed in), the wall follower when it
is on (hexapod.follow: PID -> walk command), one control tick, one burst per PCA9685. Nothing in
a step raises on bus or sensor trouble: faults are counted and kept in plain attributes for a
console to show, and the loop goes on.

Wall following from code (a console wires `wall left|right CM`, `wall off`, `pid KP KI KD`):
    runner.follow("left", 800)        # follow the left wall, side sonar reading 80 mm
    runner.follower.set_gains(25000, 500, 1000)   # seed 000's Kp, Ki, Kd in milli-units
    runner.follow_off()               # stop following; the feet are set down
State for a reply or the status line: runner.follower.mode_name, .used, .distance_only,
.distance, .angle, .error, .output, .front, .faults, .fault_total, .reason_name.
"""

from micropython import const

from hexapod import faultlog as faultlogs
from hexapod import follow, limits, sensors, tick

# The names step() reads every frame, copied as private constants: folded into the code, where an
# imported module's name is two dictionary lookups a frame (tests/test_viper_twins.py checks each
# copy against its source).
_SONAR_OK = const(0)  # hexapod.sensors.OK
_SONAR_WAIT = const(5)  # hexapod.sensors.WAIT
_SONAR_FAULT = const(3)  # hexapod.faultlog.SONAR
_SAMPLE_FRAMES = const(10)  # hexapod.battery.SAMPLE_FRAMES
_CUTOFF = const(2)  # hexapod.battery.CUTOFF
_NO_CHANGE = const(-1)  # hexapod.battery.NO_CHANGE
_BATTERY_OK = const(0)  # hexapod.battery.OK
_RELAXED = const(0)  # hexapod.tick.RELAXED
_STANDING = const(3)  # hexapod.tick.STANDING

FRAME_MS = 20
FRAME_US = 20000
SPIN_US = 1500  # a frame's last stretch waits in sleep_us: sleep_ms may end up to 1 ms late

# What power_up did, as the console's `status` shows it (boot WORD).
BOOT_NOT_YET = 0
BOOT_STOOD = 1  # the board file's "boot": "stand", with a valid calibration file
BOOT_RELAXED = 2  # the board file's "boot": "relaxed" (the default)
BOOT_UNCALIBRATED = 3  # no valid calibration file: relaxed, whatever the board file's "boot"
BOOT_BATTERY = 4  # the battery was below its cutoff at power-up: relaxed, whatever the board file's "boot"
BOOT_WORDS = ("none", "stood", "relaxed", "relaxed_uncalibrated", "relaxed_battery")
BOOT_NOTICES = (
    "",
    "boot: standing up (the board file's boot setting is stand, the servos are calibrated)",
    "boot: relaxed, no pulse until `stand` (the board file's boot setting)",
    "boot: relaxed, no pulse until `stand`: no valid calibration file (calibrate, `save`: docs/jog.md)",
    "boot: relaxed, no pulse: the battery is below its cutoff (charge it; `stand` is refused until then)",
)


class Runner:
    """Robot + servo bank + sonars -> a loop of 20 ms frames; step() runs one."""

    def __init__(
        self, geometry, servo_maps, bank, sonars, clock, mounts=None, battery=None, adc=None, others=(), keeper=None
    ):
        """geometry: hexapod.geometry.load(...); servo_maps: 18 ServoMaps (leg/joint order);
        bank: has write_frame(pulses), failed_frames, reinits; sonars: hexapod.sensors.Sonars
        (the round robin of hcsr04 rangers, hexapod.sensors order); clock: ticks_ms/ticks_us/
        ticks_add/ticks_diff/sleep_ms/sleep_us; mounts: the five sonars' (x, y, heading), 0.1 mm
        and cdeg (hexapod.robotcal.sensor_mounts; default: the shipped robot's); battery: a
        hexapod.battery.Monitor (None: no monitor) and adc what it reads (machine.ADC:
        read_u16()), read once now and every SAMPLE_FRAMES frames; others: more frame sensors
        (hexapod.sensors: frame(now_ms), faults), each asked once a frame after the sonars;
        keeper: where the fault log outlives a soft reset (drivers.faultkeep.for_port), or None."""
        self.clock = clock
        self.bank = bank
        self.robot = tick.Robot(geometry, servo_maps, bank)
        self.sonars = sonars
        self.others = tuple(others)  # asked after the sonars, in this order
        self.distances = sonars.distances  # 0.1 mm, NO_DISTANCE when not OK (the sonars' buffers)
        self.sonar_status = sonars.status
        self.frames = 0
        self.held = 0  # ticks whose frame the robot held back (hexapod.tick reason codes)
        self.next_us = clock.ticks_us()  # the next frame's start
        # The frame's own time, from step() to wait() (the console's work and a telemetry line
        # included), us: the last whole frame's, and the most since the telemetry's last line
        # (drivers/stream.py sets it back to 0 when it writes one).
        self.frame_us = 0
        self.frame_us_max = 0
        self._frame_t0 = self.next_us
        self.follower = follow.Follower(self.robot, sensors.DEFAULT_MOUNTS if mounts is None else mounts)
        self._start = None  # a follow setting waiting for the robot to stand
        self.console = None  # console.Console: polled once a frame when set (console.start)
        self.watchdog = None  # machine.WDT (the board file's watchdog_ms): fed once a frame
        self.sonar_pins = None  # (trigger, echo) per sonar, hexapod.sensors order (main.build): selftest's hints
        self.boot = BOOT_NOT_YET  # what power_up did (BOOT_WORDS)
        self.battery = battery
        self.adc = adc
        self._battery_n = 0  # frames since the last battery reading
        # The fault log takes a fault when it starts, not every frame it lasts (hexapod.faultlog).
        self.faultlog = faultlogs.FaultLog(keeper)
        self._sonar_bad = [False] * len(sonars.status)
        self._bus_failed = bank.failed_frames
        self._bus_bad = False
        self._reinits = bank.reinits
        chips = getattr(bank, "chips", ())
        self._chip_errors = [c.errors for c in chips]
        self._chip_resets = [c.resets_seen for c in chips]
        if battery is not None:
            if adc is None or not hasattr(adc, "read_u16"):
                raise ValueError("adc: a battery monitor needs an ADC with read_u16(), got %r" % (adc,))
            self._battery_changed(battery.update(adc.read_u16()))

    def follow(self, side, setpoint, speed=None, form="crab"):
        """Follow the `side` ("left" or "right") wall at `setpoint` (0.1 mm, the side sonar's
        reading, as in seed 000) walking forward at `speed` (0.1 mm/s, default follow.SPEED);
        form "crab" (the default: the PID walks sideways, turning only to stay near parallel,
        docs/wall.md), "yaw" (the PID turns through Robot.walk's yaw rate) or "sweeps" (seed 000's
        coxa sweeps). Returns 0 when following, else
        a hexapod.tick reason code (22 not standing, 21 busy, 23 unreachable) having changed
        nothing; bad values raise ValueError naming the value and what is allowed, changing
        nothing. Again on the same side: new set point and speed on the fly (no derivative kick)."""
        return self.follower.follow(side, setpoint, speed, form)

    def follow_off(self):
        """Stop following: the robot finishes its steps and sets its feet down. Returns 0."""
        self._start = None
        return self.follower.off()

    def bring_up(self, reader=None, boot=None, calibrated=None, later=False):
        """The board entry once built (main.py, code.py): a console on reader, which loads the
        calibration file, then power_up. boot ("relaxed", "stand") overrides the board file's;
        calibrated (True/False) stands in for the file where none is read (host runs; None: the
        file decides). later (main.py): a boot that does not stand leaves the file's load and
        power_up to the console's first polls, a step a frame (console.start): the first frame
        comes sooner, and no command runs before the file's calibration is in force."""
        board = self.board if boot is None else dict(self.board, boot=boot)
        if reader is not None:
            import os
            import sys

            import console

            later = later and calibrated is None and board.get("boot") != "stand"
            console.start(
                self,
                reader,
                os,
                walk_timeout_ms=self.board.get("walk_timeout_ms") or console.WALK_TIMEOUT_MS,
                write=sys.stdout.write,
                board=board if later else None,
            )
            if later:
                return self.boot
        if calibrated is None:
            calibrated = self.console is not None and self.console.cal_source == "file"
        return self.power_up(board, calibrated)

    def serve(self, frames, status_every):
        """run(); Ctrl-C leaves the loop with the servos relaxed, or held (the board file's on_exit)."""
        try:
            self.run(frames, status_every)
        except KeyboardInterrupt:
            hold = self.board.get("on_exit") == "hold"
            self.leave(hold)
            print("stopped: servos %s; runner.run() resumes" % ("held" if hold else "relaxed"))

    def power_up(self, board, calibrated, out=print):
        """What a board does at power-up (main.py, code.py): stand, and then follow the board's
        "follow" wall, only when the board file's "boot" is "stand" and calibrated (a calibration
        file that loaded); else stay relaxed, no pulse sent until a `stand` (a "follow" setting then
        waits for it). Prints one notice line with out; keeps the outcome in self.boot."""
        if board.get("follow"):
            self.follow_when_standing(board["follow"])
        if self.battery is not None and self.battery.state == _CUTOFF:
            self._start = None
            self.boot = BOOT_BATTERY
        elif not calibrated:
            self.boot = BOOT_UNCALIBRATED
        elif board.get("boot", "relaxed") != "stand":
            self.boot = BOOT_RELAXED
        else:
            self.boot = BOOT_STOOD
            self.robot.stand_up()
        out(BOOT_NOTICES[self.boot])
        return self.boot

    def follow_when_standing(self, setting):
        """Start following once the robot stands (main.py's start-up): setting is a board
        file's "follow" dict (side, setpoint, optional speed and form), checked now."""
        limits.check_request(setting["side"], setting["setpoint"], setting.get("speed"), setting.get("form", "crab"))
        self._start = setting

    def step(self):
        """One frame now: ping, tick, write. Returns the tick's code (0 = frame sent)."""
        self._frame_t0 = self.clock.ticks_us()  # the frame's time runs to wait()
        now = self.clock.ticks_ms()  # the frame's start: a ping's variable length must not look like jitter
        b = self.battery
        if b is not None:
            self._battery_n += 1
            if self._battery_n >= _SAMPLE_FRAMES:
                self._battery_n = 0
                self._battery_changed(b.update(self.adc.read_u16()))
            if b.state == _CUTOFF and self.robot.mode != _RELAXED:
                self._shut_down()
        i = self.sonars.frame(now)
        if i >= 0:  # the fault log takes a sonar's fault when it starts (after an OK reading)
            st = self.sonar_status[i]
            if st == _SONAR_OK:
                self._sonar_bad[i] = False
            elif st != _SONAR_WAIT and not self._sonar_bad[i]:
                self._sonar_bad[i] = True
                self.faultlog.record(_SONAR_FAULT, i, self.frames)
        others = self.others
        if others:  # none on the shipped boards: the frame pays one test for the hook
            for k in range(len(others)):
                others[k].frame(now)
        robot = self.robot
        if self.follower.mode:
            self.follower.update(now, i, self.distances, self.sonar_status)
        elif self._start is not None and robot.mode == _STANDING:
            s = self._start
            self._start = None
            self.follow(s["side"], s["setpoint"], s.get("speed"), s.get("form", "crab"))
        code = robot.tick(now)
        bank = self.bank
        # The bank's counters asked here, the log's bookkeeping called only when one moved or the
        # bus was bad last frame (a call a frame cost ~60 us on the emulated Pico).
        if bank.failed_frames != self._bus_failed or self._bus_bad or bank.reinits != self._reinits:
            self._watch_bank()
        self.frames += 1
        if code:
            self.held += 1
        return code

    def _watch_bank(self):
        """Log a frame some chip did not take after one that all took, and every chip reset found."""
        bank = self.bank
        if bank.failed_frames != self._bus_failed:
            self._bus_failed = bank.failed_frames
            if not self._bus_bad:
                self._bus_bad = True
                self.faultlog.record(faultlogs.I2C, self._grew(self._chip_errors, "errors"), self.frames)
        else:
            self._bus_bad = False
        if bank.reinits != self._reinits:
            self._reinits = bank.reinits
            self.faultlog.record(faultlogs.BROWNOUT, self._grew(self._chip_resets, "resets_seen"), self.frames)

    def _grew(self, seen, name):
        """The index of the first chip whose counter `name` rose since seen (updated), else of the
        first chip offline (a chip that never answered is skipped, its counters stand), else 0."""
        chips = self.bank.chips
        found = -1
        for k in range(len(seen)):
            v = getattr(chips[k], name)
            if v != seen[k]:
                seen[k] = v
                if found < 0:
                    found = k
        if found >= 0:
            return found
        for k in range(len(seen)):
            if chips[k].offline:
                return k
        return 0

    def note_reset(self, cause_is_watchdog):
        """At boot: log a watchdog reset, unless the newest kept fault is already this one (a soft
        reset after it reports the same hardware cause again)."""
        log = self.faultlog
        n = log.count()
        if not cause_is_watchdog or (n and log.entry(n - 1)[:3] == (faultlogs.WATCHDOG, 0, 0)):
            return
        log.record(faultlogs.WATCHDOG, 0, 0)

    def _battery_changed(self, state):
        """A battery state change (hexapod.battery: NO_CHANGE, OK, LOW, CUTOFF) -> the speed cap,
        the wall follower. The console announces it (console.Console.poll)."""
        if state == _NO_CHANGE:
            return
        if state == _BATTERY_OK:
            self.robot.cap_speed(0, 0)
            return
        from hexapod import battery as batteries  # loaded with the monitor: a board without one never loads it

        self.robot.cap_speed(batteries.LOW_SPEED, batteries.LOW_YAW)
        if state == _CUTOFF:
            self.faultlog.record(faultlogs.BATTERY, 0, self.frames)
            self._start = None  # a board file's follow waiting for a stand waits no more
            if self.follower.mode:
                self.follower.off()

    def _shut_down(self):
        """Below the cutoff: stop walking, then sit and relax (one step a frame, as each becomes
        possible). A relax the posture check refuses (a jogged leg that cannot get home) lets
        the servos go limp at once: the battery comes first."""
        r = self.robot
        m = r.mode
        if m == tick.WALKING:
            if r.asked_vx or r.asked_vy or r.asked_yaw:
                r.stop()  # the feet come down within a cycle, then the robot stands
            return
        if m == tick.MOVING:
            return  # a posture move finishes first (at most a few hundred frames)
        code = r.relax()
        if code == tick.PATH_IK or code == tick.PATH_SERVO:
            r.go_limp()

    def wait(self):
        """Sleep until the next 20 ms frame boundary, to the us: whole ms, then the rest in
        sleep_us (at once when late: the tick counts overruns). The frame's own time (since
        step()) goes into frame_us and frame_us_max first."""
        clock = self.clock
        now = clock.ticks_us()
        us = clock.ticks_diff(now, self._frame_t0)
        self.frame_us = us
        if us > self.frame_us_max:
            self.frame_us_max = us
        self.next_us = clock.ticks_add(self.next_us, FRAME_US)
        left = clock.ticks_diff(self.next_us, now)
        if left < -FRAME_US:
            self.next_us = clock.ticks_us()  # far behind: start counting from now, never burst
            return
        if left > SPIN_US:
            clock.sleep_ms((left - SPIN_US) // 1000)
            left = clock.ticks_diff(self.next_us, clock.ticks_us())
        if left > 0:
            clock.sleep_us(left)

    @property
    def sonar_faults(self):
        """Pings that came back OUT_OF_RANGE, NO_ECHO, STUCK or TOO_CLOSE."""
        return self.sonars.faults

    def run(self, frames=-1, status_every=0):
        """Run frames (forever when -1), each on its 20 ms boundary; print status_line every
        status_every frames (0: never)."""
        # The frames count from now, not from when the runner was built: else the first wait finds
        # itself a whole period late and the second frame starts at once, while the first frame's
        # bursts are still on the bus (it then waited ~1.4 ms for them on the emulated Pico).
        self.next_us = self.clock.ticks_us()
        n = 0
        robot = self.robot
        robot.defer = True  # a walking configure's step after the console's line, not with it
        try:
            while frames < 0 or n < frames:
                self.step()
                con = self.console
                if con is not None:
                    lines = con.lines
                    con.poll()
                    if robot.owed:
                        robot.pay(con.lines != lines)
                elif robot.owed:
                    robot.pay(False)
                if self.watchdog is not None:
                    self.watchdog.feed()
                n += 1
                if status_every and n % status_every == 0:
                    print(status_line(self))
                self.wait()
        finally:
            robot.defer = False

    def leave(self, hold=False):
        """The loop is being left (Ctrl-C): servos limp at once, or (hold) keep the last frame.
        Wall following ends either way; run() resumes from a relaxed robot."""
        self._start = None
        self.follower.off()
        if not hold:
            self.robot.go_limp()


def counters(r):
    """The loop's counters as text: frames, held frames, overruns, bus failures, reinits, sonar faults."""
    return "frames %d held %d overruns %d bus_failed %d reinit %d sonar_faults %d" % (
        r.frames,
        r.held,
        r.robot.overruns,
        r.bank.failed_frames,
        r.bank.reinits,
        r.sonar_faults,
    )


def status_line(r):
    """One line for the serial console: the counters, distances (0.1 mm) and the wall follower
    (mode, d, angle, error, output, sensors, faults)."""
    return "%s dist %s %s" % (counters(r), r.distances, follow.status_text(r.follower))
