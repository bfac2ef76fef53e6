"""The side sonars sit where an 8 cm reading keeps every foot and link clear of the wall.

The robot walks as the follower drives it (straight at its speed, turning at its largest yaw
rate either way, and its corner arc); every tick, seed 004's FK in floats (the host oracle) of
the 18 joint angles actually sent gives each leg's coxa, femur and knee joints and foot in the
body frame. The wall is where the nearer side sonar reads the smallest set point (8 cm), at any
angle within the follower's guard: its normal n = (sin a, cos a), the sonars reading their
perpendicular distance, so the wall sits at n.p = 80 mm + max(n.s) over the two sonars."""

import math

import pytest
from scenarios.rig import stand

import robots.default
from hexapod import follow, geometry, sensors, tick
from hexapod_host.testing.reference import fk

G = geometry.load(robots.default)
SETPOINT_MM = 80.0  # the paper's smallest set point, 8 cm


def joints_mm(robot, i):
    """Body-frame (x, y) in mm of leg i's coxa joint, femur joint, knee and foot (float FK)."""
    t1, t2, t3 = (a / 100 for a in robot.angles[3 * i : 3 * i + 3])
    coxa, femur, tibia, off = (v / 10 for v in (G.legs[i].coxa, G.legs[i].femur, G.legs[i].tibia, 0))
    foot = fk(t1, t2, t3, coxa, femur, tibia, off)
    a1, a2 = math.radians(t1), math.radians(t2)
    reach = (0.0, coxa, coxa + femur * math.cos(a2), math.hypot(foot[0], foot[1]))
    m = math.radians(G.mount_angle[i] / 100)
    mx, my = G.mount_x[i] / 10, G.mount_y[i] / 10
    return [(mx + r * math.cos(m + a1), my + r * math.sin(m + a1)) for r in reach]


def envelope(commands, ticks=150):
    """Every leg point (mm, body frame) over `ticks` of walking each command from a stand."""
    points = []
    for vx, yaw in commands:
        robot = tick.Robot(G, tick.default_servos(G), tick.FrameBuffer())
        t = stand(robot)
        assert robot.walk(vx, 0, yaw) == 0
        for _ in range(ticks):
            assert robot.tick(t) == 0
            t += 20
            for i in range(6):
                points += joints_mm(robot, i)
    return points


def clearance(points, side, angle_deg, mounts=sensors.DEFAULT_MOUNTS):
    """Smallest distance (mm) from the wall to any point, with the side's nearer sonar at 8 cm."""
    sign = 1 if side == "left" else -1
    a = math.radians(angle_deg)
    n = (math.sin(a), sign * math.cos(a))  # angle > 0: nose toward the wall
    f, r = (1, 2) if side == "left" else (3, 4)
    sonars = [(mounts[k][0] / 10, mounts[k][1] / 10) for k in (f, r)]
    wall = SETPOINT_MM + max(n[0] * x + n[1] * y for x, y in sonars)
    body = [(sx * 87.5, sy * 77.5) for sx in (-1, 1) for sy in (-1, 1)]
    return wall - max(n[0] * x + n[1] * y for x, y in points + body)


@pytest.fixture(scope="module")
def walks():
    speed, yaw = follow.SPEED, follow.YAW_MAX
    straight = envelope([(speed, 0)])
    turning = envelope([(speed, yaw), (speed, -yaw), (speed, follow.yaw_for_radius(speed, follow.CORNER_RADIUS))])
    return straight, turning


@pytest.mark.parametrize("side", ["left", "right"])
def test_an_8_cm_reading_keeps_every_foot_and_link_clear(walks, side):
    straight, turning = walks
    # Hand-worked: the middle foot at neutral is 77.5 + 130 = 207.5 mm out and walks straight
    # back and forth; the side sonars are 210 mm out: at 80 mm the wall is 290 mm out.
    assert clearance(straight, side, 0) == pytest.approx(290 - 207.5, abs=0.2)
    parallel = clearance(turning, side, 0)
    assert 290 - 207.5 - 1 < parallel <= 290 - 207.5 + 0.2  # turning swings no foot farther out
    guard = follow.ANGLE_GUARD // 100
    worst = min(clearance(straight + turning, side, a) for a in range(-guard, guard + 1))
    print("clearance at an 8 cm reading: %.1f mm parallel, %.1f mm within +-%d deg" % (parallel, worst, guard))
    assert worst > 80


def test_the_old_mounts_would_put_the_wall_inside_the_feet(walks):
    """The check has teeth: side sonars 65 mm out (the first board files) fail it."""
    straight, _ = walks
    old = ((1300, 0, 0), (700, 650, 9000), (-700, 650, 9000)) + sensors.DEFAULT_MOUNTS[3:]
    assert clearance(straight, "left", 0, old) == pytest.approx(65 + 80 - 207.5, abs=0.2)
