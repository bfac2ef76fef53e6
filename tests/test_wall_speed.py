"""`hexapod sim wall`'s top_speed_share (issue 22 point 5): the mean speed along the wall between start
and finish against the gait's top accepted speed, beside time_s."""

import json

import pytest

from hexapod_host.commands import cli
from hexapod_host.wall import sim
from hexapod_host.wall.world import load


def test_the_top_accepted_speed_is_the_tripods_48_3_mm_s():
    # docs/physics.md "Servo speed guard": the tripod at its 1.0 s cycle, 48.3 mm/s forward at most.
    assert sim.top_speed_mm_s() == 48.3


def test_the_wall_course_is_1_5_m():
    # wall.json: start 20 cm along the wall, finish line at 170 cm: 1,500 mm (the same in gap.json).
    for name in ("wall", "gap"):
        trial = sim.Trial(load(name), 12, 0, disturb=False, max_frames=0)
        try:
            assert trial.result()["course_mm"] == 1500.0
        finally:
            trial.close()


def test_the_share_from_the_mean_time_worked_by_hand():
    # Two successes over 1,500 mm in 40 s and 50 s: mean time 45 s, 1500 / 45 = 33.33 mm/s,
    # / 48.3 = 0.6901 (issue 22: 44.6-45.5 s is about 69 % of the tripod's top speed).
    ok = [{"course_mm": 1500.0, "time_s": 40.0}, {"course_mm": 1500.0, "time_s": 50.0}]
    got = sim.speed_share(ok)
    assert got["mean_speed_mm_s"] == pytest.approx(33.33, abs=0.005)
    assert got["top_speed_share"] == pytest.approx(1500 / 45 / 48.3, abs=1e-4)
    assert sim.speed_share([]) == {"mean_speed_mm_s": None, "top_speed_mm_s": None, "top_speed_share": None}


def test_cli_json_reports_it_beside_time_s(capsys):
    assert cli.main(["sim", "wall", "--world", "gap", "--trials", "1", "--json", "--jobs", "1"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["success_rate"] == 1.0
    assert out["top_speed_share"] == pytest.approx(1500 / out["time_s"] / 48.3, abs=1e-3)
    assert out["rows"][0]["top_speed_share"] == out["top_speed_share"]


def test_the_follower_walks_the_wall_at_90_percent_of_top_speed():
    # Issue 22 point 5's goal (>= 90 % of the tripod's 48.3 mm/s along the 1.5 m wall), on three
    # disturbed trials of `sim wall --seed 5` at 12 cm. On main d7dc18d (the PID on the raw pair) the
    # sonars' noise turned the robot about 10 deg/s on average and these took 42.0-43.3 s (share 0.730);
    # with the estimate (1/8 a sample) 34.2-34.5 s (0.904). The trials are seeded: the same every run.
    world = load("wall")
    results = [
        sim.run_trial(world, 12, sim.trial_seed(5, "wall", 12, k), bus="sink", max_frames=2500) for k in range(3)
    ]
    assert all(r["success"] for r in results), [r["why"] for r in results]
    assert sim.speed_share(results)["top_speed_share"] >= 0.9


def test_crab_walks_the_wall_at_90_percent_of_top_speed_at_8_cm():
    # The same goal at the nearest set point, on `make sim`'s own first four 8 cm trials (seed 0), in
    # the form `sim wall` uses by default. Form yaw, whose every turn costs forward speed, took
    # 38.5, 34.24, 31.6 and 39.0 s on them (share 0.8666; the 8 cm row of the README, 10 trials: 88 %);
    # crab walks sideways to the set point and turns only past its 4 degree band.
    assert sim.FORM == "crab"
    world = load("wall")
    results = {
        form: [
            sim.run_trial(world, 8, sim.trial_seed(0, "wall", 8, k), bus="sink", form=form, max_frames=2500)
            for k in range(4)
        ]
        for form in ("yaw", "crab")
    }
    for form, rs in results.items():
        assert all(r["success"] for r in rs), (form, [r["why"] for r in rs])
    assert sim.speed_share(results["yaw"])["top_speed_share"] < 0.9
    assert sim.speed_share(results["crab"])["top_speed_share"] >= 0.9
