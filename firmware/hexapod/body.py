"""Body pose and the body-frame -> leg-frame transform, in integers.

Feet are planned in the body frame (x forward, y left, z up, origin at the body centre at
coxa height) in FINE units: 0.1 mm << FINE_SHIFT, so slow motions accumulate without
rounding away. The pose moves the body over feet that stay put on the ground: translation
(x, y, z, 0.1 mm) and roll, pitch, yaw (cdeg, right-hand rule about x, y, z: positive roll
lowers the right side, positive pitch lowers the nose, positive yaw turns left) about an
adjustable centre of rotation (0.1 mm, body frame). A foot F then sits at
R^T (F - c - t) + c in the moved body, R = Rz(yaw) Ry(pitch) Rx(roll).

set_pose only records a target; slew() walks the pose there by at most POSE_STEP (0.1 mm)
and ANGLE_STEP (cdeg) per tick, so no servo jumps.
"""

from array import array

from micropython import const

from hexapod.fixmath import ONE, cos, mul_q15, sin

FINE_SHIFT = const(4)
FINE = const(16)  # fine units per 0.1 mm
_HALF = const(8)

POSE_SHIFT_MAX = const(400)  # largest |x|, |y|, |z| body translation, 0.1 mm
POSE_ANGLE_MAX = const(1500)  # largest |roll|, |pitch|, |yaw|, cdeg
CENTRE_MAX = const(2000)  # largest |x|, |y|, |z| of the centre of rotation, 0.1 mm
POSE_STEP = const(20)  # most a translation or centre coordinate changes per tick, 0.1 mm
ANGLE_STEP = const(50)  # most an angle changes per tick, cdeg

POSE_NAMES = ("x", "y", "z", "roll", "pitch", "yaw", "centre x", "centre y", "centre z")


class Body:
    """Pose state and the per-leg transform of a Geometry's six mounts."""

    def __init__(self, geometry):
        self.geometry = geometry
        # array("i") here and below: _body_viper.py and _tick_viper.py read them as machine words (ptr32).
        self.mx = array("i", [v << FINE_SHIFT for v in geometry.mount_x])
        self.my = array("i", [v << FINE_SHIFT for v in geometry.mount_y])
        self.mc = array("i", geometry.mount_cos)
        self.ms = array("i", geometry.mount_sin)
        self.pose = array("i", [0] * 9)  # x, y, z, roll, pitch, yaw, centre x, y, z (0.1 mm, cdeg)
        self.target = array("i", [0] * 9)
        self.trig = array("i", [ONE, 0, ONE, 0, ONE, 0])  # cos, sin of roll, pitch, yaw (Q15)
        self.level = True  # no pose at all: the transform skips the pose maths

    def check_pose(self, pose):
        """ValueError naming the first pose value out of its range (9 values, as in `pose`)."""
        if len(pose) != 9:
            raise ValueError("pose: need 9 values (x, y, z, roll, pitch, yaw, centre x, y, z), got %d" % len(pose))
        for k in range(9):
            v = pose[k]
            lim = POSE_SHIFT_MAX if k < 3 else (POSE_ANGLE_MAX if k < 6 else CENTRE_MAX)
            unit = "cdeg" if 3 <= k < 6 else "0.1 mm"
            if not isinstance(v, int) or isinstance(v, bool):
                raise ValueError("pose %s: need a whole number (%s), got %r" % (POSE_NAMES[k], unit, v))
            if v < -lim or v > lim:
                raise ValueError("pose %s: %d %s is outside -%d..%d" % (POSE_NAMES[k], v, unit, lim, lim))

    def set_target(self, pose):
        """Aim the pose at 9 values (checked); slew() gets there gradually."""
        self.check_pose(pose)
        for k in range(9):
            self.target[k] = pose[k]

    def settled(self):
        """True when the pose has reached its target."""
        p = self.pose
        t = self.target
        for k in range(9):  # noqa: SIM110 (a generator would allocate in the tick)
            if p[k] != t[k]:
                return False
        return True

    def slew(self):
        """One tick of pose motion toward the target; True while still moving."""
        p = self.pose
        t = self.target
        moved = False
        turned = False
        for k in range(9):
            d = t[k] - p[k]
            if d:
                step = ANGLE_STEP if 3 <= k < 6 else POSE_STEP
                if d > step:
                    d = step
                elif d < -step:
                    d = -step
                p[k] += d
                moved = True
                if 3 <= k < 6:
                    turned = True
        if turned:
            self._trig()
        if moved:
            self.level = not (p[0] or p[1] or p[2] or p[3] or p[4] or p[5])
        return moved

    def jump(self):
        """Take the target pose at once (only when no servo is driven, e.g. before the first frame)."""
        for k in range(9):
            self.pose[k] = self.target[k]
        self._trig()
        p = self.pose
        self.level = not (p[0] or p[1] or p[2] or p[3] or p[4] or p[5])

    def _trig(self):
        tr = self.trig
        for k in range(3):
            a = self.pose[3 + k]
            tr[2 * k] = cos(a)
            tr[2 * k + 1] = sin(a)

    def to_leg(self, i, x, y, z, out, j):
        """Leg i's frame (0.1 mm, rounded) of a body-frame foot in fine units, into out[j:j+3]."""
        if not self.level:
            p = self.pose
            tr = self.trig
            cx = p[6] << FINE_SHIFT
            cy = p[7] << FINE_SHIFT
            cz = p[8] << FINE_SHIFT
            x -= cx + (p[0] << FINE_SHIFT)
            y -= cy + (p[1] << FINE_SHIFT)
            z -= cz + (p[2] << FINE_SHIFT)
            c = tr[4]
            s = tr[5]
            a = mul_q15(x, c) + mul_q15(y, s)  # undo the yaw
            y = mul_q15(y, c) - mul_q15(x, s)
            x = a
            c = tr[2]
            s = tr[3]
            a = mul_q15(x, c) - mul_q15(z, s)  # undo the pitch
            z = mul_q15(x, s) + mul_q15(z, c)
            x = a
            c = tr[0]
            s = tr[1]
            a = mul_q15(y, c) + mul_q15(z, s)  # undo the roll
            z = mul_q15(z, c) - mul_q15(y, s)
            y = a
            x += cx
            y += cy
            z += cz
        dx = x - self.mx[i]
        dy = y - self.my[i]
        c = self.mc[i]
        s = self.ms[i]
        out[j] = (mul_q15(dx, c) + mul_q15(dy, s) + _HALF) >> FINE_SHIFT
        out[j + 1] = (mul_q15(dy, c) - mul_q15(dx, s) + _HALF) >> FINE_SHIFT
        out[j + 2] = (z + _HALF) >> FINE_SHIFT
        return out
