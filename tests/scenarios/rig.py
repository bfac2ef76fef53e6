"""A robot on a frame buffer with its own 20 ms clock, and the one way to stand it up."""

import standing

import robots.default as d
from hexapod import geometry, tick

TICK_MS = 20


def unguarded_geometry():
    """robots/default.py's Geometry without its servo speed guard, its stance reach limit and its
    per-gait cycles (every gait at 1 s): for the walk's kinematics beyond what the guard allows."""
    data = {k: getattr(d, k) for k in dir(d) if k.isupper()}
    data["SERVO"] = {k: v for k, v in d.SERVO.items() if k != "planner_share_permille" and k != "stance_out_max"}
    data.pop("GAIT_CYCLE_MS")
    return geometry.from_data("default", data)


def stand(robot, now=0):
    """Stand the robot up and tick it every 20 ms from now until it is STANDING (standing.stand:
    RuntimeError if it has not within its frame bound); return the clock after."""
    return now + TICK_MS * standing.stand(robot, lambda n: robot.tick(now + TICK_MS * n))


def servo_state(robot, con):
    """What a refused console command must leave as it was: the pulses, angles and mode, each
    servo's calibration (centre_us, direction, min_us, max_us) and the console's trims."""
    return [
        list(robot.pulses),
        list(robot.angles),
        robot.mode,
        [(s.centre_us, s.direction, s.min_us, s.max_us) for s in robot.servos],
        list(con.trims),
    ]


class Rig:
    """A tick.Robot on a FrameBuffer (default servos) and the clock its ticks read."""

    def __init__(self, g=None):
        self.g = geometry.load(d) if g is None else g
        self.frame = tick.FrameBuffer()
        self.robot = tick.Robot(self.g, tick.default_servos(self.g), self.frame)
        self.w = self.robot.walker
        self.t = 0
        self.faults = []  # [code, leg, leg code] of each tick run() saw fault

    def run(self, n):
        """n ticks, 20 ms apart."""
        robot = self.robot
        for _ in range(n):
            code = robot.tick(self.t)
            self.t += TICK_MS
            if code:
                self.faults.append([code, robot.fault_leg, robot.fault_code])

    def stand(self):
        self.t = stand(self.robot, self.t)
