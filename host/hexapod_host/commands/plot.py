"""`hexapod plot gait`: PNG views of the gait engine, drawn from the very core that runs on a board.

Writes into --out (default plots/):
- trajectory.png: seed 003's combined tracks (Fig. 7, Table III's s=5, x=2, z=2 cm) next to
  one foot's path over a cycle of the real walk (side view, mm).
- phases_<gait>.png: which legs are in the air at each tick of two cycles, for each gait.
- top_<gait>.png: the six feet seen from above over one cycle, with the body and its mounts.
"""

import os

from hexapod.gait import NAMES, TRIPOD
from hexapod.units import shown
from hexapod_host.commands import checks
from hexapod_host.commands.cli import UsageError

LEGS = ("1 RF", "2 RM", "3 RR", "4 LR", "5 LM", "6 LF")


def register(sub):
    p = sub.add_parser("plot", help="PNG views (gait: foot trajectories, phase diagrams, top view)")
    p.add_argument("what", choices=("gait",), help="what to plot")
    p.add_argument("--out", default="plots", help="directory for the PNGs (default plots/)")
    p.add_argument("--gait", default="all", help="%s or all (default all)" % ", ".join(NAMES))
    p.add_argument("--speed", default="100", help="forward speed, mm/s (default 100; scaled to what reach allows)")
    p.add_argument("--turn", default="0", help="yaw rate, degrees/s (default 0)")
    p.set_defaults(func=run)


def _options(args):
    from hexapod.limits import SPEED_MAX, YAW_RATE_MAX

    gaits = NAMES if args.gait == "all" else (args.gait,)
    for g in gaits:
        if g not in NAMES:
            raise UsageError("--gait: %s is not one of %s or all" % (shown(args.gait), ", ".join(NAMES)))
    speed = _number("speed", args.speed, 1, SPEED_MAX, "mm/s")  # 0.1 mm/s
    turn = _number("turn", args.turn, 2, YAW_RATE_MAX, "deg/s")  # cdeg/s
    checks.out_dir("--out", args.out)
    return gaits, speed, turn


def _number(name, text, places, limit, unit):
    from hexapod.units import parse_fixed

    try:
        return parse_fixed(text, places, limit, unit)
    except ValueError as err:
        raise UsageError("--%s: %s" % (name, err)) from None


def record(gait_name, speed, turn, cycles=2):
    """Walk the default robot in the core; per tick: feet (mm, body frame) and swing flags."""
    import standing

    import robots.default as robot_file
    from hexapod import geometry, tick
    from hexapod.gait import gait_number

    g = geometry.load(robot_file)
    robot = tick.Robot(g, tick.default_servos(g), tick.FrameBuffer())
    t = 20 * standing.stand(robot, lambda n: robot.tick(20 * n))
    robot.set_gait(gait_number(gait_name))
    robot.walk(speed, 0, turn)
    w = robot.walker
    for _ in range(3 * w.clock.cycle_ticks + 60):  # past the ramp: steady walking
        robot.tick(t)
        t += 20
    while w.phase != 0:
        robot.tick(t)
        t += 20
    rows = []
    for _ in range(cycles * w.clock.cycle_ticks):
        robot.tick(t)
        t += 20
        rows.append(
            (
                [(w.fx[i] / 160.0, w.fy[i] / 160.0, w.fz[i] / 160.0) for i in range(6)],
                [1 if w.su[i] >= 0 else 0 for i in range(6)],
            )
        )
    return g, w, rows


def margin_mm(rows):
    """Smallest static stability margin (mm) of the body centre over the recorded ticks."""
    from hexapod.stability import support_margin

    worst = None
    for feet, swing in rows:
        xs = [round(f[0] * 10) for f in feet]
        ys = [round(f[1] * 10) for f in feet]
        m = support_margin(xs, ys, [1 - s for s in swing])
        worst = m if worst is None or m < worst else worst
    return worst / 10.0


def run(args):
    gaits, speed, turn = _options(args)
    os.makedirs(args.out, exist_ok=True)
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    written = [_trajectory(plt, args.out, speed, turn)]
    for name in gaits:
        g, w, rows = record(name, speed, turn)
        written.append(_phases(plt, args.out, name, w, rows))
        written.append(_top(plt, args.out, name, g, w, rows))
    for path in written:
        print(path)
    return 0


def _arrows(ax, xs, ys, every, color):
    """Direction arrows on a drawn path: one on every `every`-th segment."""
    for k in range(every // 2, len(xs) - 1, every):
        if (xs[k], ys[k]) != (xs[k + 1], ys[k + 1]):
            ax.annotate(
                "",
                xy=(xs[k + 1], ys[k + 1]),
                xytext=(xs[k], ys[k]),
                arrowprops={"arrowstyle": "-|>", "color": color, "lw": 1.5, "mutation_scale": 14},
            )


def _step_labels(ax, pts):
    """Label seed 003's steps without overlap: one label for points that coincide (0 and 20),
    arc points pushed outward from the track's centre, ground points below, staggered when close."""
    cx = (max(p[0] for p in pts) + min(p[0] for p in pts)) / 2
    groups = []
    for k, p in enumerate(pts):
        for g in groups:
            if abs(g[1][0] - p[0]) < 1e-6 and abs(g[1][1] - p[1]) < 1e-6:
                g[0].append(k)
                break
        else:
            groups.append(([k], p))
    ground = sorted((g for g in groups if g[1][1] <= 1e-6), key=lambda g: g[1][0])
    last_x, row = None, 0
    for ks, p in ground:
        row = 1 - row if last_x is not None and p[0] - last_x < 2.5 else 0
        last_x = p[0]
        ax.annotate(
            ", ".join(map(str, ks)), p, textcoords="offset points", xytext=(0, -12 - 10 * row), ha="center", fontsize=7
        )
    for ks, p in groups:
        if p[1] > 1e-6:
            dx = 1 if p[0] >= cx else -1
            ax.annotate(
                ", ".join(map(str, ks)),
                p,
                textcoords="offset points",
                xytext=(7 * dx, 5),
                ha="left" if dx > 0 else "right",
                fontsize=7,
            )


def _trajectory(plt, out, speed, turn):
    from hexapod.trajectory import FINE_BITS, combined_point, sin90_fine

    s = 5
    table = []
    buf = [0, 0, 0]
    for k in range(4 * s + 1):
        combined_point(k, s, 2000000, 0, 2000000, buf, sin90_fine, 1 << FINE_BITS)  # 2 cm in 1e-6 cm
        table.append((buf[0] / 1e5, buf[2] / 1e5))  # mm
    _, w, rows = record(NAMES[TRIPOD], speed, turn, cycles=1)
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
    tx, tz = [p[0] for p in table], [p[1] for p in table]
    a.plot(tx, tz, "o-", ms=4, color="tab:blue")
    _arrows(a, tx, tz, 2, "tab:blue")
    _step_labels(a, table)
    a.set(
        title="seed 003 combined tracks, steps 0-20\n(Table III: s=5, x=z=20 mm)",
        xlabel="fx (mm)",
        ylabel="fz (mm)",
    )
    a.set_ylim(-6, 24)
    a.grid(True)
    x0 = w.nx[0] / 160.0
    xs = [r[0][0][0] - x0 for r in rows]
    zs = [r[0][0][2] for r in rows]
    b.plot(xs, zs, ".-", color="tab:green")
    _arrows(b, xs, zs, 6, "tab:green")
    b.set(
        title="leg 1 (RF) over one tripod cycle\n(swing forward, stance back)",
        xlabel="x from neutral (mm)",
        ylabel="z (mm)",
    )
    b.grid(True)
    fig.tight_layout()
    return _save(fig, plt, out, "trajectory.png")


def _phases(plt, out, name, w, rows):
    fig, ax = plt.subplots(figsize=(10, 3))
    for leg in range(6):
        spans = []
        start = None
        for n, (_, swing) in enumerate(rows + [(None, [0] * 6)]):
            if swing[leg] and start is None:
                start = n
            elif not swing[leg] and start is not None:
                spans.append((start, n - start))
                start = None
        pct = 100.0 / w.clock.cycle_ticks  # one tick in % of the cycle
        ax.broken_barh([(a * pct, n * pct) for a, n in spans], (5 - leg - 0.4, 0.8), color="tab:orange")
    ax.set_yticks(range(6))
    ax.set_yticklabels(list(reversed(LEGS)))
    ax.set(
        title="%s gait: legs in swing (bars) over two cycles of %d ms" % (name, w.clock.cycle_ms),
        xlabel="time (% of the cycle; one tick = 20 ms)",
    )
    ax.set_xlim(0, len(rows) * 100.0 / w.clock.cycle_ticks)
    ax.set_xticks(range(0, 201, 25))
    ax.grid(True, axis="x")
    fig.tight_layout()
    return _save(fig, plt, out, "phases_%s.png" % name)


def _top(plt, out, name, g, w, rows):
    fig, ax = plt.subplots(figsize=(7.6, 6))
    bx = [v / 10.0 for v in g.mount_x] + [g.mount_x[0] / 10.0]
    by = [v / 10.0 for v in g.mount_y] + [g.mount_y[0] / 10.0]
    ax.plot(by, bx, "k-", lw=1)
    half = rows[: len(rows) // 2]
    for leg in range(6):
        ys = [r[0][leg][1] for r in half]
        xs = [r[0][leg][0] for r in half]
        zs = [r[0][leg][2] for r in half]
        down = [r[1][leg] == 0 for r in half]
        ground = min(z for z, d in zip(zs, down, strict=True) if d)
        # Seen from above a swing retraces the stance line: draw it pushed outward by the foot's
        # lift, so the air path shows as an arch beside the ground path.
        out_y = 1 if w.ny[leg] > 0 else -1
        yl = [y + out_y * (z - ground) for y, z in zip(ys, zs, strict=True)]
        (line,) = ax.plot(yl, xs, "-", lw=0.8, label=LEGS[leg])
        c = line.get_color()
        ax.plot(
            [y for y, d in zip(ys, down, strict=True) if d],
            [x for x, d in zip(xs, down, strict=True) if d],
            "o",
            ms=3,
            color=c,
        )
        ax.plot(
            [y for y, d in zip(yl, down, strict=True) if not d],
            [x for x, d in zip(xs, down, strict=True) if not d],
            "o",
            ms=4,
            mfc="white",
            mew=0.8,
            color=c,
        )
        ax.plot([w.ny[leg] / 160.0], [w.nx[leg] / 160.0], "k+", ms=9)
    ax.plot([], [], "o", ms=3, color="grey", label="on the ground")
    ax.plot([], [], "o", ms=4, mfc="white", color="grey", label="in the air (drawn\noutward by its lift)")
    ax.plot([], [], "k+", ms=9, label="neutral foot")
    ax.plot([], [], "k-", lw=1, label="body (coxa mounts)")
    ax.invert_xaxis()  # seen from above with x forward: left (+y) is drawn on the left
    ax.set_aspect("equal")
    ax.set(
        title="%s: feet over one cycle, seen from above\nmin stability margin %.1f mm" % (name, margin_mm(rows)),
        xlabel="y, left (mm)",
        ylabel="x, forward (mm)",
    )
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0)
    fig.tight_layout()
    return _save(fig, plt, out, "top_%s.png" % name)


def _save(fig, plt, out, name):
    """Write a PNG whole or not at all: into a temporary file, then renamed over the name."""
    path = os.path.join(out, name)
    tmp = path + ".part"
    try:
        fig.savefig(tmp, dpi=100, format="png", bbox_inches="tight")
        os.replace(tmp, path)
    except OSError as err:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise UsageError("--out: cannot write %s: %s" % (path, err.strerror or err)) from None
    finally:
        plt.close(fig)
    return path
