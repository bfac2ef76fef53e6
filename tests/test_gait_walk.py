"""The walk on the real tick: straight and arc stances at constant speed, stops, switches, turns.

Every scenario runs on CPython and inside the MicroPython VM; the printed integers must be
identical, and then the properties are checked on them.
"""

import math

import pytest

from hexapod.gait import slot_ticks

TARGET = "scenarios.walk:"


def scenario(both_runtimes, name, *args):
    """Run scenarios.walk's name on both runtimes: bit-identical, no tick faulted; its rows."""
    cp, mp = both_runtimes.call(TARGET + name, *args)
    assert cp == mp
    faults, faulted, rows = cp
    assert faults == 0 and faulted == [], faulted
    return rows


def test_straight_stance_is_constant_speed(both_runtimes):
    rows = scenario(both_runtimes, "steady", 1111, 0, 0, 200, 100, ("su", "fx", "fy", "fz"))
    cmd, rows = rows[0], rows[1:]
    assert cmd == [1111, 0, 0]
    per_tick = 1111 * 16 * 20 / 1000  # fine units (0.1 mm / 16) per 20 ms
    for a, b in zip(rows, rows[1:], strict=False):
        for i in range(6):
            if a[i][0] < 0 and b[i][0] < 0:  # on the ground both ticks
                assert -(b[i][1] - a[i][1]) in (math.floor(per_tick), math.ceil(per_tick))
                assert b[i][2] == a[i][2] and b[i][3] == a[i][3]  # straight back, on the ground
    # Long-run speed is exact: the carries keep every remainder.
    stance = [r[0] for r in rows]
    assert any(s[0] >= 0 for s in stance) and any(s[0] < 0 for s in stance)


def test_turning_stance_is_an_arc_at_constant_rate(both_runtimes):
    vx, yaw = 600, 1100  # 60 mm/s, 11 deg/s: centre of the turn 312.5 mm to the left
    rows = scenario(both_runtimes, "steady", vx, 0, yaw, 200, 80, ("su", "fx", "fy"))
    cmd, rows = rows[0], rows[1:]
    assert cmd == [vx, 0, yaw]
    cy = vx / math.radians(yaw / 100) * 16  # turn centre on the body's y axis, fine units
    checked = 0
    for a, b in zip(rows, rows[1:], strict=False):
        for i in range(6):
            if a[i][0] < 0 and b[i][0] < 0:
                ra = math.hypot(a[i][1], a[i][2] - cy)
                rb = math.hypot(b[i][1], b[i][2] - cy)
                assert abs(ra - rb) <= 3  # fine units: 0.02 mm
                turn = math.atan2(b[i][2] - cy, b[i][1]) - math.atan2(a[i][2] - cy, a[i][1])
                # 0.22 degree per tick, backwards; the heading is read in whole cdeg (0.01).
                assert abs(math.degrees(turn) + yaw / 100 / 50) < 0.011
                checked += 1
    assert checked > 200
    # Over a whole stance the rate is exact to the heading's last cdeg.
    for i in range(6):
        run = [r[i] for r in rows]
        k = 0
        while k < len(run) and run[k][0] >= 0:
            k += 1
        j = k
        while j < len(run) and run[j][0] < 0:
            j += 1
        if j - k > 10:
            a, b = run[k], run[j - 1]
            turn = math.atan2(b[2] - cy, b[1]) - math.atan2(a[2] - cy, a[1])
            assert abs(math.degrees(turn) + yaw / 100 / 50 * (j - 1 - k)) < 0.011


def test_turn_in_place_pivots_about_the_body_centre(both_runtimes):
    rows = scenario(both_runtimes, "turn_in_place")
    for a, b in zip(rows, rows[1:], strict=False):
        assert a[0] == b[0] == 0 and a[1] == b[1] == 0  # the body centre does not travel
        for i in range(6):
            if a[2][i][0] < 0 and b[2][i][0] < 0:
                assert abs(math.hypot(*a[2][i][1:]) - math.hypot(*b[2][i][1:])) <= 3  # 0.02 mm


@pytest.mark.parametrize("gait", [0, 1, 2, 3])
def test_stop_finishes_the_step_and_lands_at_neutral(both_runtimes, gait):
    rows = scenario(both_runtimes, "stop", gait)
    (air, n, cycle), states, feet, (mode, faults) = rows
    assert air > 0  # the stop came with feet in the air
    assert n <= 3 * cycle
    assert feet == [[-1, 0, 0, 0]] * 6  # every foot down, exactly at neutral
    assert mode == 3 and faults == 0  # standing
    # STOPPED(0) -> STARTING(1) -> WALKING(2) -> STOPPING(3) -> STOPPED(0), in that order.
    compact = [states[0]] + [s for k, s in enumerate(states[1:]) if s != states[k]]
    assert compact == [1, 2, 3, 0]


def test_gait_switch_waits_for_all_feet_down(both_runtimes):
    rows = scenario(both_runtimes, "gait_switch")
    for target, now, n, _air_before, phase, air_after in rows:
        slot = slot_ticks(target, 1000)  # the scenario's robot walks every gait at 1 s
        assert now == target
        assert n < 200
        # The switch came at the end of a tick with every foot down; the new gait starts at one
        # of its slots (hexapod.gaitswitch.phase_in: the one whose lift order suits the feet).
        assert phase % slot == 0 and air_after == 0


def test_heading_form_matches_velocity_form(both_runtimes):
    rows = scenario(both_runtimes, "heading")
    for L, theta, half, cmd, scale, dx, dy in rows:
        assert scale == 1000
        a = math.radians(theta / 100)
        assert abs(cmd[0] - L * math.cos(a) * 1000 / half) <= 1
        assert abs(cmd[1] - L * math.sin(a) * 1000 / half) <= 1
        # Seed 003: the foot lands L along the heading: x = L cos(theta), y = L sin(theta).
        assert abs(dx - L * math.cos(a)) <= 3 and abs(dy - L * math.sin(a)) <= 3


@pytest.mark.parametrize("left,right", [(4500, 1000), (1000, 4500)])
def test_seed_000_turn_coxa_sweeps(both_runtimes, left, right):
    rows = scenario(both_runtimes, "sweeps", left, right)
    (scale, vx, yaw), (swept_left, swept_right) = rows
    assert scale == 1000 and vx > 0
    assert (yaw < 0) == (left > right)  # right turn: clockwise, negative yaw
    assert abs(swept_left - left) <= 30 and abs(swept_right - right) <= 30  # within 0.3 degree


def test_commands_beyond_reach_are_scaled_not_refused(both_runtimes):
    rows = scenario(both_runtimes, "beyond_reach")
    for cmd, scale, scaled, _step, _rho in rows:
        if cmd == [500, 0, 0]:
            assert scale == 1000 and scaled == cmd
        else:
            assert 0 < scale < 1000
            assert all(abs(s) <= abs(c) for s, c in zip(scaled, cmd, strict=True))


def test_a_leg_without_room_scales_the_walk_to_nothing(rt):
    got = rt.call(TARGET + "no_room")
    assert got == [0, [0, 0, 0]]


# robot.<method>(*args, **kwargs) while walking, and what its ValueError must say
BAD_WALKS = [
    ("walk", (3001, 0, 0), {}, "vx: 3001 0.1 mm/s is outside -3000..3000"),
    ("walk", (0, -3001, 0), {}, "vy"),
    ("walk", (0, 0, 9001), {}, "yaw_rate: 9001 cdeg/s"),
    ("walk", (1.5, 0, 0), {}, "vx: need a whole number"),
    ("walk", ("1", 0, 0), {}, "vx"),
    ("walk", (0, True, 0), {}, "vy: need a whole number"),
    ("walk_heading", (601, 0), {}, "length"),
    ("walk_heading", (-1, 0), {}, "length"),
    ("walk_heading", (100, 18001), {}, "heading"),
    ("walk_heading", (100, 1.0), {}, "heading"),
    ("walk_sweeps", (9001, 100), {}, "left sweep"),
    ("walk_sweeps", (100, -1), {}, "right sweep"),
    ("set_params", (), {"step_length": 49}, "step_length: 49 is outside 50..600"),
    ("set_params", (), {"step_length": 601}, "step_length"),
    ("set_params", (), {"lift_height": 99}, "lift_height"),
    ("set_params", (), {"lift_height": 601}, "lift_height"),
    ("set_params", (), {"cycle_ms": 499}, "cycle_ms"),
    ("set_params", (), {"cycle_ms": 5001}, "cycle_ms"),
    ("set_params", (), {"cycle_ms": "1000"}, "cycle_ms"),
    ("set_gait", (4,), {}, "gait"),
    ("set_gait", ("wave",), {}, "gait"),
    ("set_height", (599,), {}, "height"),
    ("set_height", (1001,), {}, "height"),
    ("set_height", (800.0,), {}, "height"),
    ("set_pose", (), {"x": 401}, "pose x"),
    ("set_pose", (), {"roll": -1501}, "pose roll"),
]


def test_bad_commands_raise_and_change_nothing(both_runtimes):
    rows = scenario(both_runtimes, "bad_calls", [call[:3] for call in BAD_WALKS])
    assert rows[-1] is True
    for (*call, message), text in zip(BAD_WALKS, rows[:-1], strict=True):
        assert message in text, (call, text)


def test_changes_the_feet_would_not_notice_do_not_wait(rt):
    got = rt.call(TARGET + "changes_in_flight")
    assert got == [[0, True], [0, 200, True], [1, 300, 400], [0, 400]]


@pytest.mark.parametrize("gait", ["tripod", "ripple", "wave"])
@pytest.mark.parametrize("vx,vy,yaw", [(1111, 0, 0), (-800, 500, 0), (0, 0, 2000)])
def test_swing_leaves_and_meets_the_ground_at_the_stance_speed(both_runtimes, gait, vx, vy, yaw):
    # The swing ends moving as the stance feet do (Hermite velocity terms), so a foot that
    # touches down a tick early or lifts a tick late does not fight the stance. Oracle: the
    # rigid ground motion under the body, from the command alone (float).
    rows = scenario(both_runtimes, "swing_ends", ["tripod", "tetrapod", "ripple", "wave"].index(gait), vx, vy, yaw)
    (swing, cvx, cvy, cyaw), rows = rows[0], rows[1:]
    assert (cvx, cvy, cyaw) != (0, 0, 0)  # (the longer stances of ripple and wave scale it down)
    dt = 0.02
    w = math.radians(cyaw / 100.0)

    def ground(x, y):  # fine units per tick, at body point (x, y) fine
        return (-(cvx * 16 * dt) + w * dt * y, -(cvy * 16 * dt) - w * dt * x)

    checked = 0
    for a, b in zip(rows, rows[1:], strict=False):
        for i in range(6):
            if a[i][0] < 0 and b[i][0] == 1:  # lift-off: the first tick of the swing
                d, (gx, gy) = (b[i][1] - a[i][1], b[i][2] - a[i][2]), ground(a[i][1], a[i][2])
            elif a[i][0] == swing - 1 and b[i][0] < 0:  # the landing tick
                d, (gx, gy) = (b[i][1] - a[i][1], b[i][2] - a[i][2]), ground(b[i][1], b[i][2])
            else:
                continue
            # Before this change the first and last ticks moved the foot with the body (0 %,
            # or the sine's tail forward); now exactly as the stance (rounding, and the
            # turn's per-tick arc taken as straight: 1 %).
            g = math.hypot(gx, gy)
            assert math.hypot(d[0] - gx, d[1] - gy) <= 0.01 * g + 3, (i, d, (gx, gy))
            checked += 1
    assert checked >= 6
