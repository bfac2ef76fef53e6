"""The control tick: pulses through the servo maps, overrun counting, refusals that move
nothing, gradual posture moves, and a steady tick that allocates nothing in the VM."""

import ast

import pytest

SETUP = """
import robots.default as d
from hexapod import geometry, tick
from hexapod.servo import ServoMap
g = geometry.load(d)
frame = tick.FrameBuffer()
robot = tick.Robot(g, tick.default_servos(g), frame)
w = robot.walker
T = [0]
def run(n):
    for _ in range(n):
        robot.tick(T[0])
        T[0] += 20
def stand():
    robot.stand_up()
    while robot.mode != tick.STANDING:
        run(1)
"""


def lines(text):
    return [ast.literal_eval(line) for line in text.splitlines() if line.strip()]


def test_pulses_follow_the_servo_maps(rt):
    rows = lines(
        rt.run(
            SETUP
            + """
stand()
robot.walk(900, 200, 500)
for _ in range(40):
    run(1)
    raw = [robot.servos[k].raw(robot.angles[k]) for k in range(18)]
    print([list(robot.angles), list(frame.pulses), raw, frame.frames, robot.ticks])
"""
        )
    )
    for _angles, pulses, raw, frames, ticks in rows:
        assert pulses == raw  # every pulse is its servo map's width for the joint angle
        assert frames == ticks  # one frame per tick
        assert all(600 <= p <= 2400 for p in pulses)
    assert rows[0][1] != rows[-1][1]


def test_overruns_are_counted_and_nothing_is_skipped(rt):
    got = rt.value(
        SETUP
        + """
stand()
robot.walk(1000, 0, 0)
base = robot.overruns
phases = []
for now in (100000, 100020, 100040, 100075, 100095, 100195, 100215):
    robot.tick(now)
    phases.append(w.phase)
late = robot.overruns - base
# time.ticks_ms() wraps at 2**30: 20 ms across the wrap is on time.
robot.tick(2**30 - 10)
robot.tick(10)
print([late, robot.worst_interval_ms, robot.overruns - base, phases])
"""
    )
    late, worst, total, phases = got
    assert late == 3  # the 35 ms, the 100 ms, and the jump from the stand-up clock to 100000
    assert worst >= 100
    assert total == 4  # the jump to 2**30 - 10 is late; across the wrap it is on time
    steps = [(b - a) % 1000 for a, b in zip(phases, phases[1:], strict=False)]
    assert all(s == 1 or b == 0 for s, b in zip(steps, phases[1:], strict=True))  # one frame per tick


REFUSALS = [
    ("sitting", "", "robot.walk(500, 0, 0)", "NOT_STANDING"),
    ("sitting", "", "robot.set_pose(z=100)", "NOT_STANDING"),
    ("moving", "robot.stand_up()\nrun(3)", "robot.walk(500, 0, 0)", "BUSY"),
    ("moving", "robot.stand_up()\nrun(3)", "robot.sit_down()", "BUSY"),
    ("moving", "robot.stand_up()\nrun(3)", "robot.set_height(700)", "BUSY"),
    ("walking", "stand()\nrobot.walk(800, 0, 0)\nrun(20)", "robot.stand_up()", "WALKING_NOW"),
    ("walking", "stand()\nrobot.walk(800, 0, 0)\nrun(20)", "robot.sit_down()", "WALKING_NOW"),
    ("walking", "stand()\nrobot.walk(800, 0, 0)\nrun(20)", "robot.relax()", "WALKING_NOW"),
    ("walking", "stand()\nrobot.walk(800, 0, 0)\nrun(20)", "robot.set_pose(roll=300)", "WALKING_NOW"),
    ("walking", "stand()\nrobot.walk(800, 0, 0)\nrun(20)", "robot.set_height(900)", "WALKING_NOW"),
    ("walking", "stand()\nrobot.walk(800, 0, 0)\nrun(20)", "robot.assume_angles([0] * 18)", "WALKING_NOW"),
    ("posing", "stand()\nrobot.set_pose(roll=1000)\nrun(2)", "robot.walk(500, 0, 0)", "BUSY"),
    ("posing", "stand()\nrobot.set_pose(roll=1000)\nrun(2)", "robot.stand_up()", "BUSY"),
    ("standing", "stand()", "robot.set_pose(-400, -400, 0, -1500, -1500, -1500, 2000, 2000, -2000)", "UNREACHABLE"),
    (
        "low",
        "stand()\nrobot.set_pose(0, 0, -400, 1500, 0, 0, 0, 0, 0)\nrun(40)",
        "robot.walk(500, 0, 0)",
        "UNREACHABLE",
    ),
    (
        "leaning",
        "stand()\nrobot.set_params(lift_height=100)\nrobot.set_pose(0, 0, -300, 800, 0, 0, 0, 0, 0)\nrun(40)\n"
        "robot.walk(500, 0, 0)\nrun(10)",
        "robot.set_params(lift_height=600)",
        "UNREACHABLE",
    ),
]


@pytest.mark.parametrize("state,prep,call,code", REFUSALS)
def test_refusals_move_nothing(rt, state, prep, call, code):
    got = lines(
        rt.run(
            SETUP
            + prep
            + """
snap = lambda: [robot.mode, w.state, list(w.cmd), list(robot.body.target), w.ground,
                list(w.fx), list(w.fz), robot.posture.sets, w.lift, w.next_lift, list(w.rho), w.pending]
before = snap()
print([%s, tick.%s])
print([before == snap()])
print(list(frame.pulses))
"""
            % (call, code)
        )
    )
    (result, expected), (unchanged,), pulses = got
    assert result == expected
    assert unchanged
    assert result != 0


def test_stand_up_from_anywhere_moves_gradually(rt):
    rows = lines(
        rt.run(
            SETUP
            + """
# A sprawled leg set: every leg somewhere else, declared as joint angles.
robot.assume_angles([3000, 2000, -4000, -2500, -3000, -6000, 0, 4000, -9000,
                     2000, -1000, -12000, 1500, 3000, -3000, -3000, 1000, -8000])
robot.stand_up()
prev_a = None
prev_f = None
while robot.mode != tick.STANDING:
    run(1)
    feet = [[w.fx[i], w.fy[i], w.fz[i]] for i in range(6)]
    if prev_a is not None:
        da = max(abs(robot.angles[k] - prev_a[k]) for k in range(18))
        df = max(max(abs(feet[i][j] - prev_f[i][j]) for j in range(3)) for i in range(6))
        print([da, df])
    prev_a = list(robot.angles)
    prev_f = feet
print([[w.fx[i] - w.nx[i], w.fy[i] - w.ny[i], w.fz[i] - w.ground] for i in range(6)])
print([robot.faults, robot.ticks])
"""
        )
    )
    steps, final, (faults, _ticks) = rows[:-2], rows[-2], rows[-1]
    assert faults == 0
    assert final == [[0, 0, 0]] * 6  # standing at the neutral stance
    assert len(steps) > 30
    assert max(s[1] for s in steps) <= 20 * 16 + 1  # at most 2 mm per axis per tick (fine units)
    assert max(s[0] for s in steps) <= 500  # no joint moves more than 5 degrees in a frame


def test_sit_relax_and_height(rt):
    rows = lines(
        rt.run(
            SETUP
            + """
stand()
print([robot.set_height(1000), robot.mode])
n = 0
worst = 0
prev = list(robot.angles)
while robot.mode != tick.STANDING:
    run(1)
    n += 1
    worst = max(worst, max(abs(robot.angles[k] - prev[k]) for k in range(18)))
    prev = list(robot.angles)
print([n, worst, [w.fz[i] >> 4 for i in range(6)]])
print([robot.walk(1000, 0, 0)])
run(100)
robot.stop()
run(200)
print([robot.relax(), robot.mode])
run(200)
print([robot.mode, list(frame.pulses), robot.faults])
print([robot.stand_up(), robot.mode])
run(200)
print([robot.mode, [w.fz[i] >> 4 for i in range(6)], robot.faults])
"""
        )
    )
    assert rows[0] == [0, 2]  # accepted, moving
    n, worst, zs = rows[1]
    assert zs == [-1000] * 6 and 10 <= n <= 12 and worst <= 500  # 20 mm at 2 mm per tick
    assert rows[2] == [0]
    assert rows[3] == [0, 2]
    mode, pulses, faults = rows[4]
    assert mode == 0 and pulses == [0] * 18 and faults == 0  # relaxed: no pulses, servos limp
    assert rows[5] == [0, 2]
    assert rows[6] == [3, [-1000] * 6, 0]  # standing again at the chosen height


def test_a_frame_that_needs_a_clamp_is_held(rt):
    got = rt.value(
        SETUP
        + """
stand()
good = list(frame.pulses)
frames = frame.frames
# Recalibrate one femur servo so tightly that the standing angle is outside it.
robot.servos[4] = ServoMap(centre_us=1500, min_us=1400, max_us=1500)
code = robot.tick(T[0])
print([code == tick.FRAME_SERVO, robot.faults, robot.fault_leg, frame.frames == frames,
       list(frame.pulses) == good, tick.describe(code)])
"""
    )
    held, faults, leg, no_frame, kept, text = got
    assert held and faults == 1 and leg == 2 and no_frame and kept
    assert "pulse" in text


def test_robot_construction_errors():
    import robots.default as d
    from hexapod import geometry, tick

    g = geometry.load(d)
    with pytest.raises(ValueError, match="need 18 ServoMaps"):
        tick.Robot(g, tick.default_servos(g)[:17], tick.FrameBuffer())
    with pytest.raises(ValueError, match="write_frame"):
        tick.Robot(g, tick.default_servos(g), object())
    with pytest.raises(ValueError, match="pulses: need a list of 18"):
        tick.Robot(g, tick.default_servos(g), tick.FrameBuffer(), [0] * 16)
    mine = [0] * 18
    robot = tick.Robot(g, tick.default_servos(g), tick.FrameBuffer(), mine)
    robot.stand_up()
    for k in range(100):
        robot.tick(20 * k)
    assert robot.pulses is mine and mine == robot.frame.pulses and min(mine) > 0
    with pytest.raises(ValueError, match="need 18 values"):
        tick.Robot(g, tick.default_servos(g), tick.FrameBuffer()).assume_angles([0] * 17)


ALLOC = """
import gc
import robots.default as d
from hexapod import geometry, tick
g = geometry.load(d)
robot = tick.Robot(g, tick.default_servos(g), tick.FrameBuffer())
T = [0]
def run(n):
    for _ in range(n):
        robot.tick(T[0])
        T[0] += 20
robot.stand_up()
run(5)
a = stand_bytes = walk_bytes = 0  # globals made before measuring: a new global can grow the dict
gc.collect()
gc.disable()
a = gc.mem_alloc()
while robot.mode != tick.STANDING:
    run(1)
stand_bytes = gc.mem_alloc() - a
gc.enable()
print(["stand", stand_bytes])
for gait in range(4):
    robot.set_gait(gait)
    robot.walk(800, 100, 1200)
    run(150)
    gc.collect()
    gc.disable()
    a = gc.mem_alloc()
    for n in range(400):
        # Speed and turn change every tick, through the command path as a PID loop would.
        robot.walk(600 + (n * 7) % 900, (n * 13) % 400 - 200, ((n * 37) % 4000) - 2000)
        robot.tick(T[0])
        T[0] += 20
    walk_bytes = gc.mem_alloc() - a
    gc.enable()
    robot.stop()
    while robot.mode == tick.WALKING:
        run(1)
    print([gait, walk_bytes, robot.faults])
# The extremes: longest cycle, largest step and lift, the commands at their limits.
robot.set_params(step_length=600, lift_height=600, cycle_ms=5000)
for gait in range(4):
    robot.set_gait(gait)
    robot.walk(3000, -3000, 9000)
    run(100)
    gc.collect()
    gc.disable()
    a = gc.mem_alloc()
    for n in range(300):
        s = 1 if (n // 50) % 2 else -1
        robot.walk(3000 * s, -3000, -9000 * s)
        robot.tick(T[0])
        T[0] += 20
    walk_bytes = gc.mem_alloc() - a
    gc.enable()
    robot.stop()
    while robot.mode == tick.WALKING:
        run(1)
    print([gait, walk_bytes, robot.faults])
"""


def test_steady_tick_allocates_nothing(mp):
    rows = lines(mp.run(ALLOC, heapsize="256k"))
    assert rows[0] == ["stand", 0]
    assert [r[0] for r in rows[1:]] == [0, 1, 2, 3] * 2
    for gait, walk_bytes, faults in rows[1:]:
        assert walk_bytes == 0, gait
        assert faults == 0
