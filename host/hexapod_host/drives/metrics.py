"""What a drive measures, the same for the kinematic walker and the MuJoCo model (docs/motion.md,
"Following a driver").

One record a 20 ms tick: (held, cvx, cvy, cyaw, dx, dy, dpsi, gait, margin)
- held: 1 when the walker held the body still this tick (walker.held grew), else 0;
- cvx, cvy (mm/s), cyaw (deg/s): the command in force, after the gait's own scaling (walker.cmd);
- dx, dy (mm): the body's move this tick in its own frame at mid-tick, dpsi (deg) its turn;
- gait: the gait walked (a number); margin (mm): static stability margin, None if not measured.

tracking: each tick's command is a planar twist; its turn counts as the arc R * yaw that a foot at
the mean neutral-foot radius R sweeps, so that turning in place is a distance like walking. The
commanded distance is sum |c| dt, c = (cvx, cvy, R cyaw); the distance along the commanded path is
the body's move projected on c's direction, sum (dx cvx + dy cvy + R^2 dpsi cyaw) / |c| (a move
against the command counts negative), both over the ticks with a command. tracking = along /
commanded; with nothing commanded it is 1.0 (nothing asked, nothing owed). held_commanded_mm: the
commanded distance of the held ticks (what the holds cost at most).
"""

import math

from hexapod.gait import TICK_MS

DT = TICK_MS / 1000.0


def foot_radius_mm(g):
    """Mean distance (mm) of the six neutral feet from the body centre: the arc radius that turns a
    yaw rate into a foot speed for tracking."""
    xy = [0, 0]
    total = 0.0
    for i in range(6):
        g.neutral_xy(i, xy)
        total += math.hypot(xy[0], xy[1]) / 10.0
    return total / 6


def summarise(records, radius_mm):
    """The drive's figures from its tick records (module docstring); a dict of plain values."""
    n = len(records)
    held = sum(r[0] for r in records)
    commanded = along = lost = 0.0
    changes = 0
    margins = []
    last_gait = records[0][7] if records else None
    for held_k, cvx, cvy, cyaw, dx, dy, dpsi, gait, margin in records:
        arc = radius_mm * math.radians(cyaw)
        size = math.sqrt(cvx * cvx + cvy * cvy + arc * arc)
        if size:
            commanded += size * DT
            lost += size * DT * held_k
            along += (dx * cvx + dy * cvy + radius_mm * math.radians(dpsi) * arc) / size
        if gait != last_gait:
            changes += 1
            last_gait = gait
        if margin is not None:
            margins.append(margin)
    return {
        "ticks": n,
        "held_ticks": held,
        "held_share": round(held / n, 4) if n else 0.0,
        "commanded_mm": round(commanded, 1),
        "along_mm": round(along, 1),
        "held_commanded_mm": round(lost, 1),
        "tracking": round(along / commanded, 4) if commanded else 1.0,
        "gait_changes": changes,
        "min_stability_margin_mm": round(min(margins), 1) if margins else None,
        "foot_radius_mm": round(radius_mm, 1),
    }
