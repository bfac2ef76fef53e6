"""A recording without a room (a board's) replayed in a wall simulator world (`hexapod view
--replay FILE --world W`, view/inroom.py): the world's walls in describe(), the body placed at the
world's start and moved by its recorded feet; bad combinations refused before anything starts.

The hand-worked case: world `wall` (one wall along x from 0 to 2 m, followed on the left, start
20 cm along it). The body faces +x with the left sonars' midpoint (body (0, 210) mm) at the start
distance to the wall's right: at 120 mm (no reading) the midpoint is at (200, -120), the body at
(200, -330). Feet that move 10 mm back (-x) in the body between snapshots move the body 10 mm
forward; feet turned -5 degrees about the body centre turn it +5 degrees where it stands."""

import json
import math
from pathlib import Path

import pytest

from hexapod_host.commands import cli
from hexapod_host.view import record
from hexapod_host.view.replay import ReplayError, ReplaySource
from hexapod_host.view.sim import SimSource
from hexapod_host.wall import world
from tests.test_view_record import Clock, plain

SENSORS = [[130.0, 0.0, 0.0], [100.0, 210.0, 1.5708], [-100.0, 210.0, 1.5708], [100.0, -210.0, -1.5708]]
SENSORS.append([-100.0, -210.0, -1.5708])
BOARD_DESCRIBE = {"source": "virtual", "board": "pico", "sensors": SENSORS, "body_half": [87.5, 77.5], "brackets": []}
# Six feet on the ground (z -80) around the body; the other three points of each leg above them.
FEET = [(150.0, -120.0), (0.0, -160.0), (-150.0, -120.0), (-150.0, 120.0), (0.0, 160.0), (150.0, 120.0)]


def snap(n, feet, distances=(None,) * 5, side=None, up=()):
    """Snapshot of frame n, the feet (x, y mm) on the ground (z -80) but those of the legs in `up` (z -60)."""
    legs = [
        [[x / 3, y / 3, 0.0], [x / 2, y / 2, 0.0], [x, y, 20.0], [x, y, -60.0 if i in up else -80.0]]
        for i, (x, y) in enumerate(feet)
    ]
    return {
        "frame": n,
        "time_s": n * 0.04,
        "pulses": [1500] * 18,
        "angles": [0] * 18,
        "legs": legs,
        "stance": [True] * 6,
        "body": {"x": 0.0, "y": 0.0, "z": 80.0, "yaw": 0.0},
        "distances": list(distances),
        "sonar_status": ["ok"] * 5,
        "mode": "walking",
        "follow": {"mode": "off", "side": side, "setpoint_mm": 0, "error_mm": 0, "output_dps": 0, "sensor_state": []},
        "counters": {},
        "extra": {},
    }


def turned(feet, deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return [(c * x - s * y, s * x + c * y) for x, y in feet]


def write(path, described, snaps):
    r = record.Recorder(str(path), described, clock=Clock())
    for s in snaps:
        r.write(s)
    r.close()
    return str(path)


def poses(src):
    out = []
    for i in range(len(src)):
        src.index = i
        b = src.snapshot()["body"]
        out.append((b["x"], b["y"], b["yaw"]))
    return out


def test_a_boards_recording_walks_in_the_worlds_room(tmp_path):
    # snapshot 0 at the feet; 1-5 the feet 10 mm further back each; 6-8 turned -5 degrees more each
    snaps = [snap(0, FEET)]
    snaps += [snap(k, [(x - 10.0 * k, y) for x, y in FEET]) for k in range(1, 6)]
    back = [(x - 50.0, y) for x, y in FEET]
    snaps += [snap(5 + k, turned(back, -5.0 * k)) for k in range(1, 4)]
    src = ReplaySource(write(tmp_path / "board.mcap", BOARD_DESCRIBE, snaps), world.load("wall"))
    d = src.describe()
    assert (d["source"], d["world"], d["walls"], d["finish"]) == (
        "replay of virtual",
        "wall",
        [[0.0, 0.0, 2000.0, 0.0]],
        [1700.0, -400.0, 1700.0, 400.0],
    )
    want = [(200.0 + 10 * k, -330.0, 0.0) for k in range(6)] + [(250.0, -330.0, math.radians(5 * k)) for k in (1, 2, 3)]
    assert poses(src) == [pytest.approx(w, abs=1e-6) for w in want]
    s = src.snapshot()  # the rest of the snapshot as recorded
    assert (s["body"]["z"], s["frame"], s["legs"]) == (80.0, 8, plain(snaps[8]["legs"]))
    # scrubbing back shows the pose of that snapshot again (the path is worked out once, up front)
    src.seek(0.0)
    assert (src.snapshot()["body"]["x"], src.snapshot()["body"]["y"]) == (200.0, -330.0)


def test_a_stance_changes_hands_in_the_frame_between_two_snapshots(tmp_path):
    """A board's every other frame: frames 0, 2, 4. Frames 0 -> 2: tripod A (legs 0, 2, 4) down,
    its feet 20 mm further back: the body 20 mm on. In frame 3 (not recorded) A lifts and B (1, 3,
    5) lands. A's feet at 4 are 20 mm further back again, so at 3, halfway, 10 mm: the body goes
    10 mm on to frame 3. B's feet at 4 are their frame-3 places (halfway between 2 and 4) turned
    -2 degrees about the body centre: from frame 3 the body turns +2 degrees where it stands.
    Had the step before the hand-over stood in for it, frame 4 would be at (240, -330, 0)."""
    a, b = (0, 2, 4), (1, 3, 5)
    at4 = turned(FEET, -2.0)
    f0 = [(x + 20.0, y) if i in a else (x, y) for i, (x, y) in enumerate(FEET)]
    f2 = [FEET[i] if i in a else (2 * FEET[i][0] - at4[i][0], 2 * FEET[i][1] - at4[i][1]) for i in range(6)]
    f4 = [(x - 20.0, y) if i in a else at4[i] for i, (x, y) in enumerate(FEET)]
    snaps = [snap(0, f0, up=b), snap(2, f2, up=b), snap(4, f4, up=a)]
    src = ReplaySource(write(tmp_path / "half.mcap", BOARD_DESCRIBE, snaps), world.load("wall"))
    want = [(200.0, -330.0, 0.0), (220.0, -330.0, 0.0), (230.0, -330.0, math.radians(2.0))]
    assert poses(src) == [pytest.approx(w, abs=1e-9) for w in want]
    # Three frames apart the hand-over's frame is not known: the step before stands in (20 mm on).
    snaps[2]["frame"] = 5
    src = ReplaySource(write(tmp_path / "gap3.mcap", BOARD_DESCRIBE, snaps), world.load("wall"))
    assert poses(src)[2] == pytest.approx((240.0, -330.0, 0.0), abs=1e-9)


def test_the_start_is_the_first_side_readings_on_the_followed_side(tmp_path):
    # the right wall followed: the recording says so; its right pair first read 100 and 110 mm
    right = [None, None, None, 100.0, 110.0]
    snaps = [snap(0, FEET, side="right"), snap(1, FEET, right, side="right")]
    src = ReplaySource(write(tmp_path / "r.mcap", BOARD_DESCRIBE, snaps), world.load("wall"))
    # robot on the wall's left (y > 0) facing +x, its right sonars' midpoint (0, -210) at 105 mm
    assert poses(src)[0] == pytest.approx((200.0, 315.0, 0.0))


def test_the_simulators_own_path_from_its_feet(tmp_path):
    """The simulator's run written as a board would record it (no room in describe, the body at the
    origin, no readings: the start at 120 mm, its set point, as the simulator starts it without
    disturbances): replayed in its world, the body goes where the simulator moved it. From frame 1:
    the simulator's mover starts from the first frame's feet, not from the standing pose before it."""
    src = SimSource(world.load("wall"), 12, seed=0, disturb=False)
    src.step()
    described = {k: v for k, v in src.describe().items() if k not in ("world", "walls", "finish")}
    snaps, truth = [], []
    for _ in range(1500):
        s = plain(src.snapshot())
        truth.append((s["body"]["x"], s["body"]["y"], s["body"]["yaw"]))
        s["body"].update(x=0.0, y=0.0, yaw=0.0)
        s["distances"] = [None] * 5
        snaps.append(s)
        src.step()
    src.close()
    assert truth[-1][0] - truth[0][0] > 100  # it walked along the wall
    rep = ReplaySource(write(tmp_path / "sim.mcap", {**described, "source": "virtual"}, snaps), world.load("wall"))
    assert poses(rep) == [pytest.approx(t, abs=1e-6) for t in truth]
    # Every other frame, as a board streams at 25 a second: where a stance changes hands between
    # two snapshots no foot is down in both, and the frame between is rebuilt (without it the body
    # fell 2 frames behind every half cycle: 56 mm over these 30 s, 1.4 m).
    rep = ReplaySource(
        write(tmp_path / "half.mcap", {**described, "source": "virtual"}, snaps[::2]), world.load("wall")
    )
    for (x, y, yaw), (tx, ty, tyaw) in zip(poses(rep), truth[::2], strict=True):
        assert math.hypot(x - tx, y - ty) < 6.0 and abs(yaw - tyaw) < math.radians(0.3)


def test_a_simulators_recording_keeps_its_own_room(tmp_path):
    src = SimSource(world.load("corridor"), 12, seed=0)
    path = write(tmp_path / "sim.mcap", plain(src.describe()), [plain(src.snapshot())])
    src.close()
    with pytest.raises(ReplayError, match="made in the simulator's world corridor: its room and path are in the file"):
        ReplaySource(path, world.load("wall"))


@pytest.mark.parametrize(
    "argv, message",
    [
        (["--virtual", "--world", "wall"], "--world: only with --sim or --replay"),
        (["--port", "/dev/nothing", "--world", "wall"], "--world: only with --sim or --replay"),
        (["--replay", "{board}", "--world", "nowhere"], "--world: world nowhere: cannot read"),
        (["--replay", "{sim}", "--world", "wall"], "made in the simulator's world wall"),
        (["--replay", "{board}", "--world", "wall", "--setpoint", "10"], "--setpoint: only with --sim"),
        (["--replay", "{board}", "--seed", "3"], "--seed: only with --sim"),
        (["--pico", "--setpoint", "10"], "--setpoint: only with --sim"),
    ],
)
def test_bad_combinations_are_refused_before_anything_starts(argv, message, tmp_path, capsys):
    board = write(tmp_path / "board.mcap", BOARD_DESCRIBE, [snap(0, FEET)])
    src = SimSource(world.load("wall"), 12, seed=0)
    sim = write(tmp_path / "sim.mcap", plain(src.describe()), [plain(src.snapshot())])
    src.close()
    argv = [a.format(board=board, sim=sim) for a in argv]
    with pytest.raises(SystemExit) as exc:
        cli.main(["view", *argv, "--no-browser", "--listen", "127.0.0.1:1"])
    assert exc.value.code == 2
    assert message in capsys.readouterr().err


def test_the_file_is_not_changed_by_a_replay_in_a_room(tmp_path):
    path = write(tmp_path / "board.mcap", BOARD_DESCRIBE, [snap(0, FEET), snap(1, FEET)])
    before = Path(path).read_bytes()
    src = ReplaySource(path, world.load("wall"))
    assert json.loads(src.data[1])["body"]["x"] == 0.0  # the recorded message as it was
    assert Path(path).read_bytes() == before


def _telemetry_line(s):
    """A snapshot's pulses as the board's telemetry line (docs/console.md's format): walking,
    tripod, no sonar (waiting), no battery."""
    head = [s["frame"], 4, 0, 0, 0, 0, 0, 0, 0]
    tail = ["-"] * 5 + [5] * 5 + [0, 0, "-", 0, 0, 0, 0, 2500, 2600]
    return "~T " + " ".join(map(str, head + list(s["pulses"]) + tail))


def test_a_live_board_walks_where_its_feet_carry_it():
    """A board's page moves its body by the feet of every telemetry line (board.py's odometry,
    the mover above): the simulator's run streamed as a board streams it (every other frame, no
    room), the body at the origin facing +x at the first line. Against the simulator's own path,
    turned into that frame: within the half-rate replay's bounds above."""
    from tests.test_view_virtual import source

    sim = SimSource(world.load("wall"), 12, seed=0, disturb=False)
    sim.step()
    truth = []
    with source() as (src, _):
        try:
            for k in range(1500):
                s = plain(sim.snapshot())
                if k % 2 == 0:
                    src.link.feed(_telemetry_line(s))
                    b = src.snapshot()["body"]
                    truth.append(((s["body"]["x"], s["body"]["y"], s["body"]["yaw"]), (b["x"], b["y"], b["yaw"])))
                sim.step()
        finally:
            sim.close()
    (x0, y0, yaw0), _ = truth[0]
    c, si = math.cos(yaw0), math.sin(yaw0)
    worst = (0.0, 0.0)
    for (tx, ty, tyaw), (x, y, yaw) in truth:
        dx, dy = tx - x0, ty - y0
        rx, ry = c * dx + si * dy, -si * dx + c * dy  # the truth in the first line's body frame
        worst = max(worst[0], math.hypot(x - rx, y - ry)), max(worst[1], abs(yaw - (tyaw - yaw0)))
    assert truth[-1][1][0] > 100  # it walked along +x
    assert worst[0] < 6.0 and worst[1] < math.radians(0.3), worst


def test_a_limp_or_restarted_board_starts_its_odometry_over_where_the_body_was():
    """Feet seen again after a limp line (no pulses) or a board that started over (its frame
    count went back) are not a step from the feet before: the body stays where it was."""
    from tests.test_view_virtual import source

    sim = SimSource(world.load("wall"), 12, seed=0, disturb=False)
    sim.step()
    snaps = []
    for _ in range(400):
        snaps.append(plain(sim.snapshot()))
        sim.step()
    sim.close()
    with source() as (src, _):
        for s in snaps[:200:2]:
            src.link.feed(_telemetry_line(s))
        before = src.snapshot()["body"]
        assert before["x"] > 20  # it walked
        src.link.feed(_telemetry_line({**snaps[200], "pulses": [0] * 18}))  # limp
        src.link.feed(_telemetry_line(snaps[300]))
        after = src.snapshot()["body"]
        assert (after["x"], after["y"], after["yaw"]) == (before["x"], before["y"], before["yaw"])
        src.link.feed(_telemetry_line({**snaps[100], "frame": 5}))  # the board started over
        again = src.snapshot()["body"]
        assert (again["x"], again["y"], again["yaw"]) == (before["x"], before["y"], before["yaw"])
