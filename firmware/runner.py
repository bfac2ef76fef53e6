"""The robot's control loop with its drivers handed in: a robot geometry, the servo calibration,
a servo bank (drivers.pca9685.ServoBank or the CircuitPython one), the sonars and a clock (the
`time` module on MicroPython; the virtual clock in tests). main.py builds one on a board.

Each step is one 50 Hz frame: one sonar ping (round robin), one control tick, one burst per
PCA9685. Nothing in a step raises on bus or sensor trouble: faults are counted and kept in
plain attributes for a console to show, and the loop goes on.
"""

from drivers import hcsr04
from hexapod import tick

FRAME_MS = 20


class Runner:
    """Robot + servo bank + sonars -> a loop of 20 ms frames; step() runs one."""

    def __init__(self, geometry, servo_maps, bank, sensors, clock):
        """geometry: hexapod.geometry.load(...); servo_maps: 18 ServoMaps (leg/joint order);
        bank: has write_frame(pulses), failed_frames, reinits; sensors: hcsr04 rangers in
        drivers.hcsr04 order; clock: ticks_ms/ticks_add/ticks_diff/sleep_ms."""
        self.clock = clock
        self.bank = bank
        self.robot = tick.Robot(geometry, servo_maps, bank)
        self.sonar = hcsr04.RoundRobin(sensors, tick_ms=FRAME_MS)
        self.distances = [hcsr04.NO_DISTANCE] * len(sensors)  # 0.1 mm, NO_DISTANCE when not OK
        self.sonar_status = [hcsr04.WAIT] * len(sensors)  # WAIT until a sensor has a first result
        self.sonar_faults = 0  # pings that came back NO_ECHO, STUCK or OUT_OF_RANGE
        self.frames = 0
        self.held = 0  # ticks whose frame the robot held back (hexapod.tick reason codes)
        self.next_ms = clock.ticks_ms()

    def step(self):
        """One frame now: ping, tick, write. Returns the tick's code (0 = frame sent)."""
        now = self.clock.ticks_ms()  # the frame's start: a ping's variable length must not look like jitter
        i = self.sonar.tick(self.distances, self.sonar_status)
        if i >= 0:
            st = self.sonar_status[i]
            if st != hcsr04.OK and st != hcsr04.WAIT:
                self.sonar_faults += 1
        code = self.robot.tick(now)
        self.frames += 1
        if code:
            self.held += 1
        return code

    def wait(self):
        """Sleep until the next 20 ms frame boundary (at once when late: the tick counts overruns)."""
        clock = self.clock
        self.next_ms = clock.ticks_add(self.next_ms, FRAME_MS)
        late = clock.ticks_diff(clock.ticks_ms(), self.next_ms)
        if late < 0:
            clock.sleep_ms(-late)
        elif late > FRAME_MS:
            self.next_ms = clock.ticks_ms()  # far behind: start counting from now, never burst

    def run(self, frames=-1, status_every=0):
        """Run frames (forever when -1), each on its 20 ms boundary; print status_line every
        status_every frames (0: never)."""
        n = 0
        while frames < 0 or n < frames:
            self.step()
            n += 1
            if status_every and n % status_every == 0:
                print(status_line(self))
            self.wait()


def status_line(r):
    """One line for the serial console: frames, held frames, overruns, bus and sonar faults."""
    return "frames %d held %d overruns %d bus_failed %d reinit %d sonar_faults %d dist %s" % (
        r.frames,
        r.held,
        r.robot.overruns,
        r.bank.failed_frames,
        r.bank.reinits,
        r.sonar_faults,
        r.distances,
    )
