"""The wall simulator's body moved by MuJoCo instead of by its stance feet (`hexapod sim wall --physics`).

The firmware loop, the pings, the room, the disturbances and the rules are the kinematic
simulator's (hexapod_host.wall.sim); only the mover differs. Each frame the 18 pulses the
core sent drive the MuJoCo model of the robot file (hexapod_host.physics.sim.Run: pulses ->
the board's servo maps -> actuator targets, 10 steps of 2 ms); the body's plan-view step
(its new pose in its old body frame) is taken from the model's free joint and applied to the
room's Body as the feet's step is in the kinematic one (hexapod_host.wall.room.Body.advance: the
trial's speed error and heading slip on top). The legs checked for contact are the model's:
coxa axis, femur joint, knee and foot centre of each leg where MuJoCo has them, in the plan
view of the body frame. The walls are not MuJoCo geoms: a touch ends a trial anyway, so they
never push back; contact is the kinematic simulator's test on the model's geometry.
Units: mm and radians (the room's).
"""

import math

import robots.default
from hexapod_host.physics import sim as sim_physics

_RUN = {}  # one compiled model per process (compiling takes ~0.1 s; a trial resets its data)


def _run():
    if "run" not in _RUN:
        _RUN["run"] = sim_physics.Run(*sim_physics.load_robot(robots.default))
    return _RUN["run"]


class FeetMover:
    """The kinematic simulator: the body moves by what its stance feet did (room.Body.move)."""

    def __init__(self, body, standing):
        self.body = body
        self.old = None

    def step(self, pulses, speed, slip):
        """Move the body by one frame of pulses (us); the distance moved (mm), None without a whole frame."""
        b = self.body
        if not b.legs_from_pulses(pulses):
            return None
        moved = b.move(self.old, speed, slip)
        self.old = b.feet
        return moved


class PhysicsMover:
    """MuJoCo moves the body: the model settles in the standing pulses, then each frame's pulses drive it."""

    def __init__(self, body, standing):
        self.body = body
        self.run = run = _run()
        run.servos = body.maps  # the board's servo maps: what its servos would be told
        run.frame.write_frame(standing)
        run.settle()
        m = run.model
        self.links = [m.body("%s%d" % (part, i + 1)).id for i in range(6) for part in ("coxa", "femur", "tibia")]
        self.pose = run.body_pose()

    def legs(self):
        """Each leg's coxa axis, femur joint, knee and foot (x, y, z mm) in the body frame, where the model has them."""
        d, run = self.run.data, self.run
        x0, y0, yaw = self.pose
        c, s = math.cos(yaw), math.sin(yaw)
        z0 = float(d.qpos[2]) * 1000
        out = []
        for i in range(6):
            pts = [d.xpos[self.links[3 * i + k]] for k in range(3)] + [d.site_xpos[run.foot_sites[i]]]
            leg = []
            for p in pts:
                wx, wy = float(p[0]) * 1000 - x0, float(p[1]) * 1000 - y0
                leg.append((c * wx + s * wy, -s * wx + c * wy, float(p[2]) * 1000 - z0))
            out.append(leg)
        return out

    def step(self, pulses, speed, slip):
        """Drive the model one frame; move the body by its step (mm moved)."""
        self.run.drive(pulses)
        x0, y0, yaw0 = self.pose
        self.pose = x1, y1, yaw1 = self.run.body_pose()
        c, s = math.cos(yaw0), math.sin(yaw0)
        dx, dy = x1 - x0, y1 - y0
        phi = math.atan2(math.sin(yaw1 - yaw0), math.cos(yaw1 - yaw0))
        moved = self.body.advance(phi, c * dx + s * dy, -s * dx + c * dy, speed, slip)
        self.body.set_legs(self.legs())
        return moved


MOVERS = {"kinematic": FeetMover, "physics": PhysicsMover}


END_MM = 30.0  # the paths' first and last 30 mm are not compared: they end at different places


def _to_polyline(p, a):
    """Distance (mm) of each point p (n x 2) to the polyline through a (m x 2, its points in
    order), NaN where the nearest polyline point is within END_MM of its start or end along it
    (p is beyond that path, or where it begins or ends)."""
    import numpy as np

    if len(a) < 2:
        return np.full(len(p), np.nan)
    s0, s1 = a[:-1][None, :, :], a[1:][None, :, :]
    d = s1 - s0
    ll = np.maximum((d * d).sum(axis=2), 1e-12)
    t = np.clip(((p[:, None, :] - s0) * d).sum(axis=2) / ll, 0.0, 1.0)
    near = s0 + t[:, :, None] * d
    dist = np.hypot(p[:, None, 0] - near[:, :, 0], p[:, None, 1] - near[:, :, 1])
    k = dist.argmin(axis=1)
    rows = np.arange(len(p))
    seg = np.sqrt(ll[0])
    along = np.concatenate(([0.0], np.cumsum(seg)))[k] + t[rows, k] * seg[k]
    inside = (along >= END_MM) & (along <= seg.sum() - END_MM)
    return np.where(inside, dist[rows, k], np.nan)


def path_difference(a, b):
    """How far apart two trials' paths of the side sonars' midpoint are (traces of sim_wall.run_trial):
    the mean and the largest distance (mm) of each path's points to the other path, both ways
    pooled, where both paths are: a point whose nearest point on the other path is within
    END_MM of that path's start or end is left out (the traces are sampled every 5 frames and
    end at different places)."""
    import numpy as np

    pa = np.array([(t[2], t[3]) for t in a], dtype=float).reshape(-1, 2)
    pb = np.array([(t[2], t[3]) for t in b], dtype=float).reshape(-1, 2)
    if not len(pa) or not len(pb):
        return None, None
    d = np.concatenate((_to_polyline(pa, pb), _to_polyline(pb, pa)))
    d = d[~np.isnan(d)]
    if not len(d):
        return None, None
    return round(float(d.mean()), 2), round(float(d.max()), 2)


def compare(setpoint, pairs, summarise):
    """One row of the side-by-side figures for a set point's pairs: each simulator's summarise()
    row, trials with the same outcome, the paths' difference, physics' time less kinematic's."""
    kin = summarise(setpoint, [p["kinematic"] for p in pairs])
    phys = summarise(setpoint, [p["physics"] for p in pairs])
    diffs = [p["path_diff_mm"] for p in pairs if p["path_diff_mm"] is not None]
    both = [p for p in pairs if p["kinematic"]["success"] and p["physics"]["success"]]
    return {
        "setpoint_cm": setpoint,
        "trials": len(pairs),
        "kinematic": kin,
        "physics": phys,
        "same_outcome": sum(1 for p in pairs if p["kinematic"]["success"] == p["physics"]["success"]),
        "path_diff_mm": round(sum(diffs) / len(diffs), 2) if diffs else None,
        "path_diff_max_mm": max(
            (p["path_diff_max_mm"] for p in pairs if p["path_diff_max_mm"] is not None), default=None
        ),
        "time_diff_s": round(sum(p["physics"]["time_s"] - p["kinematic"]["time_s"] for p in both) / len(both), 2)
        if both
        else None,
    }
