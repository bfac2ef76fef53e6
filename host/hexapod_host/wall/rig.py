"""The firmware's side of the wall simulator: the board's whole loop on the stub machine.

Runs on CPython (hexapod_host.wall.sim calls Rig directly) and inside the MicroPython VM
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

# Bare names, as the board has them: firmware/ and the MicroPython stubs are on sys.path (MICROPYPATH in the VM).
import _stub_clock as clock
import hcsr04_model
import main
import standing
import stub_board

from hexapod import board as boards

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


def set_distances(sonars, d):
    """What each HC-SR04 model answers on its next ping: d in 0.1 mm, NO_ECHO for nothing heard
    (also the virtual board's room, hexapod_host.vm.virtual_board)."""
    for k in range(len(sonars)):
        v = d[k]
        sonars[k].set_distance(v if v > 0 else hcsr04_model.MAX_RANGE + 1)


class Rig:
    """main.build's Runner on the stub machine, HC-SR04 models at distances the caller sets."""

    def __init__(self, board_name="pico", bus="pca"):
        if bus not in ("pca", "sink"):
            raise ValueError("bus: %r, allowed 'pca' or 'sink'" % (bus,))
        board = stub_board.reset(board_name)
        if bus == "pca":
            stub_board.pca9685_models(board)
        self.sonars = stub_board.sonar_models(board, [40001] * len(boards.sonar_pins(board)))
        # bus="sink": the Tee alone stands for the servo bank (no I2C traffic)
        self.runner = main.build(board_name, clock=clock, bank=None if bus == "pca" else Tee(None))
        self.tee = Tee(self.runner.bank if bus == "pca" else None)
        self.runner.robot.frame = self.tee
        self.robot = self.runner.robot
        self.follower = self.runner.follower

    def set_distances(self, d):
        """What each model answers on its next ping: 0.1 mm, NO_ECHO for nothing heard."""
        set_distances(self.sonars, d)

    def stand(self):
        """Stand up; returns the frames it took (the sonars ping all along), RuntimeError past 1000."""
        return standing.stand(self.robot, lambda n: self.step(), 1000)

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


if __name__ == "__main__":  # in the VM: `micropython rig.py` (hexapod_host.wall.sim.FirmwareMicroPython)
    serve()
