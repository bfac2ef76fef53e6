"""The control tick: pulses through the servo maps, overrun counting, refusals that move
nothing, gradual posture moves, and a steady tick that allocates nothing in the VM."""

import pytest


def test_pulses_follow_the_servo_maps(rt):
    rows = rt.call("scenarios.tick:pulses_while_walking")
    for _angles, pulses, raw, frames, ticks in rows:
        assert pulses == raw  # every pulse is its servo map's width for the joint angle
        assert frames == ticks  # one frame per tick
        assert all(600 <= p <= 2400 for p in pulses)
    assert rows[0][1] != rows[-1][1]


def test_overruns_are_counted_and_nothing_is_skipped(rt):
    late, worst, total, phases = rt.call("scenarios.tick:overruns")
    assert late == 3  # the 35 ms, the 100 ms, and the jump from the stand-up clock to 100000
    assert worst >= 100
    assert total == 4  # the jump to 2**30 - 10 is late; across the wrap it is on time
    steps = [(b - a) % 1000 for a, b in zip(phases, phases[1:], strict=False)]
    assert all(s == 1 or b == 0 for s, b in zip(steps, phases[1:], strict=True))  # one frame per tick


# (state the robot is brought to, then robot.<method>(*args, **kwargs), the code it must refuse with)
REFUSALS = [
    ("sitting", "walk", (500, 0, 0), {}, "NOT_STANDING"),
    ("sitting", "set_pose", (), {"z": 100}, "NOT_STANDING"),
    ("moving", "walk", (500, 0, 0), {}, "BUSY"),
    ("moving", "sit_down", (), {}, "BUSY"),
    ("moving", "set_height", (700,), {}, "BUSY"),
    ("walking", "stand_up", (), {}, "WALKING_NOW"),
    ("walking", "sit_down", (), {}, "WALKING_NOW"),
    ("walking", "relax", (), {}, "WALKING_NOW"),
    ("walking", "set_pose", (), {"roll": 300}, "WALKING_NOW"),
    ("walking", "set_height", (900,), {}, "WALKING_NOW"),
    ("walking", "assume_angles", ([0] * 18,), {}, "WALKING_NOW"),
    ("posing", "walk", (500, 0, 0), {}, "BUSY"),
    ("posing", "stand_up", (), {}, "BUSY"),
    ("standing", "set_pose", (-400, -400, 0, -1500, -1500, -1500, 2000, 2000, -2000), {}, "UNREACHABLE"),
    ("low", "walk", (500, 0, 0), {}, "UNREACHABLE"),
    ("leaning", "set_params", (), {"lift_height": 600}, "UNREACHABLE"),
]


@pytest.mark.parametrize("state,method,args,kwargs,code", REFUSALS)
def test_refusals_move_nothing(rt, state, method, args, kwargs, code):
    result, expected, unchanged, _pulses = rt.call("scenarios.tick:refusal", state, method, args, kwargs, code)
    assert result == expected
    assert unchanged
    assert result != 0


def test_stand_up_from_anywhere_moves_gradually(rt):
    steps, final, (faults, _ticks) = rt.call("scenarios.tick:stand_up_from_anywhere")
    assert faults == 0
    assert final == [[0, 0, 0]] * 6  # standing at the neutral stance
    assert len(steps) > 30
    assert max(s[1] for s in steps) <= 20 * 16 + 1  # at most 2 mm per axis per tick (fine units)
    assert max(s[0] for s in steps) <= 500  # no joint moves more than 5 degrees in a frame


def test_sit_relax_and_height(rt):
    rows = rt.call("scenarios.tick:sit_relax_and_height")
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
    held, faults, leg, no_frame, kept, text = rt.call("scenarios.tick:clamped_frame")
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


def test_steady_tick_allocates_nothing(mp):
    rows = mp.call("scenarios.tick:steady_tick_heap")
    assert rows[0] == ["stand", 0]
    assert [r[0] for r in rows[1:]] == [0, 1, 2, 3] * 2
    for gait, walk_bytes, faults in rows[1:]:
        assert walk_bytes == 0, gait
        assert faults == 0
