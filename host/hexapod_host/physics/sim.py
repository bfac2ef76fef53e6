"""`hexapod sim physics`: the core walks a MuJoCo model of the robot file, and we measure what happens.

Robot.tick runs every 20 ms into a frame sink; the 18 pulses go back through the servo maps
to angles (what a board's servos would be told) and become the model's position targets;
MuJoCo steps 2 ms at a time in between. Measured over whole gait cycles after a settling
time: achieved vs commanded speed and yaw rate (in the body frame), heading drift and
cross-track drift, body height, roll and pitch, each joint's torque demand kp (target -
angle) against the stall torque (peak, 99th percentile, time saturated), foot slip while
down, and the static stability margin on the ticks whose touching feet match the plan.

Physics units are SI floats (m, rad, s, N m); the report is in mm, degrees, N m.
"""

import math
import os
import sys

import standing

from hexapod import geometry as geometry_mod
from hexapod import tick
from hexapod.gait import NAMES, RIPPLE, TICK_MS, TRIPOD, WAVE, gait_number
from hexapod.stability import NO_SUPPORT, support_margin
from hexapod_host.physics import mjcf

STEPS_PER_TICK = int(round(TICK_MS / 1000.0 / mjcf.TIMESTEP_S))
SETTLE_S = 0.4  # standing in the model before the walk command
CONTACT_N = 0.05  # a foot carrying at least this normal force (N) is down
TABLE_GAITS = tuple(NAMES[g] for g in (TRIPOD, RIPPLE, WAVE))  # --table's gaits (docs/physics.md)


def load_robot(module, servo_overrides=None):
    """(Geometry, SERVO, PHYSICS) of a robot module with some SERVO keys replaced; ValueError on bad values."""
    name = getattr(module, "NAME", "robot")
    data = {f: getattr(module, f) for f in dir(module) if f.isupper()}
    servo = dict(getattr(module, "SERVO", None) or {})
    servo.update(servo_overrides or {})
    data["SERVO"] = servo
    g = geometry_mod.from_data(name, data)
    return g, servo, mjcf.check_physics(name, getattr(module, "PHYSICS", None))


class Run:
    """One walk of the model: set up, then step() per tick; results() summarises."""

    def __init__(self, g, servo, physics, *, flip=None):
        self.mj = mjcf.import_mujoco()
        mujoco = self.mj
        self.g = g
        self.sm = mjcf.servo_model(servo)
        self.physics = physics
        self.model = mujoco.MjModel.from_xml_string(mjcf.build(g, servo, physics, flip=flip))
        self.data = mujoco.MjData(self.model)
        self.servos = tick.default_servos(g)
        self.frame = tick.FrameBuffer()
        self.robot = tick.Robot(g, self.servos, self.frame)
        self.foot_r = physics["foot_radius"] * 1e-4
        self.body_id = self.model.body("body").id
        self.foot_geoms = [self.model.geom("foot%d" % (i + 1)).id for i in range(6)]
        self.foot_sites = [self.model.site("foot%d" % (i + 1)).id for i in range(6)]
        self.floor = self.model.geom("floor").id
        self.now = 0

    # -- setting up --------------------------------------------------------------------

    def stand(self):
        """Stand the core up (kinematically), then put the model in that stance and let it settle."""
        r = self.robot
        now = self.now
        self.now += TICK_MS * standing.stand(r, lambda n: r.tick(now + TICK_MS * (n + 1)))
        self.settle()

    def settle(self):
        """Put the model in the stance of the frame's pulses and let it settle (SETTLE_S)."""
        d = self.data
        self.mj.mj_resetData(self.model, d)
        d.qpos[:] = 0
        d.qpos[2] = self.g.body_height * 1e-4 + self.foot_r
        d.qpos[3] = 1.0
        self._targets()
        d.qpos[7:] = d.ctrl
        self.mj.mj_forward(self.model, d)
        for _ in range(int(SETTLE_S / mjcf.TIMESTEP_S)):
            self.mj.mj_step(self.model, d)

    def _targets(self):
        """Pulses of the last frame -> angles through the servo maps -> the actuators' targets (rad)."""
        p = self.frame.pulses
        for k in range(18):
            if p[k]:
                self.data.ctrl[k] = self.servos[k].angle(p[k]) * math.pi / 18000

    def drive(self, pulses):
        """One tick driven from outside: 18 pulses (us, 0 = keep) as the targets, then STEPS_PER_TICK steps."""
        self.frame.write_frame(pulses)
        self._targets()
        for _ in range(STEPS_PER_TICK):
            self.mj.mj_step(self.model, self.data)

    def body_pose(self):
        """The body's plan-view pose: x, y (mm), heading (rad) from the free joint."""
        d = self.data
        qw, qx, qy, qz = d.qpos[3:7]
        yaw = math.atan2(2 * (qw * qz + qx * qy), 1 - 2 * (qy * qy + qz * qz))
        return float(d.qpos[0]) * 1000, float(d.qpos[1]) * 1000, yaw

    # -- the walk ----------------------------------------------------------------------

    def walk(self, gait, vx, vy, yaw, seconds, *, cycle_ms=None, warmup_s=None, on_tick=None):
        """Walk at vx, vy (mm/s), yaw (deg/s) for seconds; measure after warmup_s; returns results()."""
        import numpy as np

        r = self.robot
        # The gait and its cycle in one: a gait the servos cannot swing at one cycle may well be fine at another.
        code = r.set_gait(gait, cycle_ms)
        if code != tick.OK:
            where = " at %d ms" % cycle_ms if cycle_ms is not None else ""
            raise ValueError("gait %s%s: %s" % (NAMES[gait], where, tick.describe(code)))
        code = r.walk(int(round(vx * 10)), int(round(vy * 10)), int(round(yaw * 100)))
        if code != tick.OK:
            raise ValueError("walk: %s" % tick.describe(code))
        w = r.walker
        cycle_s = w.clock.cycle_ms / 1000.0
        if warmup_s is None:
            warmup_s = 0.6 + cycle_s
        cycles = max(1, int((seconds - warmup_s) / cycle_s + 1e-9))
        first = int(round(warmup_s * 1000 / TICK_MS))
        n_ticks = first + int(round(cycles * cycle_s * 1000 / TICK_MS))
        m, d, mj = self.model, self.data, self.mj
        n_steps = (n_ticks - first) * STEPS_PER_TICK
        demand = np.zeros((n_steps, 18))
        pos = np.zeros((n_ticks - first + 1, 3))
        yaw_a = np.zeros(n_ticks - first + 1)
        rp = np.zeros((n_ticks - first + 1, 2))
        com = np.zeros((n_ticks - first + 1, 2))
        feet = np.zeros((n_ticks - first + 1, 6, 3))
        down = np.zeros((n_ticks - first + 1, 6), dtype=bool)
        plan = np.zeros((n_ticks - first + 1, 6), dtype=bool)
        kp = self.sm["kp"]
        faults0 = r.faults
        held0 = w.held
        k = 0
        for t in range(n_ticks):
            if t >= first:
                self._sample(k, pos, yaw_a, rp, com, feet, down, plan)
            self.now += TICK_MS
            r.tick(self.now)
            self._targets()
            for _ in range(STEPS_PER_TICK):
                mj.mj_step(m, d)
                if t >= first:
                    demand[k * STEPS_PER_TICK + _] = kp * (d.ctrl - d.qpos[7:])
            if t >= first:
                k += 1
            if on_tick is not None:
                on_tick(t, n_ticks)
        self._sample(k, pos, yaw_a, rp, com, feet, down, plan)
        return self.results(
            dict(pos=pos, yaw=yaw_a, rp=rp, com=com, feet=feet, down=down, plan=plan, demand=demand),
            faults=r.faults - faults0,
            held=w.held - held0,
            cmd=(vx, vy, yaw),
            gait=gait,
        )

    def _sample(self, k, pos, yaw_a, rp, com, feet, down, plan):
        d = self.data
        pos[k] = d.qpos[0:3]
        qw, qx, qy, qz = d.qpos[3:7]
        yaw_a[k] = math.atan2(2 * (qw * qz + qx * qy), 1 - 2 * (qy * qy + qz * qz))
        rp[k, 0] = math.atan2(2 * (qw * qx + qy * qz), 1 - 2 * (qx * qx + qy * qy))
        rp[k, 1] = math.asin(max(-1.0, min(1.0, 2 * (qw * qy - qz * qx))))
        com[k] = d.subtree_com[self.body_id][0:2]
        for i in range(6):
            feet[k, i] = d.site_xpos[self.foot_sites[i]]
        force = [0.0] * 6
        f6 = self._f6
        for c in range(d.ncon):
            con = d.contact[c]
            for i in range(6):
                if self.foot_geoms[i] in (con.geom1, con.geom2):
                    self.mj.mj_contactForce(self.model, d, c, f6)
                    force[i] += abs(f6[0])
        for i in range(6):
            down[k, i] = force[i] > CONTACT_N
            plan[k, i] = self.robot.walker.su[i] < 0

    @property
    def _f6(self):
        import numpy as np

        if not hasattr(self, "_f6_buf"):
            self._f6_buf = np.zeros(6)
        return self._f6_buf

    # -- the figures -------------------------------------------------------------------

    def results(self, s, *, faults, held, cmd, gait):
        import numpy as np

        dt = TICK_MS / 1000.0
        pos, yaw = s["pos"], np.unwrap(s["yaw"])
        n = len(pos) - 1
        seconds = n * dt
        # Body-frame velocity, averaged tick by tick over whole cycles.
        dp = np.diff(pos[:, :2], axis=0) / dt
        mid = (yaw[:-1] + yaw[1:]) / 2
        c, sn = np.cos(mid), np.sin(mid)
        vbx = float(np.mean(c * dp[:, 0] + sn * dp[:, 1])) * 1000
        vby = float(np.mean(-sn * dp[:, 0] + c * dp[:, 1])) * 1000
        yaw_rate = math.degrees(yaw[-1] - yaw[0]) / seconds
        w = self.robot.walker
        cvx, cvy, cyaw = w.cmd[0] / 10.0, w.cmd[1] / 10.0, w.cmd[2] / 100.0
        c2 = cvx * cvx + cvy * cvy
        speed_ratio = (vbx * cvx + vby * cvy) / c2 if c2 else None
        yaw_ratio = yaw_rate / cyaw if cyaw else None
        # Drift: heading change with no turn asked; cross-track off the commanded line.
        head = math.degrees(yaw[-1] - yaw[0]) if not cyaw else None
        cross = None
        if c2 and not cyaw:
            ux, uy = cvx / math.sqrt(c2), cvy / math.sqrt(c2)
            gx = math.cos(yaw[0]) * ux - math.sin(yaw[0]) * uy
            gy = math.sin(yaw[0]) * ux + math.cos(yaw[0]) * uy
            dx, dy = pos[-1, 0] - pos[0, 0], pos[-1, 1] - pos[0, 1]
            cross = float(abs(dx * gy - dy * gx) * 1000)
        height = (pos[:, 2] - self.foot_r) * 1000
        roll, pitch = np.degrees(np.abs(s["rp"][:, 0])), np.degrees(np.abs(s["rp"][:, 1]))
        dem = np.abs(s["demand"])
        stall = self.sm["stall"]
        peak = dem.max(axis=0)
        p99 = np.percentile(dem, 99, axis=0)
        sat = (dem > stall).mean(axis=0)
        # Foot slip: horizontal travel of a foot down at both ends of a tick.
        down, feet = s["down"], s["feet"]
        both = down[:-1] & down[1:]
        step = np.linalg.norm(np.diff(feet[:, :, :2], axis=0), axis=2) * 1000
        slip_mm = (step * both).sum(axis=0)
        down_s = both.sum(axis=0) * dt
        slip_speed = float(slip_mm.sum() / down_s.sum()) if down_s.sum() else 0.0
        # Stability margin where the touching feet are the planned stance feet.
        match = (down == s["plan"]).all(axis=1)
        margins = [_margin(feet[k, :, :2], down[k], s["com"][k]) for k in range(len(pos)) if match[k]]
        margins = [v for v in margins if v is not None]
        joints = []
        for i in range(6):
            for j in range(3):
                q = 3 * i + j
                joints.append(
                    {
                        "joint": "%s%d" % (mjcf.JOINTS[j], i + 1),
                        "peak_nm": round(float(peak[q]), 3),
                        "p99_nm": round(float(p99[q]), 3),
                        "saturated_pct": round(float(sat[q]) * 100, 2),
                    }
                )
        return {
            "gait": NAMES[gait],
            "seconds": round(seconds, 2),
            "asked": {"vx_mm_s": cmd[0], "vy_mm_s": cmd[1], "yaw_deg_s": cmd[2]},
            "commanded": {"vx_mm_s": cvx, "vy_mm_s": cvy, "yaw_deg_s": cyaw, "scale_permille": w.scale_permille},
            "achieved": {"vx_mm_s": round(vbx, 2), "vy_mm_s": round(vby, 2), "yaw_deg_s": round(yaw_rate, 3)},
            "speed_ratio": None if speed_ratio is None else round(speed_ratio, 4),
            "yaw_ratio": None if yaw_ratio is None else round(yaw_ratio, 4),
            "heading_drift_deg": None if head is None else round(head, 3),
            "cross_track_mm": None if cross is None else round(cross, 2),
            "height_mm": {
                "asked": self.g.body_height / 10.0,
                "mean": round(float(height.mean()), 2),
                "min": round(float(height.min()), 2),
                "max": round(float(height.max()), 2),
            },
            "roll_deg_max": round(float(roll.max()), 3),
            "pitch_deg_max": round(float(pitch.max()), 3),
            "stall_nm": stall,
            "torque_peak_nm": round(float(peak.max()), 3),
            "torque_p99_nm": round(float(p99.max()), 3),
            "saturated_pct": round(float((dem > stall).any(axis=1).mean()) * 100, 2),
            "joints": joints,
            "slip_mm_per_s_down": round(slip_speed, 2),
            "slip_mm_per_foot": [round(float(v), 1) for v in slip_mm],
            "plan_match_pct": round(float(match.mean()) * 100, 1),
            "margin_min_mm": None if not margins else round(min(margins), 1),
            "frame_faults": faults,
            "held_ticks": held,
        }


def _margin(xy, down, com):
    """Distance (mm) of com inside the polygon of the down feet (xy, com in m): the firmware's own
    hexapod.stability.support_margin on the feet rounded to 0.1 mm; None with fewer than three down."""
    m = support_margin(
        [round(float(x) * 10000) for x in xy[:, 0]],
        [round(float(y) * 10000) for y in xy[:, 1]],
        [bool(d) for d in down],
        round(float(com[0]) * 10000),
        round(float(com[1]) * 10000),
    )
    return None if m == NO_SUPPORT else m / 10


def simulate(
    module=None,
    *,
    gait=NAMES[TRIPOD],
    speed=60.0,
    direction=0.0,
    turn=0.0,
    seconds=6.0,
    cycle_ms=None,
    servo=None,
    flip=None,
    render=None,
    progress=False,
):
    """One walk of a robot file's model; returns the results dict (see Run.results)."""
    if module is None:
        import robots.default as module
    g, spec, physics = load_robot(module, servo)
    run = Run(g, spec, physics, flip=flip)
    run.stand()
    a = math.radians(direction)
    on_tick = None
    rec = None
    if render is not None:
        rec = Recorder(run, render)
        on_tick = rec.tick
    if progress:
        on_tick = _progress(on_tick)
    res = run.walk(
        gait_number(gait), speed * math.cos(a), speed * math.sin(a), turn, seconds, cycle_ms=cycle_ms, on_tick=on_tick
    )
    if rec is not None:
        res["render"] = rec.finish()
    return res


def _progress(inner):
    def on_tick(t, n):
        if inner is not None:
            inner(t, n)
        if t % 25 == 0 or t == n - 1:
            done = (t + 1) * 30 // n
            sys.stderr.write("\r[%s%s] %d/%d ticks" % ("#" * done, "." * (30 - done), t + 1, n))
            if t == n - 1:
                sys.stderr.write("\n")
            sys.stderr.flush()

    return on_tick


_RENDER_MISSING = []


def render_missing():
    """None if MuJoCo can render offscreen here, else why not (for a test's skip reason)."""
    if not _RENDER_MISSING:
        try:
            mj = mjcf.import_mujoco()
            mj.Renderer(mj.MjModel.from_xml_string("<mujoco/>"), 8, 8).close()
            _RENDER_MISSING.append(None)
        except Exception as exc:  # each GL backend fails its own way, at import or at context creation
            _RENDER_MISSING.append("no offscreen rendering (MUJOCO_GL=%s): %s" % (os.environ.get("MUJOCO_GL"), exc))
    return _RENDER_MISSING[0]


class Recorder:
    """PNG frames (every other tick: 25 per second) and an animated GIF of a run, offscreen."""

    def __init__(self, run, folder, width=320, height=240, every=2):
        self.run = run
        self.folder = folder
        self.every = every
        os.makedirs(folder, exist_ok=True)
        self.renderer = run.mj.Renderer(run.model, height, width)
        cam = run.mj.MjvCamera()
        cam.type = run.mj.mjtCamera.mjCAMERA_TRACKING
        cam.trackbodyid = run.body_id
        cam.distance = 0.75
        cam.elevation = -22
        cam.azimuth = 120
        self.cam = cam
        self.frames = []

    def tick(self, t, n):
        if t % self.every:
            return
        self.renderer.update_scene(self.run.data, self.cam)
        from PIL import Image

        img = Image.fromarray(self.renderer.render())
        path = os.path.join(self.folder, "frame_%04d.png" % len(self.frames))
        img.save(path)
        self.frames.append(img)

    def finish(self):
        gif = os.path.join(self.folder, "walk.gif")
        if self.frames:
            # 48 colours: the floor, the robot and its shadow need no more, and the file shrinks ~3x.
            from PIL import Image

            frames = [f.quantize(colors=48, method=Image.Quantize.MEDIANCUT) for f in self.frames]
            frames[0].save(
                gif, save_all=True, append_images=frames[1:], duration=TICK_MS * self.every, loop=0, optimize=True
            )
        self.renderer.close()
        return {"folder": self.folder, "png_frames": len(self.frames), "gif": gif}


TABLE_CASES = [
    (gait, label, kw)
    for gait in TABLE_GAITS
    for label, kw in (
        ("60 mm/s", dict(speed=60.0)),
        ("120 mm/s", dict(speed=120.0)),
        ("turn 30 deg/s", dict(turn=30.0)),
    )
]


def _table_case(job):
    gait, label, kw, servo, cycle_ms = job
    res = simulate(gait=gait, seconds=8.0, servo=servo, cycle_ms=cycle_ms, **dict(dict(speed=0.0), **kw))
    res.pop("joints")
    return dict(case=label, **res)


def table(*, servo=None, cycle_ms=None, progress=False):
    """The README's table: each gait at 60 and 120 mm/s and turning at 30 deg/s, 8 s each, on every core."""
    import multiprocessing

    jobs = [(g, label, kw, servo, cycle_ms) for g, label, kw in TABLE_CASES]
    rows = []
    with multiprocessing.get_context("spawn").Pool(min(len(jobs), os.cpu_count() or 1)) as pool:
        for k, row in enumerate(pool.imap(_table_case, jobs)):
            rows.append(row)
            if progress:
                done = (k + 1) * 30 // len(jobs)
                sys.stderr.write("\r[%s%s] %d/%d walks" % ("#" * done, "." * (30 - done), k + 1, len(jobs)))
                sys.stderr.write("\n" if k + 1 == len(jobs) else "")
                sys.stderr.flush()
    return rows


def format_table(rows):
    """Rows of table() as a Markdown table."""
    out = [
        "| gait | case | commanded | achieved | peak torque | saturated |",
        "|---|---|---|---|---|---|",
    ]
    for r in rows:
        turn = r["yaw_ratio"] is not None
        c = r["commanded"]["yaw_deg_s"] if turn else r["commanded"]["vx_mm_s"]
        ratio = r["yaw_ratio"] if turn else r["speed_ratio"]
        unit = "deg/s" if turn else "mm/s"
        values = (r["gait"], r["case"], c, unit, ratio * 100, r["torque_peak_nm"], r["saturated_pct"])
        out.append("| %s | %s | %.1f %s | %.1f %% | %.2f N m | %.1f %% |" % values)
    return "\n".join(out)


def report(res):
    """The results as a few lines of text."""
    c, a = res["commanded"], res["achieved"]
    lines = [
        "%s, %.1f s measured (whole cycles after settling)" % (res["gait"], res["seconds"]),
        "commanded   vx %7.1f  vy %7.1f mm/s  yaw %6.2f deg/s  (%d permille of the request)"
        % (c["vx_mm_s"], c["vy_mm_s"], c["yaw_deg_s"], c["scale_permille"]),
        "achieved    vx %7.1f  vy %7.1f mm/s  yaw %6.2f deg/s" % (a["vx_mm_s"], a["vy_mm_s"], a["yaw_deg_s"]),
    ]
    if res["speed_ratio"] is not None:
        lines.append("speed       %.1f %% of commanded" % (res["speed_ratio"] * 100))
    if res["yaw_ratio"] is not None:
        lines.append("yaw rate    %.1f %% of commanded" % (res["yaw_ratio"] * 100))
    if res["heading_drift_deg"] is not None:
        lines.append("drift       heading %.2f deg" % res["heading_drift_deg"])
    if res["cross_track_mm"] is not None:
        lines[-1] += ", %.1f mm off the line" % res["cross_track_mm"]
    h = res["height_mm"]
    lines += [
        "height      mean %.1f mm (asked %.1f, %.1f..%.1f)" % (h["mean"], h["asked"], h["min"], h["max"]),
        "tilt        roll max %.2f deg, pitch max %.2f deg" % (res["roll_deg_max"], res["pitch_deg_max"]),
        "torque      demand peak %.2f N m, p99 %.2f N m, stall %.2f N m; saturated %.1f %% of the time"
        % (res["torque_peak_nm"], res["torque_p99_nm"], res["stall_nm"], res["saturated_pct"]),
    ]
    for j in range(3):
        rows = [r for r in res["joints"] if r["joint"].startswith(mjcf.JOINTS[j])]
        worst = max(rows, key=lambda r: r["peak_nm"])
        lines.append(
            "  %-6s    peak %.2f N m (%s), p99 %.2f N m, saturated %.1f %%"
            % (
                mjcf.JOINTS[j],
                worst["peak_nm"],
                worst["joint"],
                max(r["p99_nm"] for r in rows),
                max(r["saturated_pct"] for r in rows),
            )
        )
    lines += [
        "foot slip   %.1f mm/s while down" % res["slip_mm_per_s_down"],
        "stability   min margin %s mm on the %.0f %% of ticks whose touching feet match the plan"
        % ("-" if res["margin_min_mm"] is None else "%.1f" % res["margin_min_mm"], res["plan_match_pct"]),
        "frames      %d faults, %d held ticks" % (res["frame_faults"], res["held_ticks"]),
    ]
    if "render" in res:
        lines.append("render      %d PNG frames and %s" % (res["render"]["png_frames"], res["render"]["gif"]))
    return "\n".join(lines)
