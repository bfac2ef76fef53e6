"""Abrupt commands the walker accepts, in MuJoCo: no servo past its stall torque in any gait, and
the tripod within the issue's 80 % (docs/physics.md, "Command reversals and the stance hold").
The stall torque comes from the robot file's datasheet figure (MG996R class, 1.1 N m)."""

import random

import numpy as np
import pytest

import robots.default as d
from hexapod import tick
from hexapod_host.physics import sim as sp

# forward <-> backward, sideways <-> forward, yaw flips, mixed (0.1 mm/s, cdeg/s), twice over.
COMMANDS = [(600, 0, 0), (-600, 0, 0), (0, 600, 0), (600, 0, 0), (0, -600, 0), (0, 0, 3000), (0, 0, -3000)]
COMMANDS += [(600, 0, 2000), (-600, 0, -2000)]


def peak_demand(gait, hold_stance=True, budget=True):
    """Largest kp x (target - angle) of any joint over every 2 ms step (N m), and the stall (N m).
    hold_stance False: no hold short of the reach disc; budget False: no swing shortened (hexapod.budget)."""
    from hexapod import walk

    if not budget:
        real = walk.in_budget
        walk.in_budget = lambda walker, i, t, cv: 0
    try:
        return _peak_demand(gait, hold_stance)
    finally:
        if not budget:
            walk.in_budget = real


def _peak_demand(gait, hold_stance):
    g, spec, physics = sp.load_robot(d)
    run = sp.Run(g, spec, physics)
    run.stand()
    r = run.robot
    assert r.set_gait(sp.gait_number(gait), None) == tick.OK
    rng = random.Random(1)
    kp, peak = run.sm["kp"], 0.0
    for seg in range(2 * len(COMMANDS)):
        assert r.walk(*COMMANDS[seg % len(COMMANDS)]) == tick.OK
        for _ in range(rng.randint(8, 60)):
            if not hold_stance:  # no hold short of the reach disc (the ease band's undone)
                for i in range(6):
                    r.walker.band[i + 12] = 0
                    r.walker.band[i + 18] = 1 << 30
            run.now += sp.TICK_MS
            r.tick(run.now)
            run._targets()
            for _ in range(sp.STEPS_PER_TICK):
                run.mj.mj_step(run.model, run.data)
                peak = max(peak, float(np.abs(kp * (run.data.ctrl - run.data.qpos[7:])).max()))
    assert r.faults == 0
    return peak, spec["stall_torque_mnm"] / 1000.0


@pytest.mark.parametrize("gait", ["tripod", "tetrapod", "ripple", "wave"])
def test_abrupt_commands_never_saturate_a_servo(gait):
    # Measured 2026-11-23 on these 18 segments: 0.865 / 0.727 / 0.799 / 0.637 N m (tripod 78.6 %).
    peak, stall = peak_demand(gait)
    assert peak < stall
    if gait == "tripod":
        assert peak <= 0.8 * stall


def test_without_the_stance_hold_and_the_swing_budget_the_tetrapod_saturates():
    # Teeth: the same commands with the hold undone and no swing shortened: 1.154 N m measured, 105 %
    # of stall (the walker before the hold).
    peak, stall = peak_demand("tetrapod", hold_stance=False, budget=False)
    assert peak > stall


def test_the_swing_budget_alone_keeps_the_tetrapod_under_stall():
    # The hold undone, the swing budget on (issue 22's planner, hexapod.budget): 0.736 N m measured
    # (67 % of stall). The tripod, the same way, peaks at 0.893 N m: past the 80 % goal, under the
    # stall; on three feet the hold is what keeps it there.
    peak, stall = peak_demand("tetrapod", hold_stance=False)
    assert peak < 0.8 * stall
