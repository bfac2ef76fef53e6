"""hexapod.follow: the wall follower's decisions in hand-worked situations, fed round-robin sonar
cycles the way runner.Runner feeds it, on a standing Robot. Every case runs for the left wall and
mirrored for the right one; a scripted tour of them is bit-identical on both runtimes."""

import copy
import math

import pytest
from scenarios.rig import Rig as StandRig

import robots.default
from drivers import hcsr04
from hexapod import follow, geometry, pid, robotcal, sensors, tick
from hexapod.turns import sweep_command

SLOTS = (0, 4, 1, 3, 2)  # drivers.hcsr04.plan for five sensors at 20 ms: front, RR, LF, RF, LR
OOR, NOECHO, STUCK, CLOSE = -1, -2, -3, -4  # a reading given as minus an hcsr04 status
SP = 800  # 8 cm set point
W = 2100 + SP  # body centre to the wall, 0.1 mm
CORNER_AT = W + follow.CORNER_RADIUS - 1300  # front readings that start a corner / block
STOP_AT = follow.FRONT_STOP - 1300


_STANDING = []


def standing_robot():
    """A Robot standing at its neutral stance (a copy of one stood up once) and the loop time."""
    if not _STANDING:
        rig = StandRig()
        rig.stand()
        _STANDING.append((rig.robot, rig.t))
    robot, t = _STANDING[0]
    # The robot's guard table is a module (robots/default_guard.py): shared, not copied.
    table = getattr(robot, "_table", None)
    return copy.deepcopy(robot, {} if table is None else {id(table): table}), t


class Rig:
    """A standing robot and its follower; cycle() feeds one 100 ms round robin of readings."""

    def __init__(self, side="left", setpoint=SP, speed=None, form="yaw"):
        self.robot, self.t = standing_robot()
        self.f = follow.Follower(self.robot)
        self.side = side
        self.dist = [hcsr04.NO_DISTANCE] * 5
        self.status = [hcsr04.WAIT] * 5
        assert self.f.follow(side, setpoint, speed, form) == 0

    def cycle(self, front=OOR, near=SP, far=SP, n=1):
        """Readings for n cycles: front, the followed side's front (`near`) and rear (`far`)
        sensor; the other side reads nothing. Mirrored for the right wall."""
        side = (near, far, OOR, OOR) if self.side == "left" else (OOR, OOR, near, far)
        want = (front,) + side
        for _ in range(n):
            for k in SLOTS:
                v = want[k]
                self.status[k] = hcsr04.OK if v >= 0 else -v
                self.dist[k] = v if v >= 0 else hcsr04.NO_DISTANCE
                self.f.update(self.t, k, self.dist, self.status)
                self.robot.tick(self.t)
                self.t += 20
        return self.f

    def away(self, yaw):
        """yaw (cdeg/s) as 'turning away from the wall' (positive) for either side."""
        return -yaw if self.side == "left" else yaw


SIDES = ["left", "right"]


def test_the_round_robin_mounts_and_gains_the_rig_assumes():
    # The order, names and codes are hexapod.sensors' alone (tests/test_sensors.py); the rig's
    # slot table and mounts are the driver's plan and the robot file's.
    assert hcsr04.plan(5, 20, hcsr04.NEIGHBOURS, 60, 38) == SLOTS
    assert robotcal.sensor_mounts(robotcal.load("default")) == sensors.DEFAULT_MOUNTS
    assert (pid.KP, pid.KI, pid.KD) == (25000, 500, 1000)  # seed 000's Kp = 25, Ki = 0.5, Kd = 1


@pytest.mark.parametrize("side", SIDES)
def test_parallel_at_the_set_point_walks_straight(side):
    rig = Rig(side)
    f = rig.cycle(n=5)
    assert (f.mode_name, f.distance, f.angle, f.error, f.output, f.vx, f.yaw) == ("following", SP, 0, 0, 0, 800, 0)
    assert f.used == side + "_front+" + side + "_rear" and not f.distance_only and f.updates == 5
    assert f.pid.ts_ms == 100  # one update per round robin: both sensors fresh


@pytest.mark.parametrize("side", SIDES)
def test_the_pair_estimate_is_the_walks_prediction_corrected_by_an_8th(side):
    # A float oracle of the estimator (issue 22 point 5): between two pair samples the angle to the
    # wall moves by the walker's own heading change (away from the wall opens it) and the distance by
    # the forward travel at that angle (sum of the walked speed x 20 ms x sin angle); each sample then
    # pulls both 1/8 of the way toward what the sonars read. Readings 76 mm, parallel: the robot
    # turns away, the readings do not change.
    rig = Rig(side)
    f = rig.f
    away = 1 if side == "right" else -1  # the walker's yaw sign that turns away from this wall
    walker = rig.robot.walker
    angle, dist = None, None  # degrees, 0.1 mm
    psi, walked, held = walker.psi, 0, walker.held
    want = (0, SP - 40, SP - 40, OOR, OOR) if side == "left" else (0, OOR, OOR, SP - 40, SP - 40)
    for _ in range(6):
        for k in SLOTS:
            rig.status[k] = hcsr04.OK if k and want[k] >= 0 else hcsr04.OUT_OF_RANGE
            rig.dist[k] = want[k] if k and want[k] >= 0 else hcsr04.NO_DISTANCE
            n = f.updates
            f.update(rig.t, k, rig.dist, rig.status)
            if walker.held == held:  # the body moved in the last tick (a held tick moves nothing)
                walked += walker.vel[0]
            held = walker.held
            if f.updates > n and angle is None:
                assert (f.distance, f.angle) == (760, 0)  # the first sample is taken as it is
                angle, dist = 0.0, 760.0
                psi, walked = walker.psi, 0
            elif f.updates > n:  # a sample: predict from the walk since the last one, then correct
                turn = ((walker.psi - psi + 1800000) % 3600000 - 1800000) / 10000
                angle += away * turn
                dist += walked * 0.02 * math.sin(math.radians(angle))
                angle += (0.0 - angle) / 8
                dist += (760 - dist) / 8
                psi, walked = walker.psi, 0
                assert abs(f.angle - angle * 100) <= 1 and abs(f.distance - dist) <= 1, (f.angle, f.distance)
            rig.robot.tick(rig.t)
            rig.t += 20
    assert angle > 0.5 and dist > 761  # it did turn away, and the prediction moved the wall out


@pytest.mark.parametrize("side", SIDES)
def test_angled_toward_and_away_turn_the_right_way(side):
    # Nose toward the wall: front sensor 78 mm, rear 82 mm. angle = atan(-4 / 200) = -1.15 deg;
    # e = (80 - 80) - 100 mm * sin(-1.15 deg) = 2.0 mm -> first sample P only: u = 25 * 20 = 500, away.
    rig = Rig(side)
    f = rig.cycle(near=780, far=820)
    assert (f.distance, f.angle, f.error, f.output) == (800, -115, 20, 500)
    assert rig.away(f.yaw) == 500
    rig = Rig(side)
    f = rig.cycle(near=820, far=780)  # nose away: turn toward
    assert (f.angle, f.error, f.output) == (115, -20, -500) and rig.away(f.yaw) == -500


@pytest.mark.parametrize("side", SIDES)
def test_too_close_and_too_far_when_parallel(side):
    rig = Rig(side)
    f = rig.cycle(near=760, far=760)  # 4 mm close: u = 25 * 40
    assert (f.error, f.output, rig.away(f.yaw)) == (40, 1000, 1000)
    # The next sample: the robot has begun turning away, so the walk's prediction puts the look-ahead
    # point farther out than the unchanged readings say (test_the_pair_estimate_...): less error, still away.
    f = rig.cycle(near=760, far=760)
    assert 0 < f.error < 40 and 0 < f.output < 1000 and rig.away(f.yaw) == f.output
    rig = Rig(side)
    f = rig.cycle(near=900, far=900)  # 1 cm far: 250 per mm would be 2500, toward
    assert rig.away(f.yaw) == -2500
    rig = Rig(side)
    f = rig.cycle(near=1000, far=1000)  # 2 cm far: clamped at the follower's largest yaw rate
    assert rig.away(f.yaw) == -follow.YAW_MAX


@pytest.mark.parametrize("side", SIDES)
def test_the_angle_guard_holds_the_angle_inside_the_beam(side):
    # Nose 8.5 deg away (readings 70 and 40 mm: atan(30 / 200)) and close: d = 55 mm,
    # e = 25 - 100 sin(8.53 deg) = 10.17 mm would turn further away; past 8 degrees it holds instead.
    rig = Rig(side)
    f = rig.cycle(near=700, far=400)
    assert (f.angle, f.error, f.pid.output, f.output, f.yaw) == (853, 102, 2550, 0, 0)
    rig = Rig(side)
    # 14 deg toward and far (85 and 135 mm): e = 80 - 110 + 100 sin(14.04 deg) = -5.75 mm, no further turn toward
    f = rig.cycle(near=850, far=1350)
    assert (f.angle, f.error, f.pid.output, f.output, f.yaw) == (-1404, -57, -1425, 0, 0)
    rig = Rig(side)
    f = rig.cycle(near=400, far=700)  # 8.5 deg toward and close: turning away is always allowed
    assert f.output == follow.YAW_MAX and rig.away(f.yaw) == follow.YAW_MAX


@pytest.mark.parametrize("side", SIDES)
def test_on_one_sonar_past_the_guard_the_turn_toward_the_wall_goes_on(side):
    # An outside corner: 14 deg toward and far on the pair (guarded: no turn), then the front
    # sonar loses the wall. On the rear one alone the angle is odometry (fading by 1/16 an update,
    # still past the guard) and the wall's end draws away: the robot must keep turning toward it
    # (the corridor world's outside corner: the guard stopped it there, 6.6 % of 500 trials ended
    # too far).
    rig = Rig(side)
    f = rig.cycle(near=850, far=1350)
    assert (f.angle, f.output) == (-1404, 0)
    f = rig.cycle(near=NOECHO, far=1350, n=3)
    assert f.distance_only and f.used == side + "_rear" and f.angle <= -follow.ANGLE_GUARD
    # 135 mm on the rear sonar (100 mm behind the pair's middle), nose a degrees toward the wall,
    # 8 <= a <= 14.04: the look-ahead point (100 mm ahead) is 135 - 200 sin a = 86.5..107.2 mm out,
    # 6.5..27.2 mm too far: turn toward it.
    assert -272 <= f.error <= -65 and f.output < 0 and rig.away(f.yaw) < 0


@pytest.mark.parametrize("side", SIDES)
def test_inside_corner_turns_away_in_time_then_follows(side):
    rig = Rig(side)
    f = rig.cycle(front=CORNER_AT + 1, n=2)
    assert f.mode_name == "following" and f.yaw == 0
    f = rig.cycle(front=CORNER_AT - 1)
    # An arc of CORNER_RADIUS away from the wall: 80 mm/s * 5730 / 250 mm = 1833 cdeg/s.
    assert (f.mode_name, f.vx, rig.away(f.yaw)) == ("corner", 800, 1833)
    f = rig.cycle(front=CORNER_AT + follow.CORNER_HYST - 1, n=3)
    assert f.mode_name == "corner" and f.turned * (1 if side == "right" else -1) > 0
    n = f.updates
    f = rig.cycle(front=OOR)  # the wall ahead has gone by: following again, PID afresh
    assert f.mode_name == "following" and f.updates == n + 1 and f.pid.samples == 1


@pytest.mark.parametrize("side", SIDES)
def test_something_too_close_in_front_stops_the_robot_until_it_clears(side):
    rig = Rig(side)
    rig.cycle(n=2)
    f = rig.cycle(front=STOP_AT - 1)
    assert (f.mode_name, f.reason_name, f.vx, f.yaw) == ("blocked", "obstacle ahead", 0, 0)
    assert rig.robot.walker.state == 3  # stopping: finishing the steps, feet set down
    f = rig.cycle(front=STOP_AT + follow.FRONT_HYST - 1, n=40)
    assert f.mode_name == "blocked" and rig.robot.mode == tick.STANDING
    f = rig.cycle(front=OOR)
    assert f.mode_name == "following" and rig.robot.mode == tick.WALKING and f.vx == 800


@pytest.mark.parametrize("side", SIDES)
def test_a_lost_wall_turns_toward_where_it_was_then_searches_then_stops(side):
    rig = Rig(side)
    rig.cycle(n=3)
    f = rig.cycle(near=OOR, far=OOR, n=2)
    assert f.mode_name == "following"  # two misses: still the same wall, no new reading to steer on
    f = rig.cycle(near=OOR, far=OOR)
    # Third miss: lost. Arc toward the wall with its distance as radius: 800 * 5730 / 2900.
    assert (f.mode_name, f.used, f.vx, rig.away(f.yaw)) == ("lost", "none", 800, -1580)
    assert f.state[1:3] == [follow.NO_WALL] * 2 or f.state[3:5] == [follow.NO_WALL] * 2
    turned = 0
    while f.mode_name == "lost":
        turned = f.turned
        rig.cycle(near=OOR, far=OOR)
    start = rig.t  # the search began within the last 100 ms
    assert f.mode_name == "searching"
    assert follow.LOST_TURN - 300 < turned * (1 if side == "left" else -1) <= follow.LOST_TURN  # toward the wall
    yaw = rig.away(f.yaw)
    rig.cycle(near=OOR, far=OOR, n=50)
    assert -yaw > -rig.away(f.yaw) > 0  # the spiral widens
    while f.mode_name == "searching":
        rig.cycle(near=OOR, far=OOR)
    assert (f.mode_name, f.reason_name) == ("stopped", "wall not found")
    assert follow.SEARCH_MS - 100 <= rig.t - start <= follow.SEARCH_MS + 100
    rig.cycle(n=3)
    assert f.mode_name == "stopped"  # for good: follow() again to restart


@pytest.mark.parametrize("side", SIDES)
def test_a_wall_found_again_is_followed(side):
    rig = Rig(side)
    f = rig.cycle(near=OOR, far=OOR, n=4)
    assert f.mode_name == "lost"
    f = rig.cycle(near=900, far=OOR)
    assert (f.mode_name, f.used, f.distance_only) == ("following", side + "_front", True)
    f = rig.cycle(near=900, far=900, n=2)  # the rear one joins: the pair from the next pair on
    assert (f.mode_name, f.distance_only) == ("following", False)
    # A fresh estimate from the first pair (900, 0), then an 8th of the way from the walk's prediction
    # (the robot turned toward the wall in the 100 ms between) back to the readings.
    assert abs(f.distance - 900) <= 2 and abs(f.angle) < 100


@pytest.mark.parametrize("side", SIDES)
def test_one_failed_side_sensor_follows_on_distance_alone_and_says_so(side):
    rig = Rig(side)
    rig.cycle(n=2)
    f = rig.cycle(near=NOECHO, n=2)
    assert not f.distance_only and f.updates == 2  # not steered on, and no update without it
    f = rig.cycle(near=NOECHO)
    assert f.distance_only and f.used == side + "_rear" and f.state[1 if side == "left" else 3] == follow.FAILED
    assert f.faults == ([0, 3, 0, 0, 0] if side == "left" else [0, 0, 0, 3, 0]) and f.fault_total == 3
    n = f.updates
    f = rig.cycle(near=NOECHO, far=760)  # 4 mm close on the rear sensor alone, parallel: away
    assert f.updates == n + 1 and f.distance == 760 and f.error == 40 and rig.away(f.yaw) > 0
    assert "distance only" in follow.status_text(f) and "faults 4" in follow.status_text(f)
    f = rig.cycle(near=800, far=800)  # it answers again: back on the pair
    assert not f.distance_only and f.used == side + "_front+" + side + "_rear"


@pytest.mark.parametrize("side", SIDES)
@pytest.mark.parametrize("bad", [STUCK, OOR, 800 + follow.WALL_GAP + 1])
def test_the_other_sensor_faults(side, bad):
    rig = Rig(side)
    rig.cycle(n=2)
    f = rig.cycle(far=bad, n=3)
    assert f.distance_only and f.used == side + "_front" and f.mode_name == "following"
    assert f.state[2 if side == "left" else 4] == (follow.FAILED if bad == STUCK else follow.NO_WALL)
    assert f.fault_total == (3 if bad == STUCK else 0)  # out of range / no wall is no fault


@pytest.mark.parametrize("side", SIDES)
def test_a_dropout_is_skipped_not_fed_twice(side):
    rig = Rig(side)
    f = rig.cycle(near=780, far=780, n=2)
    n, i = f.updates, f.pid.i
    f = rig.cycle(near=NOECHO, far=780)
    assert f.updates == n and f.pid.i == i and not f.distance_only  # nothing new to steer on
    f = rig.cycle(near=780, far=780)
    # Both fresh again at the later of the two pings: left_front (slot 2) comes after the rear
    # reading of the dropped cycle, 160 ms after the last pair; right_front (slot 3) follows
    # right_rear (slot 1) in the same cycle, 200 ms after. Each reading is fed once.
    ts = 160 if side == "left" else 200
    assert f.updates == n + 1 and f.pid.ts_ms == ts
    assert abs(f.pid.i - (i + 0.5 * ts / 1000 * f.error)) <= 1  # + Ki Ts e, over the longer interval


@pytest.mark.parametrize("side", SIDES)
def test_a_reading_that_jumps_away_is_an_edge_not_the_wall(side):
    rig = Rig(side)
    rig.cycle(n=2)
    f = rig.cycle(near=800 + follow.JUMP + 1)
    assert f.updates == 2 and f.reading[1 if side == "left" else 3] == 800
    f = rig.cycle(near=800 + follow.JUMP)
    assert f.updates == 3 and f.reading[1 if side == "left" else 3] == 800 + follow.JUMP


@pytest.mark.parametrize("side", SIDES)
def test_both_side_sensors_failed_stop_and_report(side):
    rig = Rig(side)
    rig.cycle(n=2)
    f = rig.cycle(near=NOECHO, far=STUCK, n=3)
    assert (f.mode_name, f.reason_name) == ("stopped", "both side sensors failed")
    assert rig.robot.walker.state == 3 and f.fault_total == 6
    assert "stopped (both side sensors failed)" in follow.status_text(f)


@pytest.mark.parametrize("side", SIDES)
def test_front_failed_and_side_too_close_stop(side):
    rig = Rig(side)
    f = rig.cycle(front=NOECHO, n=2)
    assert f.mode_name == "following"
    f = rig.cycle(front=STUCK)
    assert (f.mode_name, f.reason_name) == ("stopped", "front sensor failed")
    rig = Rig(side)
    f = rig.cycle(far=CLOSE)
    assert f.mode_name == "following"
    f = rig.cycle(far=CLOSE)
    assert (f.mode_name, f.reason_name) == ("stopped", "a side sensor reads under 2 cm")


@pytest.mark.parametrize("side", SIDES)
def test_out_of_range_from_under_4_cm_is_too_close_not_a_lost_wall(side):
    # Inside 2 cm the module holds its echo for 38 ms: the driver reports OUT_OF_RANGE.
    rig = Rig(side)
    rig.cycle(near=390, far=390)
    f = rig.cycle(near=OOR, far=OOR)
    assert f.mode_name == "following" and f.fault_total == 2
    f = rig.cycle(near=OOR, far=OOR)
    assert (f.mode_name, f.reason_name) == ("stopped", "a side sensor reads under 2 cm")
    rig = Rig(side)
    rig.cycle(near=400, far=400)
    f = rig.cycle(near=OOR, far=OOR, n=3)
    assert (f.mode_name, f.fault_total) == ("lost", 0)


@pytest.mark.parametrize("side", SIDES)
def test_other_sensors_are_ignored(side):
    rig = Rig(side)
    other = Rig("right" if side == "left" else "left")
    f = rig.cycle(n=2)
    # The other side failing entirely changes nothing for this side.
    for k in (3, 4) if side == "left" else (1, 2):
        rig.status[k] = hcsr04.NO_ECHO
        f.update(rig.t, k, rig.dist, rig.status)
    assert f.fault_total == 0 and f.mode_name == "following"
    assert other.f.mode_name == "following"


def test_set_point_changes_on_the_fly_without_a_derivative_kick():
    rig = Rig()
    f = rig.cycle(near=800, far=800, n=3)
    assert f.follow("left", 1000, None, "yaw") == 0  # the rig's form (the follower's default is crab)
    f = rig.cycle(near=800, far=800)
    # e jumps to 200 (20 mm): P = 5000 -> clamped; the D term sees the still measurement: 0.
    assert (f.setpoint, f.error, f.pid.d, f.pid.p) == (1000, 200, 0, 5000) and f.output == follow.YAW_MAX
    assert f.updates == 4  # the same follow, not restarted


def test_sweeps_form_is_seed_000s_turn():
    rig = Rig(form="sweeps")
    full = [0, 0]
    sweep_command(rig.robot.walker, 4500, 1000, full)  # the paper's right turn
    f = rig.cycle(near=600, far=600)  # 2 cm close to the left wall: full output, turn right
    assert f.output == follow.YAW_MAX and (f.vx, f.yaw) == tuple(full)
    assert rig.robot.walker.req_vx == full[0] and rig.robot.walker.req_yaw == full[1]
    rig = Rig("right", form="sweeps")
    f = rig.cycle(near=600, far=600)  # mirrored: left turn, the same forward speed
    assert (f.vx, f.yaw) == (full[0], -full[1])
    rig = Rig(form="sweeps")
    f = rig.cycle(near=800, far=800, n=3)
    assert (f.output, f.vx, f.yaw) == (0, 800, 0)  # straight at the set speed


@pytest.mark.parametrize(
    "args, match",
    [
        (("up", 800), "side: 'up', allowed 'left' or 'right'"),
        ((None, 800), "side: None"),
        (("Left", 800), "side: 'Left'"),
        (("left", 399), r"setpoint: 399 is outside 400..5000 \(0.1 mm"),
        (("left", 5001), "setpoint: 5001"),
        (("left", 80.0), "setpoint: 80.0"),
        (("left", "800"), "setpoint: '800'"),
        (("left", True), "setpoint: True"),
        (("left", None), "setpoint: None"),
        (("left", 800, 0), r"speed: 0 is outside 100..3000 \(0.1 mm/s\)"),
        (("left", 800, -800), "speed: -800"),
        (("left", 800, 3001), "speed: 3001"),
        (("left", 800, 80.5), "speed: 80.5"),
        (("left", 800, False), "speed: False"),
        (("left", 800, None, "coxa"), "form: 'coxa', allowed 'yaw', 'sweeps' or 'crab'"),
    ],
)
def test_bad_follow_requests_are_refused_and_change_nothing(args, match):
    rig = Rig("right", 1200, 600)
    rig.cycle(near=1100, far=1150, n=2)
    f = rig.f
    before = (f.mode, f.side, f.setpoint, f.speed, f.form, f.updates, f.vx, f.yaw, rig.robot.walker.req_yaw)
    with pytest.raises(ValueError, match=match):
        f.follow(*args)
    assert (f.mode, f.side, f.setpoint, f.speed, f.form, f.updates, f.vx, f.yaw, rig.robot.walker.req_yaw) == before


@pytest.mark.parametrize("gains", [(-1, 500, 1000), (25000, 0.5, 1000), (25000, 500, 100001), ("25", 0, 0)])
def test_bad_gains_are_refused_and_change_nothing(gains):
    rig = Rig()
    rig.f.set_gains(30000, 0, 2000)
    with pytest.raises(ValueError, match="k[pid]: .* is outside 0..100000"):
        rig.f.set_gains(*gains)
    assert (rig.f.pid.kp, rig.f.pid.ki, rig.f.pid.kd) == (30000, 0, 2000)


def test_follow_refuses_a_robot_that_is_not_standing_and_changes_nothing():
    g = geometry.load(robots.default)
    robot = tick.Robot(g, tick.default_servos(g), tick.FrameBuffer())
    f = follow.Follower(robot)
    assert f.follow("left", 800) == tick.NOT_STANDING and f.mode_name == "off" and f.side is None
    robot.stand_up()
    robot.tick(0)
    assert f.follow("left", 800) == tick.BUSY and f.mode_name == "off" and robot.walker.req_vx == 0
    assert f.off() == 0 and f.mode_name == "off"


@pytest.mark.parametrize(
    "mounts, match",
    [
        (sensors.DEFAULT_MOUNTS[:4], "need 5"),
        (((1300, 0, 4500),) + sensors.DEFAULT_MOUNTS[1:], "front heading 4500"),
        (sensors.DEFAULT_MOUNTS[:1] + ((1000, -2100, 9000),) + sensors.DEFAULT_MOUNTS[2:], "left_front y -2100"),
        (sensors.DEFAULT_MOUNTS[:2] + ((1000, 2100, 9000),) + sensors.DEFAULT_MOUNTS[3:], "left_front x 1000 must be"),
        (sensors.DEFAULT_MOUNTS[:4] + ((0, 0, -9000),), "right_rear y 0"),
        (sensors.DEFAULT_MOUNTS[:4] + ((0, -2100, -9000.0),), "right_rear"),
    ],
)
def test_bad_mounts_are_refused(mounts, match):
    robot, _ = standing_robot()
    with pytest.raises(ValueError, match=match):
        follow.Follower(robot, mounts)


def test_decisions_are_bit_identical_on_both_runtimes(both_runtimes):
    cp, mp = both_runtimes.call("scenarios.follow:tour", 1500)
    assert cp == mp
    modes = {r[0] for r in cp}
    assert {follow.FOLLOWING, follow.CORNER} <= modes and len(cp) == 60


# --- issue 24: the rules a planted bug broke without a test failing --------------------------------


@pytest.mark.parametrize("side", SIDES)
def test_a_corner_that_never_clears_is_a_dead_end(side):
    # Something ahead inside the corner distance for ever: the robot arcs away; once its own
    # heading (the walker's psi, 0.0001 deg) has turned 270 deg (CORNER_TURN) without the corner
    # clearing, it stops, 'dead end', instead of circling for ever.
    rig = Rig(side)
    rig.cycle(n=2)
    psi = rig.robot.walker.psi
    turned = 0  # the walker's heading change, summed a cycle at a time (0.0001 deg)
    cycles = 0
    while cycles < 700:  # at the guard-capped ~6 deg/s, 270 deg is ~450 cycles (45 s)
        cycles += 1
        f = rig.cycle(front=CORNER_AT - 1)
        d = (rig.robot.walker.psi - psi + 1800000) % 3600000 - 1800000
        psi = rig.robot.walker.psi
        turned += d
        if f.mode_name != "corner":
            break
    assert (f.mode_name, f.reason_name) == ("stopped", "dead end"), (cycles, f.mode_name)
    # just past 270 deg (a cycle turns ~0.6 deg), away from the wall
    assert 2700000 <= rig.away(turned) <= 2700000 + 10000, turned
    assert 400 < cycles < 600, cycles


@pytest.mark.parametrize("side", SIDES)
def test_on_one_sonar_turning_away_opens_the_angle(side):
    # On the rear sonar alone the angle to the wall is the walker's own heading change since the
    # last pair (let fade 1/16 an update): turning away from the wall (the rear sonar 10 mm close)
    # must make the angle positive (nose away) and never larger than the turn itself.
    rig = Rig(side)
    rig.cycle(n=2)
    f = rig.cycle(near=NOECHO, n=3)
    assert f.distance_only and f.angle == 0
    psi0 = rig.robot.walker.psi
    f = rig.cycle(near=NOECHO, far=SP - 100, n=8)
    d = (rig.robot.walker.psi - psi0 + 1800000) % 3600000 - 1800000  # wrapped, 0.0001 deg
    turned_away = rig.away(d // 100)  # cdeg, away from the wall positive
    assert turned_away > 100, turned_away  # measured 321 cdeg (left)
    assert 0 < f.angle <= turned_away, (f.angle, turned_away)


@pytest.mark.parametrize("side", SIDES)
def test_a_sensor_change_keeps_the_integral_and_takes_no_derivative(side):
    # 4 mm close on the pair for 20 cycles: an integral builds (7 output units: the robot turns away and
    # the estimate sees the wall draw away, so the error shrinks). The front sonar
    # fails: another measurement, so the derivative starts afresh (the PID's sample count starts
    # again) but the integral is kept (the wall did not move).
    rig = Rig(side)
    f = rig.cycle(near=SP - 40, far=SP - 40, n=20)
    i_pair = f.pid.i
    assert i_pair > 3 and f.pid.samples >= 20
    f = rig.cycle(near=NOECHO, far=SP - 40, n=3)
    assert f.distance_only
    assert f.pid.samples <= 2, f.pid.samples  # reset at the change, then one update or two
    assert f.pid.i >= i_pair, (f.pid.i, i_pair)


# --- issue 22 point 5: form crab, sideways to the set point -------------------------------------------


def away_y(side, vy):
    """vy (0.1 mm/s, + to the robot's left) as 'walking away from the wall' (positive) for either side."""
    return -vy if side == "left" else vy


@pytest.mark.parametrize("side", SIDES)
def test_crab_walks_sideways_to_the_set_point_without_turning(side):
    # Parallel, 4 mm close: the PID holds the distance itself (no look-ahead), P only on the first
    # sample: u = 25 * 40 = 1000 cdeg/s, walked as a sideways speed of 800 * 1000 / CRAB_DIV (9000) =
    # 88 (0.1 mm/s) away from the wall; no turn.
    rig = Rig(side, form="crab")
    f = rig.cycle(near=760, far=760)
    assert (f.distance, f.angle, f.error, f.output, f.vx, f.yaw) == (760, 0, 40, 1000, 800, 0)
    assert follow.CRAB_DIV == 9000 and away_y(side, f.vy) == 88
    # The next sample: the walk's prediction has moved the wall by the sideways travel (0.4 mm):
    # less error, still away.
    f = rig.cycle(near=760, far=760)
    assert f.distance == 764 and 0 < f.error < 40 and 0 < away_y(side, f.vy) < 88 and f.yaw == 0
    rig = Rig(side, form="crab")
    f = rig.cycle(near=800, far=800)  # at the set point, parallel: straight on
    assert (f.error, f.output, f.vx, f.vy, f.yaw) == (0, 0, 800, 0, 0)


@pytest.mark.parametrize("side", SIDES)
def test_crab_cancels_the_headings_drift_and_turns_only_past_its_band(side):
    # Nose 1.15 deg toward the wall at the set point (78 and 82 mm): no error, no turn (inside
    # CRAB_BAND, 4 deg); the sideways speed cancels the heading's drift: 800 * sin(1.15 deg) = 16 away.
    rig = Rig(side, form="crab")
    f = rig.cycle(near=780, far=820)
    assert (f.distance, f.angle, f.error, f.output, f.yaw) == (800, -115, 0, 0, 0) and away_y(side, f.vy) == 16
    # 5.71 deg toward (70 and 90 mm): 800 * sin(5.71 deg) = 80 away, and a turn away of the excess
    # over the band per second: 571 - 400 = 171 cdeg/s.
    rig = Rig(side, form="crab")
    f = rig.cycle(near=700, far=900)
    assert (f.distance, f.angle, f.error) == (800, -571, 0)
    assert away_y(side, f.vy) == 80 and rig.away(f.yaw) == 171


@pytest.mark.parametrize("side", SIDES)
def test_crab_turns_as_form_yaw_past_10_degrees_and_on_one_sonar(side):
    # 11.3 deg toward (60 and 100 mm, after a corner, say): the yaw form's law, look-ahead and all:
    # e = 0 + 100 mm * sin(11.31 deg) = 19.6 mm -> 25 * 196 = 4900, clamped at YAW_MAX; no sideways step.
    rig = Rig(side, form="crab")
    f = rig.cycle(near=600, far=1000)
    assert (f.angle, f.error, f.output, f.vy) == (-1131, 196, follow.YAW_MAX, 0)
    assert rig.away(f.yaw) == follow.YAW_MAX
    # On the rear sonar alone (an outside corner, a gap): the same as form yaw, a turn.
    for form in ("yaw", "crab"):
        rig = Rig(side, form=form)
        f = rig.cycle(near=800, far=800, n=2)
        f = rig.cycle(near=OOR, far=900, n=3)
        assert f.distance_only and f.vy == 0
        if form == "yaw":
            want = (f.distance, f.error, f.output, f.yaw)
        else:
            assert (f.distance, f.error, f.output, f.yaw) == want


@pytest.mark.parametrize("side", SIDES)
def test_crab_turns_at_the_walls_end_and_until_back_near_the_set_point(side):
    # The wall 20 mm beyond the 8 cm set point, parallel: crab (sideways toward it, no turn). Then the
    # front sonar reads 23 mm farther than the rear (the wall's end leaving its beam: 6.56 deg nose
    # away in this one sample, 0.82 deg in the estimate): form yaw's turn toward the wall, no sideways
    # step, and form yaw it stays while the estimate reads the wall over set point + 10 mm (an outside
    # corner reads far until the robot is round it), even with the pair parallel again.
    rig = Rig(side, form="crab")
    f = rig.cycle(near=1000, far=1000, n=12)
    assert f.distance == 930 and f.yaw == 0 and away_y(side, f.vy) < 0
    f = rig.cycle(near=1230, far=1000)
    assert (f.distance, f.angle, f.vy) == (941, 82, 0) and rig.away(f.yaw) == -follow.YAW_MAX
    for _ in range(8):
        f = rig.cycle(near=1000, far=1000)
        assert f.vy == 0 and rig.away(f.yaw) == -follow.YAW_MAX and f.distance > SP + 100
    seen = []
    for _ in range(5):
        f = rig.cycle(near=SP, far=SP)
        seen.append((f.distance, f.vy == 0))
    # Turning while the estimate is over 90 mm (95.2, 93.2, 91.4 mm), sideways again once within it.
    assert [turning for _, turning in seen] == [True, True, True, False, False]
    assert seen[2][0] > SP + 100 >= seen[3][0]
    assert rig.away(f.yaw) == 0 and away_y(side, f.vy) < 0


@pytest.mark.parametrize("side", SIDES)
def test_crab_after_one_sonar_crabs_at_once_on_the_pair(side):
    # A turn on one sonar (a gap's edge) is not held: back on the pair 15 mm far, it crabs again.
    rig = Rig(side, form="crab")
    f = rig.cycle(near=SP, far=SP, n=2)
    f = rig.cycle(near=OOR, far=950, n=3)
    assert f.distance_only and f.vy == 0
    f = rig.cycle(near=950, far=950, n=2)
    assert not f.distance_only and f.distance > SP + 100 and away_y(side, f.vy) < 0


def test_crab_decisions_are_bit_identical_on_both_runtimes(both_runtimes):
    cp, mp = both_runtimes.call("scenarios.follow:tour", 1500, "crab")
    assert cp == mp
    assert {r[0] for r in cp} >= {follow.FOLLOWING, follow.CORNER} and len(cp) == 60
    assert any(r[6] for r in cp)  # it did walk sideways
