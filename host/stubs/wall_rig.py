"""The firmware's side of the wall simulator: the board's whole loop on the stub machine.

Runs on CPython (hexapod_host.sim_wall calls Rig directly) and inside the MicroPython VM
(`serve()` on stdin/stdout, one line per frame), the same code either way, so the trajectory
of a trial is the same on both runtimes as long as the firmware is bit-identical.

The runner is built by main.build on the stub machine: the board file, the sonars on stub pins
with HC-SR04 models (the real drivers/hcsr04.py pings them on the virtual clock), the servo
bank on the I2C model with PCA9685 models (bus="pca"), or a frame sink instead of the bus
(bus="sink", faster; the same pulses). Each frame the simulator hands in the five distances
the models answer with (0.1 mm; 0 = no echo heard, the module holds its echo for 38 ms) and
takes back the 18 pulses the core sent (us, 0 = none) and the follower's state. The firmware
cannot tell: it sees pins, a clock and a bus.
"""

import _stub_clock as clock
import _stub_i2c
import _stub_pins
import hcsr04_model
import main
from _stub_i2c import shared_bus
from pca9685_model import PCA9685Model

from hexapod import board as boards
from hexapod import tick

NO_ECHO = 0  # a distance of 0 from the simulator: nothing heard


class Tee:
    """Stands between the robot and its servo bank: keeps a copy of each frame sent (us)."""

    def __init__(self, bank):
        self.bank = bank
        self.pulses = [0] * 18
        self.sent = 0  # frames handed to the bank

    def write_frame(self, pulses):
        p = self.pulses
        for k in range(18):
            p[k] = pulses[k]
        self.sent += 1
        if self.bank is not None:
            self.bank.write_frame(pulses)

    @property
    def failed_frames(self):
        return self.bank.failed_frames if self.bank is not None else 0

    @property
    def reinits(self):
        return self.bank.reinits if self.bank is not None else 0


class Rig:
    """main.build's Runner on the stub machine, HC-SR04 models at distances the caller sets."""

    def __init__(self, board_name="pico", bus="pca"):
        clock.reset(0)
        _stub_pins.reset()
        _stub_i2c.reset()
        board = boards.load(board_name)
        if bus == "pca":
            i2c_bus = shared_bus(board["i2c"]["id"])
            i2c_bus.clock_us = clock.now_us
            for c in board["pca9685"]["chips"]:
                i2c_bus.attach(PCA9685Model(c["address"], osc_hz=c["osc_hz"]))
        elif bus != "sink":
            raise ValueError("bus: %r, allowed 'pca' or 'sink'" % (bus,))
        self.sonars = [hcsr04_model.HCSR04(t, e, distance=40001) for t, e in boards.sensor_pins(board)]
        if bus == "pca":
            self.runner = main.build(board_name, clock=clock)
            self.tee = Tee(self.runner.bank)
        else:
            self.runner = _build_on_sink(board_name)
            self.tee = Tee(None)
        self.runner.robot.frame = self.tee
        self.robot = self.runner.robot
        self.follower = self.runner.follower

    def set_distances(self, d):
        """What each model answers on its next ping: 0.1 mm, NO_ECHO for nothing heard."""
        for k in range(len(self.sonars)):
            v = d[k]
            self.sonars[k].set_distance(v if v > 0 else hcsr04_model.MAX_RANGE + 1)

    def stand(self):
        """Stand up; returns the frames it took (the sonars ping all along)."""
        self.robot.stand_up()
        n = 0
        while self.robot.mode != tick.STANDING and n < 1000:
            self.step()
            n += 1
        return n

    def step(self):
        """One 20 ms frame of the real loop; returns the tick's code."""
        code = self.runner.step()
        self.runner.wait()
        return code

    def begin(self, side, setpoint, speed, form, gains, d):
        """Stand up with the sonars answering d (0.1 mm), set the gains (milli-units), follow.
        Returns (frames standing up took, follow()'s code)."""
        self.set_distances(d)
        n = self.stand()
        self.follower.set_gains(gains[0], gains[1], gains[2])
        return n, self.runner.follow(side, setpoint, speed, form)

    def frame(self, d):
        """Distances in, one frame, (code, pulses, mode, fault_total, reason) out."""
        self.set_distances(d)
        code = self.step()
        f = self.follower
        return code, self.tee.pulses, f.mode, f.fault_total, f.reason


def _build_on_sink(board_name):
    """main.build with the servo bank replaced by the Tee alone (no I2C traffic)."""
    from machine import Pin, time_pulse_us
    from runner import Runner

    import robots.default
    from drivers import hcsr04
    from hexapod import geometry

    board = boards.load(board_name)
    table = boards.servo_table(board)
    sensors = []
    pins = boards.sensor_pins(board)
    for k in range(len(pins)):
        trigger, echo = pins[k]
        sensors.append(
            hcsr04.HCSR04(
                Pin(trigger, Pin.OUT), Pin(echo, Pin.IN), clock, time_pulse_us, samples=main.SONAR_SAMPLES[k], irq=True
            )
        )
    g = geometry.load(robots.default)
    return Runner(g, [row[2] for row in table], Tee(None), sensors, clock, boards.sensor_mounts(board))


def serve(readline=None, write=None):
    """The VM's side of the pipe. First line: `board bus side setpoint speed form kp ki kd` and
    five distances; it answers `standing N CODE`. Then per frame five distances (0.1 mm) in, and one line out:
    code, the 18 pulses, follower mode, fault total, reason. An empty line ends."""
    import sys

    readline = readline or sys.stdin.readline
    write = write or sys.stdout.write
    w = readline().split()
    rig = Rig(w[0], w[1])
    n, code = rig.begin(w[2], int(w[3]), int(w[4]), w[5], [int(v) for v in w[6:9]], [int(v) for v in w[9:14]])
    write("standing %d %d\n" % (n, code))
    while True:
        line = readline()
        if not line or not line.strip():
            break
        d = [int(v) for v in line.split()]
        code, pulses, mode, faults, reason = rig.frame(d)
        write("%d %s %d %d %d\n" % (code, " ".join([str(p) for p in pulses]), mode, faults, reason))
        if hasattr(sys.stdout, "flush"):
            sys.stdout.flush()
