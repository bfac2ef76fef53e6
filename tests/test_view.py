"""hexapod view without a browser: a snapshot's geometry against a hand-worked FK case, the
simulator source, the player's stepping (no clock: advance() is given the time), the CLI's
refusals. The page itself: tests/test_view_browser.py."""

import math
import socket

import pytest

from hexapod_host.commands import cli
from hexapod_host.view import player as player_mod
from hexapod_host.view.scene import geometry, segment_pose
from hexapod_host.view.sim import SimSource
from hexapod_host.view.source import Source, pose
from hexapod_host.wall import world
from hexapod_host.wall.room import Body

# boards/pico.py's servo rows: centre 1500 us (tibia 2400, mirrored 600), 10 us per degree,
# the left legs' femur and tibia mirrored. Leg 1 (RF) and leg 5 (LM): coxa 0, femur +30,
# tibia -120 degrees (the tibia straight down); legs 2, 3 (right) and 4, 6 (left) straight out.
PULSES = [1500, 1800, 1200] + [1500, 1500, 2400] * 2 + [1500, 1500, 600] + [1500, 1200, 1800] + [1500, 1500, 600]
SENSORS = [[130, 0, 0.0], [100, 210, math.pi / 2], [-100, 210, math.pi / 2], [100, -210, -math.pi / 2]]
SENSORS.append([-100, -210, -math.pi / 2])  # boards/pico.py's sonars, mm and rad
DESCRIBED = {"sensors": SENSORS, "body_half": [87.5, 77.5], "brackets": [[77.5, 87.5, 100, 210]]}


def hand_snapshot():
    """The body at (1000, 500) mm facing +y (yaw 90 degrees), coxa plane 50.5 mm up: feet 1 and 5 on the ground."""
    snap = pose(Body("pico"), PULSES)
    snap.update(
        body={"x": 1000.0, "y": 500.0, "z": 50.5, "yaw": math.pi / 2},
        distances=[None, 123.4, 120.0, None, None],
        sonar_status=["no_echo", "ok", "ok", "out_of_range", "wait"],  # hexapod.sensors.STATUS_NAMES
    )
    return snap


def close(a, b, tol=1e-3):
    return all(abs(x - y) <= tol for x, y in zip(a, b, strict=True))


def test_pulses_to_joint_angles_through_the_servo_maps():
    snap = hand_snapshot()
    assert snap["angles"][0:3] == [0, 3000, -12000]  # leg 1: 1500, 1800, 1200 us
    assert snap["angles"][12:15] == [0, 3000, -12000]  # leg 5, mirrored: 1500, 1200, 1800 us
    assert snap["angles"][3:6] == [0, 0, 0] and snap["angles"][9:12] == [0, 0, 0]
    assert snap["stance"] == [True, False, False, False, True, False]  # the two feet 50.5 mm below the coxa plane


def test_a_hand_worked_leg_in_the_world():
    # Seed 004's FK by hand, robots/default.py: coxa 30, femur 85, tibia 125 mm, femur joint 32 mm up.
    # Leg 1 mounts at (87.5, -77.5) facing -45 degrees; knee reach 30 + 85 cos 30 = 103.61216 mm,
    # along -45: 73.26486 each way; knee 32 + 85 sin 30 = 74.5 mm up, foot 125 below it.
    # Body frame -> world with yaw 90: (x, y) -> (1000 - y, 500 + x), z + 50.5.
    g = geometry(DESCRIBED, hand_snapshot())
    coxa, femur, tibia = g["links"][0:3]
    assert close(coxa[0], [1077.5, 587.5, 50.5])
    assert close(coxa[1], [1000 + 98.71320, 500 + 108.71320, 82.5])  # 30 mm along -45: 21.21320 each way
    assert close(femur[1], [1000 + 150.76486, 500 + 160.76486, 125.0])
    assert close(tibia[1], [1000 + 150.76486, 500 + 160.76486, 0.0])
    assert close(g["feet"][0], tibia[1])
    # Leg 5 mounts at (0, 77.5) facing +90: its foot 77.5 + 103.61216 mm out, on the ground.
    assert close(g["feet"][4], [1000 - 181.11216, 500.0, 0.0])
    # Leg 2 straight out: 30 + 85 + 125 = 240 mm beyond its mount (0, -77.5), at the femur joint's 32 mm.
    assert close(g["feet"][1], [1317.5, 500.0, 82.5])
    assert g["stance"] == [True, False, False, False, True, False]
    assert close(g["brackets"][0][1], [1000 - 210, 500 + 100, 50.5])
    assert g["body"] == {"centre": [1000.0, 500.0, 50.5], "yaw": math.pi / 2, "half": [87.5, 77.5]}


def test_beams_from_the_sonars_with_their_readings():
    beams = geometry(DESCRIBED, hand_snapshot())["beams"]
    # front: (130, 0) -> world (1000, 630), facing +y; no echo is a fault, drawn 150 mm long
    assert beams[0]["state"] == "fault" and close(beams[0]["start"], [1000, 630, 50.5])
    assert close(beams[0]["end"], [1000, 780, 50.5])
    # left front: (100, 210) -> (790, 600), facing -x in the world, 123.4 mm
    assert beams[1]["state"] == "ok" and close(beams[1]["end"], [790 - 123.4, 600, 50.5])
    assert beams[1]["mm"] == 123.4
    # right front: out of range (nothing heard): grey, 150 mm toward +x
    assert beams[3]["state"] == "none" and close(beams[3]["end"], [1210 + 150, 600, 50.5])
    assert beams[4]["state"] == "none"  # waiting for its turn is no fault


def test_every_sonar_status_a_source_gives_has_its_beam_colour():
    from hexapod import sensors
    from hexapod_host.view.scene import beam_state

    assert sensors.STATUS_NAMES == ("ok", "out_of_range", "no_echo", "stuck", "too_close", "wait", "pending")
    assert [beam_state(n) for n in sensors.STATUS_NAMES] == ["ok", "none", "fault", "fault", "fault", "none", "none"]


def test_a_segment_as_a_unit_cylinder():
    centre, rot, length = segment_pose([0, 0, 0], [0, 0, 2])  # straight up
    assert centre == [0, 0, 1] and length == 2
    assert [row[1] for row in rot] == [0, 0, 1]  # the cylinder's y onto +z
    centre, rot, length = segment_pose([1, 2, 3], [4, 6, 3])  # a 3-4-5 triangle, level
    assert close(centre, [2.5, 4, 3]) and length == pytest.approx(5)
    assert close([row[1] for row in rot], [0.6, 0.8, 0])
    # a rotation: orthonormal, determinant +1
    cols = [[row[k] for row in rot] for k in range(3)]
    for i in range(3):
        for j in range(3):
            assert sum(a * b for a, b in zip(cols[i], cols[j], strict=True)) == pytest.approx(1.0 if i == j else 0.0)
    x, y, z = cols
    assert close([x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]], z)


def test_the_simulator_source_stands_the_robot_at_the_robot_files_height():
    src = SimSource(world.load("wall"), 12, seed=0, disturb=False)
    try:
        d = src.describe()
        assert d["walls"] == [[0.0, 0.0, 2000.0, 0.0]]  # wall.json: 0..200 cm on y = 0
        snap = src.snapshot()
        assert snap["body"]["z"] == pytest.approx(80.0, abs=0.05)  # robots/default.py BODY_HEIGHT 800 (0.1 mm)
        assert snap["stance"] == [True] * 6
        start = (snap["body"]["x"], snap["body"]["y"])
        for _ in range(100):
            src.step()
        snap = src.snapshot()
        assert snap["frame"] == 100 and snap["follow"]["mode"] == "following"
        assert snap["body"]["x"] - start[0] > 20  # walking along the wall (+x)
        assert snap["distances"][1] == pytest.approx(snap["extra"]["wall_mm"], abs=30)  # left front sees the wall
    finally:
        src.close()


class Counter(Source):
    """A source that counts its frames and is done after `end` of them."""

    steppable = True

    def __init__(self, end=10**9):
        self.n, self.end, self.restarts = 0, end, 0

    def describe(self):
        return {"source": "counter"}

    def step(self):
        self.n += 1

    def done(self):
        return self.n >= self.end

    def restart(self):
        self.n, self.restarts = 0, self.restarts + 1

    def snapshot(self):
        return {
            "frame": self.n,
            "time_s": self.n * self.frame_s,
            "body": {"x": float(self.n), "y": 0.0, "z": 80.0, "yaw": 0.0},
            "distances": [None] * 5,
            "follow": {"mode": "off", "side": None, "setpoint_mm": 0, "error_mm": 0, "output_dps": 0},
        }


def test_the_player_steps_real_time_times_speed():
    p = player_mod.Player(Counter())
    p.advance(0.2)  # 0.2 s at 1x: ten 20 ms frames
    assert p.source.n == 10
    p.set_speed(2.0)
    p.advance(0.2)
    assert p.source.n == 30
    p.set_speed(0.25)
    p.advance(0.2)  # 2.5 frames: 2 now, the half carried
    assert p.source.n == 32
    p.advance(0.2)
    assert p.source.n == 35
    p.set_speed(8.0)
    p.advance(60.0)  # a stalled machine catches up at most MAX_FRAMES (100) at once
    assert p.source.n == 135
    assert p.updates == 6  # one snapshot published at the start and one per advance


def test_pause_step_and_the_end_of_a_trial():
    p = player_mod.Player(Counter(end=12))
    p.pause()
    p.advance(1.0)
    assert p.source.n == 0
    p.step()
    assert p.source.n == 1 and p.snap["frame"] == 1
    p.start()
    p.step()  # no single steps while running
    assert p.source.n == 1
    p.advance(1.0)  # 50 frames owed, the trial ends at 12
    assert p.source.n == 12 and not p.running and p.done()
    p.step()
    assert p.source.n == 12
    p.start()  # the next trial
    assert p.source.restarts == 1 and p.source.n == 0 and p.running and p.trail == [(0.0, 0.0)]


def test_a_speed_not_offered_is_refused():
    p = player_mod.Player(Counter())
    with pytest.raises(ValueError, match=r"speed: 3, allowed 0.25, 0.5, 1, 2, 4, 8"):
        p.set_speed(3)
    assert p.speed == 1.0


@pytest.mark.parametrize(
    "args, message",
    [
        (["--sim", "--virtual-port", "/dev/pts/1"], "--virtual-port: only with --virtual"),
        (["--virtual", "--virtual-port", "/dev/no-such-pty"], "--virtual-port /dev/no-such-pty: no such port"),
        (["--sim", "--listen", ":8080"], "no host; say 127.0.0.1:8080 (this machine) or 0.0.0.0:8080"),
        (["--sim", "--listen", "127.0.0.1:http"], "the port 'http' is not a whole number"),
        (["--sim", "--listen", "127.0.0.1:70000"], "port 70000 is outside 1..65535"),
        (["--sim", "--speed", "3"], "--speed: 3, allowed 0.25, 0.5, 1, 2, 4, 8"),
        (["--sim", "--world", "nowhere"], "world nowhere: cannot read"),
        (["--sim", "--setpoint", "2"], "--setpoint: 2 is outside 4..50"),
        (["--sim", "--fps", "0"], "--fps: 0 is outside 1..60"),
        (["--sim", "--fps", "61"], "--fps: 61 is outside 1..60"),
        (["--sim", "--fps", "-5"], "--fps: -5 is outside 1..60"),
        (["--sim", "--fps", "2.5"], "--fps: '2.5' is not a whole number"),
        (["--sim", "--fps", "fast"], "--fps: 'fast' is not a whole number"),
        (["--sim", "--fps", ""], "--fps: '' is not a whole number"),
    ],
)
def test_cli_bad_arguments_exit_2(args, message, capsys):
    with pytest.raises(SystemExit) as exc:
        cli.main(["view", *args])
    assert exc.value.code == 2
    assert message in capsys.readouterr().err


@pytest.mark.parametrize("argv, fps", [([], 20), (["--fps", "1"], 1), (["--fps", "60"], 60), (["--fps", "5"], 5)])
def test_the_scene_redraws_at_the_fps_asked(argv, fps, monkeypatch):
    """--fps reaches the page's 3-D scene (NiceGUI's ui.scene fps: its redraws a second); the
    default is NiceGUI's own, 20."""
    import asyncio

    from hexapod_host.view import server

    served = []

    def serve(player, host, port, show, fps):
        served.append(fps)
        asyncio.run(_scene_fps(player, fps, served))

    monkeypatch.setattr(server, "serve", serve)
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    assert cli.main(["view", "--sim", *argv, "--no-browser", "--listen", "127.0.0.1:%d" % port]) == 0
    assert served == [fps, fps]  # what run() passed, what the page's scene took


async def _scene_fps(player, fps, out):
    from nicegui.testing.user_simulation import user_simulation

    from hexapod_host.view import page

    views = []
    async with user_simulation(root=lambda: views.append(page.View(player, page.Driver(player.source), fps))) as user:
        await user.open("/")
        out.append(views[0].scene.props["fps"])


def test_cli_refuses_a_port_already_taken(capsys):
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        s.listen()
        port = s.getsockname()[1]
        with pytest.raises(SystemExit) as exc:
            cli.main(["view", "--sim", "--listen", "127.0.0.1:%d" % port])
    assert exc.value.code == 2
    assert "--listen 127.0.0.1:%d: cannot listen there" % port in capsys.readouterr().err


def test_a_bare_port_listens_on_this_machine_only():
    from hexapod_host.commands.view import parse_listen
    from hexapod_host.view.server import is_loopback

    assert parse_listen("8081") == ("127.0.0.1", 8081)
    assert parse_listen("[::1]:8082") == ("::1", 8082)
    assert is_loopback("127.0.0.1") and is_loopback("::1") and is_loopback("localhost")
    assert not is_loopback("0.0.0.0") and not is_loopback("192.168.1.20")


def test_the_virtual_boards_trace_is_read_as_it_grows(tmp_path):
    """browser.VirtualBoard.trace() parses only what was appended since it last read, and a line
    still being written (no newline yet) waits for the next call."""
    from hexapod_host.view.browser import VirtualBoard

    board = object.__new__(VirtualBoard)  # the reader alone: no board started
    board.trace_path, board._events, board._read = str(tmp_path / "trace.txt"), [], 0
    assert board.trace() == []  # not written yet
    path = tmp_path / "trace.txt"
    path.write_text("L 3 100 walk 40 0 0\nP 4 1")
    assert board.trace() == [("L", 3, 100, ["walk", "40", "0", "0"])]
    with open(path, "a") as f:
        f.write("20 0=1500 5=1454\nM 5 140 3 0 0 0\n")
    assert board.trace() == [
        ("L", 3, 100, ["walk", "40", "0", "0"]),
        ("P", 4, 120, ["0=1500", "5=1454"]),
        ("M", 5, 140, ["3", "0", "0", "0"]),
    ]
    first = board.trace()
    first.append("a caller's own")
    assert len(board.trace()) == 3  # each call returns a list of its own
