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

from hexapod import follow, limits, sensors, tick

FRAME_MS = 20
FRAME_US = 20000
SPIN_US = 1500  # a frame's last stretch waits in sleep_us: sleep_ms may end up to 1 ms late


class Runner:
    """Robot + servo bank + sonars -> a loop of 20 ms frames; step() runs one."""

    def __init__(self, geometry, servo_maps, bank, sonars, clock, mounts=None, others=()):
        """geometry: hexapod.geometry.load(...); servo_maps: 18 ServoMaps (leg/joint order);
        bank: has write_frame(pulses), failed_frames, reinits; sonars: hexapod.sensors.Sonars
        (the round robin of hcsr04 rangers, hexapod.sensors order); clock: ticks_ms/ticks_us/
        ticks_add/ticks_diff/sleep_ms/sleep_us; mounts: the five sonars' (x, y, heading), 0.1 mm
        and cdeg (hexapod.robotcal.sonar_mounts; default: the shipped robot's); others: more
        frame sensors (hexapod.sensors: frame(now_ms), faults), each asked once a frame after
        the sonars."""
        self.clock = clock
        self.bank = bank
        self.robot = tick.Robot(geometry, servo_maps, bank)
        self.sonars = sonars
        self.sensors = (sonars,) + tuple(others)  # every frame sensor, in the order a frame asks them
        self.distances = sonars.distances  # 0.1 mm, NO_DISTANCE when not OK (the sonars' buffers)
        self.sonar_status = sonars.status
        self.frames = 0
        self.held = 0  # ticks whose frame the robot held back (hexapod.tick reason codes)
        self.next_us = clock.ticks_us()  # the next frame's start
        self.follower = follow.Follower(self.robot, sensors.DEFAULT_MOUNTS if mounts is None else mounts)
        self._start = None  # a follow setting waiting for the robot to stand
        self.console = None  # console.Console: polled once a frame when set (console.start)
        self.watchdog = None  # machine.WDT (the board file's watchdog_ms): fed once a frame

    def follow(self, side, setpoint, speed=None, form="yaw"):
        """Follow the `side` ("left" or "right") wall at `setpoint` (0.1 mm, the side sonar's
        reading, as in seed 000) walking forward at `speed` (0.1 mm/s, default follow.SPEED);
        form "yaw" (the PID turns through Robot.walk's yaw rate) or "sweeps" (seed 000's coxa
        sweeps). Returns 0 when following, else a hexapod.tick reason code (22 not standing,
        21 busy, 23 unreachable) having changed nothing; bad values raise ValueError naming the
        value and what is allowed, changing nothing. Again on the same side: new set point and
        speed on the fly (no derivative kick)."""
        return self.follower.follow(side, setpoint, speed, form)

    def follow_off(self):
        """Stop following: the robot finishes its steps and sets its feet down. Returns 0."""
        self._start = None
        return self.follower.off()

    def follow_when_standing(self, setting):
        """Start following once the robot stands (main.py's start-up): setting is a board
        file's "follow" dict (side, setpoint, optional speed and form), checked now."""
        limits.check_follow(setting["side"], setting["setpoint"], setting.get("speed"), setting.get("form", "yaw"))
        self._start = setting

    def step(self):
        """One frame now: ping, tick, write. Returns the tick's code (0 = frame sent)."""
        now = self.clock.ticks_ms()  # the frame's start: a ping's variable length must not look like jitter
        frame_sensors = self.sensors
        for k in range(len(frame_sensors)):
            frame_sensors[k].frame(now)
        if self.follower.mode:
            self.follower.update(now, self.sonars.last, self.distances, self.sonar_status)
        elif self._start is not None and self.robot.mode == tick.STANDING:
            s = self._start
            self._start = None
            self.follow(s["side"], s["setpoint"], s.get("speed"), s.get("form", "yaw"))
        code = self.robot.tick(now)
        self.frames += 1
        if code:
            self.held += 1
        return code

    def wait(self):
        """Sleep until the next 20 ms frame boundary, to the us: whole ms, then the rest in
        sleep_us (at once when late: the tick counts overruns)."""
        clock = self.clock
        self.next_us = clock.ticks_add(self.next_us, FRAME_US)
        left = clock.ticks_diff(self.next_us, clock.ticks_us())
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
        n = 0
        while frames < 0 or n < frames:
            self.step()
            if self.console is not None:
                self.console.poll()
            if self.watchdog is not None:
                self.watchdog.feed()
            n += 1
            if status_every and n % status_every == 0:
                print(status_line(self))
            self.wait()

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
