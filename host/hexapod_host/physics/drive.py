"""A driver's command stream on the MuJoCo model (`hexapod sim physics --commands FILE`): the stream's
lines asked as the console asks them, Robot.tick's pulses driving the model, and the drive's
figures (hexapod_host.drives.metrics) from the model's body, plus its torque and tilt.

Per tick: the body's move from the free joint (turned into the body frame at mid-tick), whether the
walker held, the command in force (walker.cmd); per 2 ms step each joint's demand kp (target -
angle) against the stall torque; the tilt of the body's z axis from vertical; and the stability
margin of the centre of mass inside the touching feet on ticks whose touching feet are the planned
stance feet (as hexapod_host.physics.sim measures it).
"""

import math

import numpy as np

from hexapod import tick
from hexapod.gait import NAMES, TICK_MS
from hexapod_host.drives import metrics
from hexapod_host.drives.play import end_ticks
from hexapod_host.physics.sim import STEPS_PER_TICK, Run, _margin, load_robot
from hexapod_host.vm.drive_play import ask


def play(commands, gait=0, module=None, servo=None, on_tick=None):
    """The stream on the model from standing in `gait`: the figures as a dict (drives.play's keys)."""
    if module is None:
        import robots.default as module
    g, spec, physics = load_robot(module, servo)
    run = Run(g, spec, physics)
    run.stand()
    r, w = run.robot, run.robot.walker
    if gait != r.gait:
        code = r.set_gait(gait)
        if code:
            raise ValueError("gait %s: %s" % (NAMES[gait], tick.describe(code)))
    ticks = end_ticks(commands, gait)
    m, d, mj = run.model, run.data, run.mj
    kp, stall = run.sm["kp"], run.sm["stall"]
    peak = 0.0
    peak_tick = 0
    saturated = 0
    tilt = 0.0
    faults = 0
    refused = []
    records = []
    # Run._sample's buffers for one sample: position, heading, roll and pitch, centre of mass, feet.
    pos, head, rp, com = np.zeros((1, 3)), np.zeros(1), np.zeros((1, 2)), np.zeros((1, 2))
    feet, down, plan = np.zeros((1, 6, 3)), np.zeros((1, 6), dtype=bool), np.zeros((1, 6), dtype=bool)
    nxt = 0
    for k in range(ticks):
        while nxt < len(commands) and commands[nxt][1] <= TICK_MS * k:
            refused += [(commands[nxt][0], what, code) for what, code in ask(r, commands[nxt])]
            nxt += 1
        held0 = w.held
        x0, y0, yaw0 = run.body_pose()
        run.now += TICK_MS
        if r.tick(run.now):
            faults += 1
        run._targets()
        for _ in range(STEPS_PER_TICK):
            mj.mj_step(m, d)
            demand = np.abs(kp * (d.ctrl - d.qpos[7:]))
            top = float(demand.max())
            if top > peak:
                peak, peak_tick = top, k
            saturated += top > stall
        x1, y1, yaw1 = run.body_pose()
        turn = math.remainder(yaw1 - yaw0, 2 * math.pi)
        mid = yaw0 + turn / 2
        dx = math.cos(mid) * (x1 - x0) + math.sin(mid) * (y1 - y0)
        dy = -math.sin(mid) * (x1 - x0) + math.cos(mid) * (y1 - y0)
        qx, qy = d.qpos[4], d.qpos[5]
        tilt = max(tilt, math.degrees(math.acos(max(-1.0, min(1.0, 1 - 2 * (qx * qx + qy * qy))))))
        run._sample(0, pos, head, rp, com, feet, down, plan)
        margin = None
        if (down[0] == plan[0]).all():
            margin = _margin(feet[0, :, :2], down[0], com[0])
            margin = None if margin is None else float(margin)
        c = w.cmd
        records.append(
            (w.held - held0, c[0] / 10.0, c[1] / 10.0, c[2] / 100.0, dx, dy, math.degrees(turn), w.clock.gait, margin)
        )
        if on_tick is not None:
            on_tick(k, ticks)
    res = metrics.summarise(records, metrics.foot_radius_mm(g))
    matched = sum(1 for rec in records if rec[8] is not None)
    res.update(
        model="physics",
        gait=NAMES[gait],
        seconds=round(ticks * TICK_MS / 1000.0, 2),
        stall_nm=stall,
        peak_torque_nm=round(peak, 3),
        peak_torque_share=round(peak / stall, 4),
        peak_torque_t_ms=peak_tick * TICK_MS,
        saturated_share=round(saturated / (ticks * STEPS_PER_TICK), 4),
        max_tilt_deg=round(tilt, 2),
        margin_ticks_share=round(matched / ticks, 4),
        frame_faults=faults,
        refused=[{"line": ln, "what": what, "code": code} for ln, what, code in refused],
    )
    return res
