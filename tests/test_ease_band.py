"""The stance hold's ease band (hexapod.budget.swing_budget, off_band; issue 22, docs/physics.md): a stance foot
may walk past its step, but not further outside the distances from its coxa where its next swing keeps
its whole servo budget. Hand-worked on the default robot's middle right leg, and the steady walks whose
holds grew with time when the hold was only the reach disc."""

import json

import pytest

import robots.default as default_robot
from hexapod import budget, geometry, walk
from hexapod.body import FINE_SHIFT
from hexapod_host import drives
from hexapod_host.drives.play import play

RM = 1  # leg 2: coxa axis at (0, -77.5 mm), pointing -y; neutral foot 130 mm further out


def at(radial, x=0):
    """A body-frame point (fine) radial 0.1 mm from leg 2's coxa axis along its mount, x across it."""
    return x << FINE_SHIFT, (-775 - radial) << FINE_SHIFT


@pytest.fixture
def w():
    w = walk.Walker(geometry.load(default_robot))
    w.srho[RM] = 300  # a 30 mm half stance passed by the servo guard
    budget.swing_budget(w)
    return w


def test_the_band_is_the_neutral_reach_within_the_guards_half_stance(w):
    # 130 mm +- (30 + 1.6 mm): 98.4..161.6 mm from the coxa axis, squared in 0.1 mm.
    assert (w.band[RM + 12], w.band[RM + 18]) == (984 * 984, 1616 * 1616)
    assert (w.band[RM], w.band[RM + 6]) == (0, -775)  # its coxa axis


@pytest.mark.parametrize(
    "now,then,held",
    [
        ((1616, 0), (1617, 0), 1),  # from the outer edge, 0.1 mm past it
        ((1616, 0), (1615, 0), 0),  # back inside
        ((1620, 0), (1620, 100), 1),  # outside, sideways: further out (sqrt(1620^2 + 100^2))
        ((1620, 0), (1619, 0), 0),  # outside, coming back: walks on
        ((984, 0), (983, 0), 1),  # the inner edge (a folded leg), 0.1 mm nearer
        ((980, 0), (981, 0), 0),  # inside it, coming back out
        ((1300, 0), (1300, 300), 0),  # neutral reach, 30 mm across: 130.3 mm, well inside
    ],
)
def test_a_stance_foot_holds_only_going_further_outside_the_band(w, now, then, held):
    w.fx[RM], w.fy[RM] = at(*now)
    w.ax[RM], w.ay[RM] = at(*then)
    assert budget.off_band(w, RM) == held


def stream(*lines):
    return drives.parse("".join(json.dumps(line) + "\n" for line in lines), "test")


@pytest.mark.parametrize("gait,vx,vy", [(1, 300, 0), (2, 0, 300), (2, 200, 200)])
def test_a_steady_walk_at_the_top_speed_holds_only_in_its_start(gait, vx, vy):
    # With the hold at the reach disc alone, the tetrapod forward held 51 ticks in 6 s and 154 in 12 s,
    # the ripple sideways 77 and 188 (docs/physics.md): the feet drifted out. Inside the band they keep
    # their place: whatever the start costs, the next 6 s cost nothing. (The ripple's turned feet may
    # leave the band: a steady walk's feet lifted for the command they walk, so none is turned; with
    # every ripple foot let out of the band the sideways walk held 88 and 147 ticks.)
    held = [
        play(stream({"t_ms": 0, "vx": vx, "vy": vy}, {"t_ms": ms, "stop": True}), gait, "cpython")["held_ticks"]
        for ms in (6000, 12000)
    ]
    assert held[0] == held[1], held


# -- a ripple foot the command turned away from (budget.turned) ----------------------------


def turned_after(w, lift, now, gait=2, leg=RM):
    """budget.turned for leg's foot lifted at command `lift` (vx, vy, yaw), the command now `now`."""
    w.clock.set(gait, 2280)
    for k in range(3):
        w.band[24 + leg + 6 * k] = lift[k]
        w.cmd[k] = now[k]
    return budget.turned(w, leg)


@pytest.mark.parametrize(
    "lift,now,turned",
    [
        ((300, 0, 0), (300, 0, 0), 0),  # the same command
        ((300, 0, 0), (-300, 0, 0), 1),  # a reversal
        ((300, 0, 0), (0, 250, 0), 1),  # forward into sideways: 90 degrees
        ((300, 0, 0), (155, 257, 0), 0),  # 58.9 degrees (cos 0.516): walks on as it was
        ((300, 0, 0), (145, 262, 0), 1),  # 61.0 degrees (cos 0.484)
        ((0, 0, 1000), (400, 0, 0), 1),  # turning in place, then 40 mm/s: 1000 cdeg/s counts as 400
        ((0, 0, 1000), (400, 0, 1000), 0),  # 45 degrees
        ((300, 0, 0), (0, 0, 0), 0),  # stopping: held as before
        ((0, 0, 0), (-300, 0, 0), 0),  # lifted standing (or never lifted)
        ((3000, 3000, 9000), (-3000, -3000, -9000), 1),  # the largest commands: small ints on a board
    ],
)
def test_a_foot_is_turned_past_60_degrees(w, lift, now, turned):
    # cos = lift . now / (|lift| |now|) in (vx, vy, 0.4 yaw), 0.1 mm/s; turned when below 1/2.
    assert turned_after(w, lift, now) == turned


def test_only_the_ripples_feet_are_turned(w):
    for gait in (0, 1, 3):
        assert turned_after(w, (300, 0, 0), (-300, 0, 0), gait) == 0


@pytest.mark.parametrize("lift,held", [((-300, 0, 0), 0), ((300, 0, 0), 1)])
def test_a_turned_ripple_foot_walks_on_past_its_band(w, lift, held):
    # Leg 2 at the band's outer edge going 0.1 mm past it (held above), walking forward at 30 mm/s: a
    # foot that lifted for going backward walks on; one that lifted for forward is held as before.
    w.fx[RM], w.fy[RM] = at(1616)
    w.ax[RM], w.ay[RM] = at(1617)
    turned_after(w, lift, (300, 0, 0))
    assert budget.off_band(w, RM) == held


def test_the_walker_keeps_each_lifts_command():
    # Walker._maybe_lift writes the command in force at each lift-off (plain and viper ticks share it).
    from scenarios import rig

    from hexapod import tick

    g = geometry.load(default_robot)
    robot = tick.Robot(g, tick.default_servos(g), tick.FrameBuffer())
    t = rig.stand(robot)
    w = robot.walker
    assert robot.walk(200, -100, 500) == tick.OK
    lifted = set()
    for k in range(100):
        if k == 50:
            assert robot.walk(-150, 0, 0) == tick.OK
        before = list(w.su)
        assert robot.tick(t) == tick.OK
        t += 20
        for i in range(6):
            if before[i] < 0 <= w.su[i]:
                assert [w.band[24 + i], w.band[30 + i], w.band[36 + i]] == list(w.cmd)
                lifted.add((k >= 50, i))
    assert len(lifted) == 12  # a tripod cycle is 50 ticks: every leg lifted for each command
