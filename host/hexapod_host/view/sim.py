"""The wall simulator as a view source (`hexapod view --sim`): its trials one after another,
frame by frame, through hexapod_host.wall.sim.Trial, the very loop `hexapod sim wall` runs
(the board's firmware on the stub machine, the room's sonars, the body moved by its feet)."""

from hexapod import follow, sensors, tick
from hexapod_host.view.source import Source, pose
from hexapod_host.wall.room import BODY_HALF
from hexapod_host.wall.sim import FRAME_S, Trial, trial_seed


def _mm(v):
    """0.1 mm from the firmware to mm; None for its 'no reading' (negative)."""
    return None if v < 0 else v / 10


class SimSource(Source):
    """Trials in a world (hexapod_host.wall.world.World) at one set point (cm): trial k runs on
    the seed `hexapod sim wall` gives its k-th trial, disturbances on unless disturb=False."""

    name = "sim"
    frame_s = FRAME_S
    steppable = True

    def __init__(self, world, setpoint_cm=12, seed=0, side=None, disturb=True):
        self.world, self.setpoint_cm, self.seed = world, setpoint_cm, seed
        self.side, self.disturb = side, disturb
        self.index = -1
        self.trial = None
        self.restart()

    def restart(self):
        """The next trial (the first one on the first call)."""
        self.close()
        self.index += 1
        seed = trial_seed(self.seed, self.world.name, self.setpoint_cm, self.index)
        # The frame sink, not the I2C model: the same frames (tests/test_wall_sim.py), a third of the work.
        self.trial = Trial(
            self.world,
            self.setpoint_cm,
            seed,
            side=self.side,
            disturb=self.disturb,
            bus="sink",
            record=False,
            form="crab",  # the board's default (Runner.follow), as `hexapod sim wall` runs it
        )
        self._last = None

    def close(self):
        if self.trial is not None:
            self.trial.close()

    def describe(self):
        b = self.trial.body
        return {
            "source": self.name,
            "world": self.world.name,
            "walls": [list(w) for w in self.world.walls],
            "finish": list(self.world.finish),
            "sensors": [[x, y, h] for x, y, h in b.sensors],
            "body_half": list(BODY_HALF),
            "brackets": [list(seg) for seg in b.outline[4:]],  # body edge -> sonar, mm (room.Body's outline)
            "frame_s": self.frame_s,
        }

    def step(self):
        self.trial.step()

    def done(self):
        return self.trial.done

    def snapshot(self):
        t = self.trial
        rig = t.fw.rig
        runner, f, b = rig.runner, rig.follower, t.body
        legs = pose(b, t.pulses) or self._last
        self._last = legs
        z = -min(leg[3][2] for leg in legs["legs"])
        return {
            "frame": t.n,
            "time_s": round(t.n * self.frame_s, 3),
            **legs,
            "body": {"x": b.x, "y": b.y, "z": z, "yaw": b.theta},
            "distances": [_mm(v) for v in runner.distances],
            "sonar_status": [sensors.STATUS_NAMES[s] for s in runner.sonar_status],
            "mode": tick.MODE_NAMES[rig.robot.mode],
            "follow": {
                "mode": follow.MODE_NAMES[f.mode],
                "side": f.side,
                "setpoint_mm": f.setpoint / 10,
                "error_mm": f.error / 10,
                "output_dps": f.output / 100,
                "sensor_state": [follow.STATE_NAMES[s] for s in f.state],
            },
            "counters": {
                "frames": runner.frames,
                "held": runner.held,
                "overruns": rig.robot.overruns,
                "bus_failed": runner.bank.failed_frames,
                "reinit": runner.bank.reinits,
                "sonar_faults": runner.sonar_faults,
            },
            "extra": {
                "trial": self.index,
                "done": t.done,
                "why": t.why,
                "wall_mm": t.wall_mm,
                "path_mm": round(t.path, 1),
                # the walk asked (the follower's), as the telemetry's vx vy yaw: mm/s, mm/s, deg/s
                "walk": [rig.robot.asked_vx / 10, rig.robot.asked_vy / 10, rig.robot.asked_yaw / 100],
                "battery_mv": None if runner.battery is None else runner.battery.level_mv,
            },
        }
