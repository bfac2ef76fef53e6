"""`hexapod sim wall --physics`: the wall simulator's body moved by MuJoCo against the stance-feet
arithmetic. Expectations: the gait's own numbers (speed x cycle per stride), the kinematic
simulator's disturbance model (the bounds below sit inside it), FK of the joint angles (float
oracle), hand-made paths."""

import json
import math

import pytest

from hexapod_host.commands import cli
from hexapod_host.wall import physics as wall_physics
from hexapod_host.wall import rig as wall_rig
from hexapod_host.wall import sim as sim_wall
from hexapod_host.wall import world
from hexapod_host.wall.room import Body

SHORT = {  # a 40 cm walk along a straight wall: trials of ~5 s
    "walls": [[0, 0, 100, 0]],
    "follow": "left",
    "start": {"wall": 0, "along": 20},
    "finish": [60, 0, 60, -40],
    "time_limit_s": 20,
}


def walk_both(vx, yaw, frames=550):
    """One rig walking (vx 0.1 mm/s, yaw cdeg/s); both movers fed the same pulses each frame; the
    poses (x, y mm, heading rad) of [kinematic, physics] at frames 300 and `frames`, and the
    largest distance between a link end of the two (FK of the pulses sent vs the model's), mm."""
    rig = wall_rig.Rig("pico", "sink")
    rig.set_distances([9000] * 5)
    rig.stand()
    bodies = [Body(), Body()]
    standing = bodies[0].neutral_legs()
    assert list(rig.tee.pulses) == standing  # the core stands in the neutral stance
    movers = [wall_physics.FeetMover(bodies[0], standing), wall_physics.PhysicsMover(bodies[1], standing)]
    assert rig.robot.walk(vx, 0, yaw) == 0
    poses, gap = {}, 0.0
    for n in range(frames + 1):
        rig.step()
        for m in movers:
            m.step(rig.tee.pulses, 1.0, 0.0)
        poses[n] = [(b.x, b.y, b.theta) for b in bodies]
        for a, b in zip(bodies[0].links, bodies[1].links, strict=True):
            gap = max(gap, math.hypot(a[2] - b[2], a[3] - b[3]))
    return poses[300], poses[frames], gap


def test_a_straight_walk_goes_the_same_way_in_both():
    # 40 mm/s (under the servo guard's 48 mm/s for the tripod, so not scaled), the tripod's 1000 ms
    # cycle: 200 mm in the 5 strides from frame 300 (hand-worked). The bounds sit inside the kinematic simulator's own
    # disturbances (sd 5 % speed error per trial, sd 1 degree of heading slip per stride, so
    # 2.2 degrees over 5 strides): distance within 3 %, heading within 0.5 degree, and so
    # sideways within 200 mm x sin 0.5 deg / 2 = 0.9 mm.
    start, end, _ = walk_both(400, 0)
    (k0, p0), (k1, p1) = start, end
    kin = math.hypot(k1[0] - k0[0], k1[1] - k0[1])
    phys = math.hypot(p1[0] - p0[0], p1[1] - p0[1])
    assert kin == pytest.approx(200.0, abs=1.0)
    assert 0.97 * kin <= phys <= 1.03 * kin
    assert abs(math.degrees((p1[2] - p0[2]) - (k1[2] - k0[2]))) < 0.5
    side = -(p1[0] - p0[0]) * math.sin(p0[2]) + (p1[1] - p0[1]) * math.cos(p0[2])
    assert abs(side) < 0.9


def test_an_arc_is_the_same_arc_in_both():
    # 20 mm/s at 6 deg/s (inside the servo guard's budget: not scaled), frames 300..550: the
    # model's heading goes from 36 to 66 degrees, so its steps must be turned into the body frame
    # right. Kinematically 30 degrees on a circle of 191.0 mm (v / w). Physics: the turn within
    # the goal (>= 95 % of the yaw rate, <= 105 %; measured 29.6 degrees), the chord within 3 % of the kinematic
    # one (as the straight walk), and pointing half its own turn off the start heading, as a
    # circle's chord does.
    (k0, p0), (k1, p1), gap = walk_both(200, 600)
    kin, phys = k1[2] - k0[2], p1[2] - p0[2]
    assert math.degrees(kin) == pytest.approx(30.0, abs=0.3)
    assert 0.95 * kin <= phys <= 1.05 * kin
    chord = math.hypot(k1[0] - k0[0], k1[1] - k0[1])
    assert chord == pytest.approx(2 * 20.0 / math.radians(6) * math.sin(kin / 2), abs=1.5)
    chord_p = math.hypot(p1[0] - p0[0], p1[1] - p0[1])
    assert 0.97 * chord <= chord_p <= 1.03 * chord
    heading = math.atan2(p1[1] - p0[1], p1[0] - p0[0]) - p0[2]
    assert math.degrees(heading - phys / 2) == pytest.approx(0.0, abs=0.5)
    # Walking, the model's links trail the pulses (servo lag in the swings, sag): within 6 mm of
    # FK of the pulses sent at every frame (measured 4.7), against 82 mm of clearance at 8 cm.
    assert gap < 6.0


def test_the_legs_checked_for_contact_are_the_models():
    # Standing: each leg's coxa axis, femur joint, knee and foot where MuJoCo has them, against
    # FK of the angles sent (room.Body). The coxa axis is the mount (exact); the links sag
    # under the body's weight by 1.5-2 mm (docs/physics.md), never more than 2 mm in plan.
    body = Body()
    standing = body.neutral_legs()
    fk_links, fk_feet = list(body.links), list(body.feet)
    legs = wall_physics.PhysicsMover(body, standing).legs()
    for i, leg in enumerate(legs):
        refs = [fk_links[3 * i + k][:2] for k in range(3)] + [fk_feet[i][:2]]
        gaps = [math.hypot(p[0] - r[0], p[1] - r[1]) for p, r in zip(leg, refs, strict=True)]
        assert gaps[0] < 1e-6 and max(gaps) < 2.0
        assert fk_feet[i][2] + 2.0 > leg[3][2] > fk_feet[i][2]  # the body sags toward its feet


def test_along_the_wall_both_simulators_hold_the_same_path():
    # Undisturbed, 12 cm: both done, no contact, each held within 3 mm (the sonar noise's sd),
    # and the two paths of the side sonars' midpoint less than 1 mm apart on average and 3 mm at
    # most: under one sd of a ping's noise, a difference the follower cannot see.
    # Measured: 0.22 mm mean, 0.73 mm at most; RMS 0.10 and 0.29 mm.
    w = world.load("wall")
    k = sim_wall.run_trial(w, 12, "u", disturb=False, record=True, bus="sink")
    p = sim_wall.run_trial(w, 12, "u", disturb=False, record=True, bus="sink", mover="physics")
    for r in (k, p):
        assert (r["success"], r["contact"]) == (True, False) and r["rms_mm"] < 0.4  # measured 0.10, 0.29 mm
    mean, most = wall_physics.path_difference(k["trace"], p["trace"])
    assert mean < 1.0 and most < 3.0


def test_path_difference_by_hand():
    # Two parallel paths 4 mm apart, the second one starting 10 mm later and ending 30 mm
    # further: points whose nearest point on the other path is within 30 mm of its start or
    # end are left out, the rest are 4 mm off.
    a = [(0, 0, x, 0.0, 0) for x in range(0, 101, 10)]
    b = [(0, 0, x, 4.0, 0) for x in range(10, 131, 10)]
    assert wall_physics.path_difference(a, b) == (4.0, 4.0)
    # Two corners 3 mm apart (the paths' vertices only): d's corner is 3 mm from c's first leg,
    # c's corner is 3 sqrt 2 from d's; the four ends are left out.
    c = [(0, 0, 0, 0, 0), (0, 0, 100, 0, 0), (0, 0, 100, 100, 0)]
    d = [(0, 0, 0, 3, 0), (0, 0, 97, 3, 0), (0, 0, 97, 100, 0)]
    mean, most = wall_physics.path_difference(c, d)
    assert most == pytest.approx(3 * math.sqrt(2), abs=0.005) and mean == pytest.approx(
        (3 + 3 * math.sqrt(2)) / 2, abs=0.005
    )
    # A path that hooks back at its end (the body's last wobble before the finish): the other
    # path's points past it stay out.
    e = [(0, 0, x, 2.0, 0) for x in range(0, 181, 10)] + [(0, 0, 172, -4.0, 0)]
    assert wall_physics.path_difference(a + [(0, 0, x, 0.0, 0) for x in range(110, 201, 10)], e) == (2.0, 2.0)
    assert wall_physics.path_difference(a, a[:1]) == (None, None)


def test_pairs_do_not_depend_on_the_worker_count(tmp_path):
    f = tmp_path / "short.json"
    f.write_text(json.dumps(SHORT))
    one = sim_wall.run_trials(str(f), [12], 3, 5, jobs=1, mover="both")
    two = sim_wall.run_trials(str(f), [12], 3, 5, jobs=2, mover="both")
    assert one == two
    pairs = one[12]
    assert pairs[0]["physics"] != pairs[1]["physics"] and pairs[0]["physics"] != pairs[0]["kinematic"]
    # Each pair's kinematic half is the plain trial: the same as `hexapod sim wall` on that seed.
    alone = sim_wall.run_trials(str(f), [12], 3, 5, jobs=1)
    assert [p["kinematic"]["rms_mm"] for p in pairs] == [r["rms_mm"] for r in alone[12]]
    assert "trace" in pairs[0]["physics"] and "trace" not in pairs[1]["physics"]


def test_cli_json_and_text(capsys, tmp_path):
    f = tmp_path / "short.json"
    f.write_text(json.dumps(SHORT))
    args = ["sim", "wall", "--physics", "--world", str(f), "--setpoint", "10", "12", "--trials", "1", "--jobs", "1"]
    assert cli.main([*args, "--json"]) == 0
    captured = capsys.readouterr()
    assert captured.err == ""
    out = json.loads(captured.out)
    assert [r["setpoint_cm"] for r in out["rows"]] == [10, 12] and out["trials"] == 2
    # Disturbed, one trial per set point on the 40 cm wall: every run done by both movers, the
    # same outcome each time, the paths under 1 mm apart on average (measured 0.33 and 0.55 mm,
    # at most 1.09 and 1.4 mm) and the RMS errors 0.33..0.97 mm (the sonar noise's sd is 3 mm).
    for r in [out] + out["rows"]:
        for m in ("kinematic", "physics"):
            assert r[m]["trials"] == r["trials"] and r[m]["success_rate"] == 1.0
            assert 0.15 < r[m]["rms_mm"] < 1.5
        assert r["same_outcome"] == r["trials"] and r["path_diff_mm"] < 1.0 and r["path_diff_max_mm"] < 2.0
        assert r["path_diff_mm"] <= r["path_diff_max_mm"]
    png = tmp_path / "both.png"
    assert cli.main([*args, "--plot", str(png)]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith("hexapod sim wall --physics: world short")
    assert lines[1].split()[:6] == ["set", "point", "trials", "success", "(physics)", "same"]
    assert [line.split()[:2] for line in lines[2:4]] == [["10", "cm"], ["12", "cm"]]
    assert len({len(line) for line in lines[1:4]}) == 1  # aligned
    assert lines[4].startswith("kinematic: ") and lines[5].startswith("physics: ")
    assert lines[6].startswith("same outcome in ") and lines[-1] == "plot: %s" % png
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--trials", "0"], "--trials: 0 is outside 1..100000"),
        (["--trials", "many"], "--trials: 'many' is not a whole number"),
        (["--setpoint", "51"], "--setpoint: 51 is outside 4..50 cm"),
        (["--setpoint", "inf"], "--setpoint: inf is outside"),
        (["--jobs", "-2"], "--jobs: -2 is outside 1..256"),
        (["--world", "moon"], "world moon: cannot read"),
        (["--follow", "both"], "--follow: 'both', allowed left or right"),
        (["--plot", "both.svg"], "--plot: 'both.svg', allowed a file name ending in .png"),
        (["--form", "zigzag"], "--form: 'zigzag', allowed yaw, sweeps or crab"),
        (["--gains", "101", "0.5", "1"], "--gains P: 101 is outside 0..100"),
    ],
)
def test_cli_bad_arguments_exit_2(args, message, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(SystemExit) as exc:
        cli.main(["sim", "wall", "--physics", *args])
    assert exc.value.code == 2
    assert message in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def test_a_pair_without_a_path_difference_is_left_out_of_the_row():
    # A trial stopped within its first 30 mm has no comparable path (path_difference gives None):
    # the row's mean and largest difference come from the other pairs (a 200-trial run at 8 cm
    # crashed on this before).
    def pair(ok, diff):
        run = {"success": ok, "time_s": 10.0 if ok else 1.0}
        return {"kinematic": run, "physics": dict(run), "path_diff_mm": diff, "path_diff_max_mm": diff and 2 * diff}

    row = wall_physics.compare(8, [pair(True, 1.0), pair(False, None), pair(True, 3.0)], lambda sp, runs: len(runs))
    assert (row["path_diff_mm"], row["path_diff_max_mm"], row["same_outcome"], row["time_diff_s"]) == (2.0, 6.0, 3, 0.0)
    row = wall_physics.compare(8, [pair(False, None)], lambda sp, runs: len(runs))
    assert (row["path_diff_mm"], row["path_diff_max_mm"], row["time_diff_s"]) == (None, None, None)
