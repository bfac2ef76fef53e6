"""`hexapod virtual-board --world`: the virtual board's sonars read the wall simulator's room
(hexapod_host.wall.board_room), the body moved by its feet, in real time. The board is waited
on by its own frame counter; the host's clock only stops a hang."""

import json
import math
import time

import pytest

from hexapod_host.commands import cli
from hexapod_host.commands import console as console_cmd
from hexapod_host.wall.sim import side_midpoint, wall_distance

HANG_S = 300  # a board that stopped counting frames, not a slow machine
# The wall simulator's precision at a 12 cm set point on the wall world: RMS error after the
# first 30 cm, 0.81-0.84 mm over 100 trials each (docs/figures.md, the final-main table).
SIM_RMS_MM = 0.84
SETTLE_FRAMES = 700  # 14 s of board time: past the simulator's unjudged first 30 cm (about 55 cm in), still on the wall
# The servo speed guard caps the follower's walk at 48 mm/s (docs/figures.md, docs/physics.md);
# the follower asks for 80 mm/s (hexapod/follow.py SPEED): no frame can carry the body farther.
FOLLOW_MM_S = 80.0


def words(reply):
    w = reply.split()
    return dict(zip(w[1::2], w[2::2], strict=False))


def status(link):
    return words(link.request("status"))


def sonar(link):
    """{name: mm or None} from `sonar` (None: no reading)."""
    w = link.request("sonar").split()
    assert w[0] == "ok", w
    return {w[k]: (float(w[k + 1]) if w[k + 2] == "ok" else None) for k in range(1, len(w), 3)}


def wait_frames(link, n, pause=0.05):
    """Status once the board has run frame n (its own counter); a hang fails the test. pause: between
    polls (0 for an eager board, whose frames the polls drive)."""
    give_up = time.monotonic() + HANG_S
    while True:
        st = status(link)
        if int(st["frames"]) >= n:
            return st
        assert time.monotonic() < give_up, "the board stopped at frame %s" % st["frames"]
        time.sleep(pause)


def test_front_sonar_reads_a_wall_straight_ahead_at_the_start(virtual_board, tmp_path):
    """A world with a wall across the robot's path, 60 cm along the start wall. The start: 20 cm
    along, the side sonars' midpoint (x 0 in the body, robots/default_cal.py) there; the front
    sonar 130 mm ahead of the body centre: 600 - 200 - 130 = 270.0 mm ahead of it. The left pair
    (body y 210 mm, facing the wall) are the start distance, 150.0 mm, from the start wall; the
    right pair face away into nothing. 0.2 mm: the echo's whole us (0.17 mm) and the driver's rounding."""
    path = tmp_path / "ahead.json"
    world = {
        "walls": [[0, 0, 200, 0], [60, -100, 60, 10]],
        "follow": "left",
        "start": {"wall": 0, "along": 20},
        "finish": [170, -40, 170, 40],
        "time_limit_s": 60,
    }
    path.write_text(json.dumps(world))
    _, link, room = virtual_board("", world=str(path))
    wait_frames(link, 25)  # every sonar pinged (round robin, 60 ms apart each)
    d = sonar(link)
    assert abs(d["front"] - 270.0) <= 0.2, d
    assert abs(d["left_front"] - 150.0) <= 0.2 and abs(d["left_rear"] - 150.0) <= 0.2, d
    assert d["right_front"] is None and d["right_rear"] is None, d
    assert room.frames >= 25  # the room stepped with the board


def test_wall_left_12_follows_the_wall_world_at_12_cm(virtual_board):
    """`stand`, `wall left 12` on the wall world (a straight wall on the left; the robot starts
    15 cm from it, facing along it): the follower is `following`, its distance (status wall_d)
    and the room's (the side sonars' midpoint to the wall) are 120 mm within the simulator's RMS
    once past its settling walk, and the body walked along the wall, the side readings
    changing as it closed in. An eager board polled without a pause: each `status` runs the next
    frame at once, so the ~1,000 frames go as fast as the VM and the line run them, and each
    sample is taken at the frame it names (everything here counts in the board's frames)."""
    _, link, room = virtual_board("", world="wall", pace="eager")
    assert link.request("stand") == "ok mode moving"
    give_up = time.monotonic() + HANG_S
    while status(link)["mode"] != "standing":
        assert time.monotonic() < give_up, "never stood"
    start = sonar(link)
    assert abs(start["left_front"] - 150.0) <= 0.2, start  # standing up moved nothing sideways
    x0 = room.body.x
    assert link.request("wall left 12") == "ok wall left setpoint 12.00"
    f0 = int(status(link)["frames"])
    st = wait_frames(link, f0 + SETTLE_FRAMES, pause=0)
    errors, room_errors, sides = [], [], []
    mx, my = side_midpoint(room.body, "left")
    for k in range(1, 6):
        st = wait_frames(link, f0 + SETTLE_FRAMES + 50 * k, pause=0)
        assert st["wall_mode"] == "following" and st["wall"] == "left", st
        errors.append(float(st["wall_d"]) - 120.0)
        room_errors.append(wall_distance(room.walls, *room.body.to_world(mx, my)) - 120.0)
        sides.append(sonar(link)["left_front"])
    frames = int(st["frames"]) - f0
    rms = math.sqrt(sum(e * e for e in errors) / len(errors))
    room_rms = math.sqrt(sum(e * e for e in room_errors) / len(room_errors))
    assert rms <= SIM_RMS_MM and room_rms <= SIM_RMS_MM, (errors, room_errors)
    assert all(abs(s - start["left_front"]) > 20.0 for s in sides), sides  # 15 cm -> 12 cm
    walked = room.body.x - x0
    assert 300.0 <= walked <= FOLLOW_MM_S * frames * 0.02, walked  # along the wall, at most its speed
    assert abs(room.body.theta) < math.radians(2), room.body.theta  # still parallel to it


def test_bad_world_is_refused_before_anything_starts(monkeypatch, capsys, tmp_path):
    def started(*args, **kw):
        raise AssertionError("a virtual board was started")

    monkeypatch.setattr(console_cmd, "start_virtual_board", started)
    bad = tmp_path / "bad.json"
    bad.write_text('{"walls": []}')
    blocked = tmp_path / "blocked.json"  # a wall right across the start: the robot would stand on it
    blocked.write_text(
        json.dumps(
            {
                "walls": [[0, 0, 200, 0], [20, -30, 20, 5]],
                "follow": "left",
                "start": {"wall": 0, "along": 20},
                "finish": [170, -40, 170, 40],
                "time_limit_s": 60,
            }
        )
    )
    cases = (
        ("nope", "--world: world nope: cannot read (No such file or directory); shipped worlds: corridor, corrugated,"),
        (str(bad), "--world: world %s: follow is missing (need walls, follow, start, finish, time_limit_s)" % bad),
        (str(blocked), "--world: world %s: start: 15 cm from wall 0 the robot stands on wall 1" % blocked),
    )
    for value, message in cases:
        with pytest.raises(SystemExit) as stop:
            cli.main(["virtual-board", "--world", value])
        assert stop.value.code == 2
        out, err = capsys.readouterr()
        assert out == "" and err.startswith("hexapod: error: " + message), err
