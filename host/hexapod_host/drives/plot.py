"""`hexapod sim kinematics --commands FILE --plot FILE.png`: the stream asked, and per gait the commanded
distance against the distance along the commanded path (docs/motion.md "Following a driver"), the
held ticks shaded: where the holds fall and what they cost."""

import math
import os

from hexapod.gait import TICK_MS
from hexapod_host.drives.play import records

DT = TICK_MS / 1000.0


def figure(commands, results, radius_mm):
    """A matplotlib figure: the asked command on top, one panel per result (kinematic, with "_rows")."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(len(results) + 1, 1, figsize=(11, 2.2 * (len(results) + 1)), sharex=True, squeeze=False)
    axes = axes[:, 0]
    t = [c[1] / 1000.0 for c in commands]
    for k, label in ((2, "vx asked, mm/s"), (3, "vy asked, mm/s"), (4, "yaw asked, deg/s")):
        scale = 100.0 if k == 4 else 10.0
        axes[0].step(t, [c[k] / scale for c in commands], where="post", label=label)
    axes[0].legend(loc="upper right", fontsize=7)
    axes[0].set_title("the stream as asked", fontsize=9)
    for ax, res in zip(axes[1:], results, strict=True):
        asked, along, held = [], [], []
        total_c = total_a = 0.0
        for rec in records(res["_rows"]):
            # metrics.summarise's sums, kept tick by tick
            arc = radius_mm * math.radians(rec[3])
            size = math.sqrt(rec[1] * rec[1] + rec[2] * rec[2] + arc * arc)
            if size:
                total_c += size * DT
                total_a += (rec[4] * rec[1] + rec[5] * rec[2] + radius_mm * math.radians(rec[6]) * arc) / size
            asked.append(total_c)
            along.append(total_a)
            held.append(rec[0])
        ticks = [k * DT for k in range(len(asked))]
        ax.plot(ticks, asked, label="commanded distance (after the gait's scaling)")
        ax.plot(ticks, along, label="along the commanded path")
        for k, h in enumerate(held):
            if h:
                ax.axvspan(ticks[k], ticks[k] + DT, color="red", alpha=0.25, lw=0)
        ax.set_ylabel("mm")
        ax.legend(loc="upper left", fontsize=7)
        ax.set_title(
            "%s: held %.1f %% of ticks (red), tracking %.3f" % (res["gait"], 100 * res["held_share"], res["tracking"]),
            fontsize=9,
        )
    axes[-1].set_xlabel("s")
    fig.tight_layout()
    return fig


def write(path, commands, results, radius_mm):
    """figure() written to path whole or not at all."""
    import matplotlib.pyplot as plt

    fig = figure(commands, results, radius_mm)
    tmp = path + ".part"
    fig.savefig(tmp, format="png", dpi=80)
    plt.close(fig)
    os.replace(tmp, path)
