"""The simulated room's physics, in floats on the host: sonar beams, the body moved by its stance
feet, contact with the walls. Units: mm and radians; world frame x, y (cm in the JSON, converted
by hexapod_host.wall.world); body frame x forward, y left (docs/wall.md, host half).

- Sonar (`beam_distance`): the nearest wall point inside a sensor's beam, a cone of BEAM_HALF
  either side of its heading. Exact: the distance to a straight wall is convex along it, so its
  minimum over the part inside the cone is the perpendicular foot when that lies inside, else
  where the cone's two edge rays cut the wall or a wall end inside the cone. The first echo
  (nearest wall) wins; the HC-SR04 hears nothing under 2 cm or beyond 4 m.
- Body (`Body.move`): each frame the servo pulses the core sent are turned back into joint
  angles (the board's servo maps) and feet (float FK, hexapod_host.testing.reference); the feet on the
  ground in both frames stay put in the world, so the body's motion is the least-squares rigid
  2-D motion that carries them from this frame's body coordinates to the last's (2-D Kabsch).
- Contact (`Body.touches`): the body outline, the sonar brackets, and every leg's coxa, femur
  and tibia links (coxa axis -> femur joint -> knee -> foot, FK of the angles sent) against
  the walls, with CONTACT_MM of clearance for the links' thickness.
"""

import math

import robots.default
from hexapod import board as boards
from hexapod import geometry, robotcal
from hexapod_host.testing.reference import fk

BEAM_HALF = math.radians(15)  # HC-SR04: about 15 degrees either side of its axis
MIN_MM = 20.0  # nothing closer is heard (the module holds its echo for 38 ms)
MAX_MM = 4000.0
GROUND_MM = 0.3  # a foot this close to the lowest one is on the ground (pulses are 0.1 degree: z within 0.2 mm)
CONTACT_MM = 5.0  # half a link's thickness: closer than this to a wall is a touch
BODY_HALF = (87.5, 77.5)  # robots/default.py: a 175 x 155 mm body, mounts at its corners


def _cross(ax, ay, bx, by):
    return ax * by - ay * bx


def beam_distance(walls, sx, sy, heading, half=BEAM_HALF):
    """Distance (mm) from a sensor at (sx, sy) facing `heading` (rad) to the nearest wall point
    inside its beam, or None. walls: (x1, y1, x2, y2) in mm."""
    ux, uy = math.cos(heading), math.sin(heading)
    ch = math.cos(half)
    edges = ((math.cos(heading - half), math.sin(heading - half)), (math.cos(heading + half), math.sin(heading + half)))
    best = None
    for x1, y1, x2, y2 in walls:
        ax, ay, dx, dy = x1 - sx, y1 - sy, x2 - x1, y2 - y1
        cands = []
        for px, py in ((ax, ay), (ax + dx, ay + dy)):  # the wall's ends
            r = math.hypot(px, py)
            if r > 0 and px * ux + py * uy >= ch * r:
                cands.append(r)
        ll = dx * dx + dy * dy
        t = -(ax * dx + ay * dy) / ll  # the perpendicular foot
        if 0.0 < t < 1.0:
            px, py = ax + t * dx, ay + t * dy
            r = math.hypot(px, py)
            if r > 0 and px * ux + py * uy >= ch * r:
                cands.append(r)
        for ex, ey in edges:  # the beam's edge rays
            den = _cross(ex, ey, dx, dy)
            if den == 0.0:
                continue
            s = _cross(ax, ay, dx, dy) / den  # along the ray
            w = _cross(ax, ay, ex, ey) / den  # along the wall
            if s > 0.0 and 0.0 <= w <= 1.0:
                cands.append(s)
        for r in cands:
            if best is None or r < best:
                best = r
    return best


def point_segment(px, py, x1, y1, x2, y2):
    """Distance (mm) from a point to a segment."""
    dx, dy = x2 - x1, y2 - y1
    ll = dx * dx + dy * dy
    t = 0.0 if ll == 0 else max(0.0, min(1.0, ((px - x1) * dx + (py - y1) * dy) / ll))
    return math.hypot(px - x1 - t * dx, py - y1 - t * dy)


def segments_cross(a, b):
    """True when segments a and b ((x1, y1, x2, y2)) meet, ends included."""
    ax, ay, bx, by = a
    cx, cy, dx, dy = b
    d1 = _cross(bx - ax, by - ay, cx - ax, cy - ay)
    d2 = _cross(bx - ax, by - ay, dx - ax, dy - ay)
    d3 = _cross(dx - cx, dy - cy, ax - cx, ay - cy)
    d4 = _cross(dx - cx, dy - cy, bx - cx, by - cy)
    if ((d1 > 0 > d2) or (d1 < 0 < d2)) and ((d3 > 0 > d4) or (d3 < 0 < d4)):
        return True
    return (
        min(
            point_segment(cx, cy, ax, ay, bx, by),
            point_segment(dx, dy, ax, ay, bx, by),
            point_segment(ax, ay, cx, cy, dx, dy),
            point_segment(bx, by, cx, cy, dx, dy),
        )
        == 0.0
    )


def segment_distance(a, b):
    """Shortest distance (mm) between two segments."""
    if segments_cross(a, b):
        return 0.0
    return min(
        point_segment(b[0], b[1], *a),
        point_segment(b[2], b[3], *a),
        point_segment(a[0], a[1], *b),
        point_segment(a[2], a[3], *b),
    )


def grounded(feet):
    """Which feet (x, y, z mm) are on the ground: within GROUND_MM of the lowest one."""
    z0 = min(f[2] for f in feet)
    return [f[2] <= z0 + GROUND_MM for f in feet]


def rigid_2d(q, p):
    """Least-squares rigid motion (phi rad, tx, ty mm) carrying points q onto p (2-D Kabsch)."""
    n = len(q)
    qx = sum(v[0] for v in q) / n
    qy = sum(v[1] for v in q) / n
    px = sum(v[0] for v in p) / n
    py = sum(v[1] for v in p) / n
    s = c = 0.0
    for (ax, ay), (bx, by) in zip(q, p, strict=True):
        ax, ay, bx, by = ax - qx, ay - qy, bx - px, by - py
        c += ax * bx + ay * by
        s += ax * by - ay * bx
    phi = math.atan2(s, c)
    co, si = math.cos(phi), math.sin(phi)
    return phi, px - (co * qx - si * qy), py - (si * qx + co * qy)


class Body:
    """The robot in the room: pose, legs from pulses, sensors, outline."""

    def __init__(self, board_name="pico", robot=robots.default):
        self.g = geometry.load(robot)
        g = self.g
        cal = robotcal.load(robot.__name__.rsplit(".", 1)[-1], g.limits)
        self.maps = [row[2] for row in boards.servo_table(boards.load(board_name), robotcal.servo_maps(cal))]
        self.lengths = [(lg.coxa / 10, lg.femur / 10, lg.tibia / 10, lg.femur_offset / 10) for lg in g.legs]
        self.mounts = [(g.mount_x[i] / 10, g.mount_y[i] / 10, math.radians(g.mount_angle[i] / 100)) for i in range(6)]
        self.sensors = [(x / 10, y / 10, math.radians(h / 100)) for x, y, h in robotcal.sensor_mounts(cal)]
        bx, by = BODY_HALF
        corners = ((bx, by), (-bx, by), (-bx, -by), (bx, -by))
        self.outline = [corners[k] + corners[(k + 1) % 4] for k in range(4)]
        for x, y, _ in self.sensors:  # brackets from the body's edge out to each sonar
            ex = max(-bx, min(bx, x))
            ey = max(-by, min(by, y))
            if (ex, ey) != (x, y):
                self.outline.append((ex, ey, x, y))
        self.x = self.y = self.theta = 0.0
        self.links = []  # body-frame (x1, y1, x2, y2) of every leg link, mm
        self.feet = []  # body-frame (x, y, z) of every foot, mm
        self.stance = []

    def place(self, x, y, theta):
        self.x, self.y, self.theta = x, y, theta

    def to_world(self, bx, by):
        c, s = math.cos(self.theta), math.sin(self.theta)
        return self.x + c * bx - s * by, self.y + s * bx + c * by

    def joint_angles(self, pulses):
        """The 18 joint angles (cdeg) that 18 pulses (us) stand for, through the board's servo maps."""
        return [self.maps[k].angle(pulses[k]) for k in range(18)]

    def leg_points(self, angles):
        """Each leg's coxa axis, femur joint, knee and foot (x, y, z mm, body frame) for 18 joint
        angles (cdeg): float FK of the robot file's legs."""
        legs = []
        for i in range(6):
            t1, t2, t3 = (angles[3 * i + k] / 100 for k in range(3))
            coxa, femur, tibia, off = self.lengths[i]
            fx, fy, fz = fk(t1, t2, t3, coxa, femur, tibia, off)
            a2 = math.radians(t2)
            mx, my, m = self.mounts[i]
            a = m + math.radians(t1)
            ca, sa = math.cos(a), math.sin(a)
            reach = (0.0, coxa, coxa + femur * math.cos(a2), math.hypot(fx, fy))
            height = (0.0, off, off + femur * math.sin(a2), fz)
            legs.append([(mx + r * ca, my + r * sa, z) for r, z in zip(reach, height, strict=True)])
        return legs

    def legs_from_pulses(self, pulses):
        """Feet and links (body frame, mm) from the 18 pulses sent (us); False (legs kept) while a leg has no pulse."""
        for i in range(6):
            if not pulses[3 * i]:
                return False
        self.set_legs(self.leg_points(self.joint_angles(pulses)))
        return True

    def set_legs(self, legs):
        """Links and feet (body frame, mm) from each leg's coxa axis, femur joint, knee and foot
        (x, y, z): the links are their plan view, the feet keep z."""
        links = []
        for pts in legs:
            links += [pts[k][:2] + pts[k + 1][:2] for k in range(3)]
        self.feet, self.links = [tuple(pts[3]) for pts in legs], links

    def neutral_legs(self, height_mm=None):
        """Links and feet of the neutral stance (for the start check before any frame); returns its 18 pulses (us)."""
        g = self.g
        h = g.body_height if height_mm is None else height_mm * 10
        out = [0, 0, 0]
        pulses = [0] * 18
        for i in range(6):
            g.legs[i].ik(g.neutral_reach, 0, -h, out)
            for k in range(3):
                self.maps[3 * i + k].pulse(out[k], pulses, 3 * i + k)
        self.legs_from_pulses(pulses)
        return pulses

    def move(self, old_feet, speed=1.0, slip=0.0):
        """Integrate the body's motion since old_feet (this frame's feet on the ground in both
        frames stay put), translation scaled by `speed`, heading plus `slip` (rad). Returns the
        distance moved (mm)."""
        if not old_feet:
            return 0.0
        q, p = [], []
        for a, b, on_a, on_b in zip(self.feet, old_feet, grounded(self.feet), grounded(old_feet), strict=True):
            if on_a and on_b:
                q.append((a[0], a[1]))
                p.append((b[0], b[1]))
        self.stance = q
        if len(q) < 2:
            return 0.0
        return self.advance(*rigid_2d(q, p), speed, slip)

    def advance(self, phi, tx, ty, speed=1.0, slip=0.0):
        """Move by one frame's step: the new body pose in the old body frame (phi rad, tx, ty mm),
        translation scaled by `speed`, heading plus `slip` (rad) while it moves. Returns the
        distance moved (mm)."""
        tx *= speed
        ty *= speed
        c, s = math.cos(self.theta), math.sin(self.theta)
        self.x += c * tx - s * ty
        self.y += s * tx + c * ty
        moved = math.hypot(tx, ty)
        self.theta += phi + (slip if moved > 0.01 or abs(phi) > 1e-5 else 0.0)
        return moved

    def sensor_pose(self, k):
        """World (x, y, heading) of sensor k (drivers.hcsr04 order)."""
        x, y, h = self.sensors[k]
        wx, wy = self.to_world(x, y)
        return wx, wy, self.theta + h

    def world_segments(self):
        """Every outline, bracket and leg link in the world frame."""
        out = []
        for x1, y1, x2, y2 in self.outline + self.links:
            out.append(self.to_world(x1, y1) + self.to_world(x2, y2))
        return out

    def touches(self, walls, margin=CONTACT_MM):
        """Index of the first wall closer than `margin` to any part of the robot, or -1."""
        segs = self.world_segments()
        radius = max(math.hypot(s[0] - self.x, s[1] - self.y) for s in segs)
        radius = max(radius, max(math.hypot(s[2] - self.x, s[3] - self.y) for s in segs)) + margin
        for k, w in enumerate(walls):
            if point_segment(self.x, self.y, *w) > radius:
                continue
            for s in segs:
                if segment_distance(s, w) < margin:
                    return k
        return -1
