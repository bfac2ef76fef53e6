"""hexapod.pid stepped through a sequence of samples."""

from hexapod import pid


def updates(gains, samples):
    """Per (gains, out_max, i_max): the output and the integral after each (setpoint, measurement, ms) sample."""
    out = []
    for g, om, im in gains:
        p = pid.PID(*g, out_max=om, i_max=im)
        for sp, m, t in samples:
            out.append(p.update(sp, m, t))
            out.append(p.i)
    return out
