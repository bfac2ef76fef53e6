"""Streams played on several gaits at once (`--gait all`): one process per run on every core, a
progress bar on stderr, and the figures as text."""

import os
import sys

from hexapod.gait import NAMES


def one(job):
    """A run: (model, commands, gait, runtime or servo overrides) -> its figures. The kinematic walker
    on runtime "both" runs on CPython and in the VM and says whether every integer agreed; its
    results keep the player's integers under "_rows" (for a plot)."""
    model, commands, gait, extra = job
    if model == "physics":
        from hexapod_host.physics.drive import play

        return play(commands, gait, servo=extra)
    from hexapod_host.drives.play import play

    if extra != "both":
        return play(commands, gait, extra)
    res = play(commands, gait, "cpython")
    vm = play(commands, gait, "micropython")
    res.update(runtime="both", runtimes_identical=res["_rows"] == vm["_rows"])
    return res


def run_all(jobs, progress=False):
    """Each job's figures, in order, the jobs spread over the machine's cores."""
    if len(jobs) == 1:
        return [one(jobs[0])]
    import multiprocessing

    out = []
    with multiprocessing.get_context("spawn").Pool(min(len(jobs), os.cpu_count() or 1)) as pool:
        for k, res in enumerate(pool.imap(one, jobs)):
            out.append(res)
            if progress:
                bar(k + 1, len(jobs), "runs")
    return out


def bar(done, total, what):
    """A 30-character progress bar on stderr, a newline when done."""
    n = done * 30 // total
    sys.stderr.write("\r[%s%s] %d/%d %s" % ("#" * n, "." * (30 - n), done, total, what))
    sys.stderr.write("\n" if done == total else "")
    sys.stderr.flush()


def gaits(spec):
    """--gait's value -> gait numbers: one name, or 'all'."""
    if spec == "all":
        return list(range(len(NAMES)))
    if spec not in NAMES:
        raise ValueError("--gait: %r, allowed %s or all" % (spec, ", ".join(NAMES)))
    return [NAMES.index(spec)]


def report(results):
    """The figures as a Markdown table, one row a run."""
    out = [
        "| gait | model | held share | tracking | peak torque / stall | saturated | max tilt | min margin "
        "| gait changes | refused | faults |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in results:
        out.append(
            "| %s | %s | %.1f %% (%d of %d ticks) | %.3f (%.0f of %.0f mm) | %s | %s | %s | %s | %d | %d | %d |"
            % (
                r["gait"],
                r["model"],
                r["held_share"] * 100,
                r["held_ticks"],
                r["ticks"],
                r["tracking"],
                r["along_mm"],
                r["commanded_mm"],
                _pct(r["peak_torque_share"]),
                _pct(r["saturated_share"]),
                "-" if r["max_tilt_deg"] is None else "%.2f deg" % r["max_tilt_deg"],
                "-" if r["min_stability_margin_mm"] is None else "%.1f mm" % r["min_stability_margin_mm"],
                r["gait_changes"],
                len(r["refused"]),
                r["frame_faults"],
            )
        )
    return "\n".join(out)


def _pct(v):
    return "-" if v is None else "%.1f %%" % (v * 100)
