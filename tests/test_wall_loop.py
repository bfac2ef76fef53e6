"""Wall following through the whole loop on the stub machine: board file, PCA9685 and HC-SR04
models set at distances, the virtual clock, runner.Runner.follow / follow_off, in both runtimes."""

from tests.test_runner import SETUP

RIG = (
    SETUP
    + """
plug(0x40)
plug(0x41)
r = main.build(clock=clock)
r.robot.stand_up()
frames(r, 150)
f = r.follower


def at(front, lf, lr, rf, rr):
    for k, d in enumerate((front, lf, lr, rf, rr)):
        SONAR[k].set_distance(d)


def state():
    return (f.mode_name, f.used, f.distance, f.angle, f.error, f.output, f.vx, f.yaw, r.robot.mode)
"""
)


def run_both(both_runtimes, body):
    cp, mp = both_runtimes(RIG + body, heapsize="4m")
    assert cp == mp
    return __import__("ast").literal_eval(cp.strip().splitlines()[-1])


def test_follow_left_wall_through_the_loop(both_runtimes):
    out = run_both(
        both_runtimes,
        """
at(9000, 800, 800, 9000, 9000)
code = r.follow("left", 800)
frames(r, 30)
parallel = state()
at(9000, 700, 760, 9000, 9000)  # 7 cm at the front sensor, nose toward the wall
frames(r, 30)
toward = state()
off = r.follow_off()
bad = frames(r, 100)
print((code, parallel, toward, off, f.mode_name, r.robot.mode, r.robot.walker.state, bad))
""",
    )
    code, parallel, toward, off, mode, robot_mode, walker_state, bad = out
    assert code == 0
    # Parallel at the set point: straight on at the default speed, no turn.
    assert parallel == ("following", "left_front+left_rear", 800, 0, 0, 0, 800, 0, 4)
    name, used, d, angle, e, u, vx, yaw, _ = toward
    # Hand-worked: d = 73 mm, angle = atan(-6 / 200) = -1.72 deg, e = 80 - 73 + 100 * 6 / 200 = 10 mm
    # (the sonar chain reads 0.1 mm long: HC-SR04 model and driver round up).
    assert name == "following" and 730 <= d <= 731 and angle == -172
    assert 99 <= e <= 100 and u > 0 and yaw < 0  # too close and nose in: turn right, away from the wall
    assert off == 0 and mode == "off" and robot_mode == 3 and walker_state == 0 and bad == []


def test_a_steady_wall_follow_frame_allocates_nothing(mp):
    """Ping + follower (PID, walk command) + tick + two bursts, in the VM: 0 heap bytes."""
    from hexapod_host.testing.runtimes import HEAP_PROBE

    src = (
        RIG
        + HEAP_PROBE
        + """
at(9000, 780, 800, 9000, 9000)  # 2 mm close, nose 0.6 deg in: the integral moves every update
r.follow("left", 800)
frames(r, 100)


def run(n):
    for _ in range(n):
        r.step()
        r.wait()


before = f.updates
sent = f.yaw
print((heap_bytes(run, 300), f.updates - before, f.mode_name, r.robot.mode, r.held, sent != f.yaw))
"""
    )
    heap, updates, mode, robot_mode, held, turned = mp.value(src, heapsize="4m")
    assert (mode, robot_mode, held) == ("following", 4, 0)
    assert updates >= 55 and turned  # two runs of 300 frames: every 100 ms a PID update, new commands
    assert heap == 0


def test_main_starts_following_from_the_board_setting(both_runtimes):
    src = (
        SETUP
        + """
plug(0x40)
plug(0x41)
import boards.pico
for k, d in enumerate((9000, 1150, 1150, 9000, 9000)):
    SONAR[k].set_distance(d)
boards.pico.BOARD["follow"] = {"side": "left", "setpoint": 1200, "speed": 600}
try:
    r = main.main(frames=300, clock=clock)
finally:
    boards.pico.BOARD["follow"] = None
f = r.follower
print((f.mode_name, f.side, f.setpoint, f.speed, f.updates > 10, f.distance, f.yaw < 0, r.robot.mode))
"""
    )
    cp, mp = both_runtimes(src, heapsize="4m")
    assert cp == mp
    lines = cp.strip().splitlines()
    assert lines[0].startswith("frames 250 ") and " wall left following d 115" in lines[0]
    # 5 mm inside the 12 cm set point: it turns away from the wall (right, clockwise).
    assert eval(lines[-1]) == ("following", "left", 1200, 600, True, 1150, True, 4)  # noqa: S307


def test_follow_refuses_until_standing_and_bad_values_change_nothing(rt):
    src = (
        SETUP
        + """
plug(0x40)
plug(0x41)
SONAR[0].set_distance(9000)  # nothing ahead
r = main.build(clock=clock)
out = [r.follow("left", 800)]  # relaxed
r.robot.stand_up()
frames(r, 2)
out.append(r.follow("right", 800))  # standing up
for args in (("middle", 800), ("left", 0), ("left", 800, 99999), ("left", 800, None, "wave")):
    try:
        r.follow(*args)
        out.append("accepted")
    except ValueError as e:
        out.append(str(e).split(":")[0])
frames(r, 150)
out.append((r.follower.mode_name, r.robot.mode, r.robot.walker.req_vx))
out.append(r.follow("right", 800))
frames(r, 10)
out.append((r.follower.mode_name, r.robot.mode))
print(out)
"""
    )
    out = rt.value(src, heapsize="4m")
    assert out == [22, 21, "side", "setpoint", "speed", "form", ("off", 3, 0), 0, ("following", 4)]
