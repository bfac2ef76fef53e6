"""`hexapod plot gait`: PNG views of the gait engine, drawn from the very core that runs on a board.

Writes into --out (default plots/):
- trajectory.png: seed 003's combined tracks (Fig. 7, Table III's s=5, x=2, z=2 cm) next to
  one foot's path over a cycle of the real walk (side view, mm).
- phases_<gait>.png: which legs are in the air at each tick of two cycles, for each gait.
- top_<gait>.png: the six feet seen from above over one cycle, with the body and its mounts.
"""

import os

from hexapod_host.cli import UsageError

GAITS = ("tripod", "tetrapod", "ripple", "wave")
LEGS = ("1 RF", "2 RM", "3 RR", "4 LR", "5 LM", "6 LF")


def register(sub):
    p = sub.add_parser("plot", help="PNG views (gait: foot trajectories, phase diagrams, top view)")
    p.add_argument("what", choices=("gait",), help="what to plot")
    p.add_argument("--out", default="plots", help="directory for the PNGs (default plots/)")
    p.add_argument("--gait", default="all", help="tripod, tetrapod, ripple, wave or all (default all)")
    p.add_argument("--speed", default="100", help="forward speed, mm/s (default 100; scaled to what reach allows)")
    p.add_argument("--turn", default="0", help="yaw rate, degrees/s (default 0)")
    p.set_defaults(func=run)


def _options(args):
    from hexapod.units import parse_fixed
    from hexapod.walk import SPEED_MAX, YAW_RATE_MAX

    gaits = GAITS if args.gait == "all" else (args.gait,)
    for g in gaits:
        if g not in GAITS:
            raise UsageError("--gait: %r is not one of %s or all" % (args.gait, ", ".join(GAITS)))
    try:
        speed = parse_fixed(args.speed, 1)  # mm/s -> 0.1 mm/s
        turn = parse_fixed(args.turn, 2)  # deg/s -> cdeg/s
    except ValueError as err:
        raise UsageError("--speed/--turn: %s" % err) from None
    if abs(speed) > SPEED_MAX:
        raise UsageError("--speed: %s mm/s is outside -%d..%d mm/s" % (args.speed, SPEED_MAX // 10, SPEED_MAX // 10))
    if abs(turn) > YAW_RATE_MAX:
        raise UsageError(
            "--turn: %s deg/s is outside -%d..%d deg/s" % (args.turn, YAW_RATE_MAX // 100, YAW_RATE_MAX // 100)
        )
    if os.path.exists(args.out) and not os.path.isdir(args.out):
        raise UsageError("--out: %r exists and is not a directory" % args.out)
    return gaits, speed, turn


def record(gait_name, speed, turn, cycles=2):
    """Walk the default robot in the core; per tick: feet (mm, body frame) and swing flags."""
    import robots.default as robot_file
    from hexapod import geometry, tick
    from hexapod.gait import gait_number

    g = geometry.load(robot_file)
    robot = tick.Robot(g, tick.default_servos(g), tick.FrameBuffer())
    t = 0
    robot.stand_up()
    while robot.mode != tick.STANDING:
        robot.tick(t)
        t += 20
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
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    os.makedirs(args.out, exist_ok=True)
    written = [_trajectory(plt, args.out, speed, turn)]
    for name in gaits:
        g, w, rows = record(name, speed, turn)
        written.append(_phases(plt, args.out, name, w, rows))
        written.append(_top(plt, args.out, name, g, w, rows))
    for path in written:
        print(path)
    return 0


def _trajectory(plt, out, speed, turn):
    from hexapod.trajectory import FINE_BITS, combined_point, sin90_fine

    s = 5
    table = []
    buf = [0, 0, 0]
    for k in range(4 * s + 1):
        combined_point(k, s, 2000000, 0, 2000000, buf, sin90_fine, 1 << FINE_BITS)
        table.append((buf[0] / 1e6, buf[2] / 1e6))
    _, w, rows = record("tripod", speed, turn, cycles=1)
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4))
    a.plot([p[0] for p in table], [p[1] for p in table], "o-")
    for k, p in enumerate(table):
        a.annotate(str(k), p, textcoords="offset points", xytext=(3, 3), fontsize=7)
    a.set(title="seed 003 combined tracks (Table III: s=5, x=2, z=2)", xlabel="fx (cm)", ylabel="fz (cm)")
    a.grid(True)
    x0 = w.nx[0] / 160.0
    xs = [r[0][0][0] - x0 for r in rows]
    zs = [r[0][0][2] for r in rows]
    b.plot(xs, zs, ".-")
    b.set(title="leg 1 (RF) over one tripod cycle, smooth touch-down", xlabel="x from neutral (mm)", ylabel="z (mm)")
    b.grid(True)
    fig.tight_layout()
    path = os.path.join(out, "trajectory.png")
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


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
        ax.broken_barh(spans, (5 - leg - 0.4, 0.8), color="tab:orange")
    ax.set_yticks(range(6))
    ax.set_yticklabels(list(reversed(LEGS)))
    ax.set(
        title="%s gait: legs in swing (bars) over two cycles of %d ms" % (name, w.clock.cycle_ms),
        xlabel="tick (20 ms)",
    )
    ax.set_xlim(0, len(rows))
    ax.grid(True, axis="x")
    fig.tight_layout()
    path = os.path.join(out, "phases_%s.png" % name)
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def _top(plt, out, name, g, w, rows):
    fig, ax = plt.subplots(figsize=(6, 6))
    bx = [v / 10.0 for v in g.mount_x] + [g.mount_x[0] / 10.0]
    by = [v / 10.0 for v in g.mount_y] + [g.mount_y[0] / 10.0]
    ax.plot(by, bx, "k-", lw=1)
    half = rows[: len(rows) // 2]
    for leg in range(6):
        ys = [r[0][leg][1] for r in half]
        xs = [r[0][leg][0] for r in half]
        down = [r[1][leg] == 0 for r in half]
        (line,) = ax.plot(ys, xs, "-", lw=0.8, label=LEGS[leg])
        on_ground = [(y, x) for y, x, d in zip(ys, xs, down, strict=True) if d]
        ax.plot([p[0] for p in on_ground], [p[1] for p in on_ground], ".", ms=3, color=line.get_color())
        ax.plot([w.ny[leg] / 160.0], [w.nx[leg] / 160.0], "k+")
    ax.invert_xaxis()  # seen from above with x forward: left (+y) is drawn on the left
    ax.set_aspect("equal")
    ax.set(
        title="%s: feet over one cycle (dots: on the ground)\nmin stability margin %.1f mm" % (name, margin_mm(rows)),
        xlabel="y, left (mm)",
        ylabel="x, forward (mm)",
    )
    ax.legend(fontsize=7, loc="center")
    fig.tight_layout()
    path = os.path.join(out, "top_%s.png" % name)
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path
