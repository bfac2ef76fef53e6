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


@pytest.mark.parametrize("gait,vx,vy", [(1, 300, 0), (2, 0, 300)])
def test_a_steady_walk_at_the_top_speed_holds_only_in_its_start(gait, vx, vy):
    # With the hold at the reach disc alone, the tetrapod forward held 51 ticks in 6 s and 154 in 12 s,
    # the ripple sideways 77 and 188 (docs/physics.md): the feet drifted out. Inside the band they keep
    # their place: whatever the start costs, the next 6 s cost nothing.
    held = [
        play(stream({"t_ms": 0, "vx": vx, "vy": vy}, {"t_ms": ms, "stop": True}), gait, "cpython")["held_ticks"]
        for ms in (6000, 12000)
    ]
    assert held[0] == held[1], held
