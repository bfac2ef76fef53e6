"""MJCF (MuJoCo's model format) of a robot file: body box, three links a leg, servos, a floor.

Units convert here and nowhere else: the robot file's 0.1 mm, cdeg, g, mN m become MuJoCo's
m, rad, kg, N m. The model follows the core's conventions (design.md, physics notes): body
frame x forward, y left, z up, origin at the body centre at coxa height; each leg's coxa
joint turns about +z at its mount, femur and tibia about -y (positive = up), joint angle 0
with the leg stretched out level along its mount direction, so qpos (rad) = cdeg * pi / 18000
with no offsets. A foot is a small sphere whose centre is the IK foot point (site footN).

The servos are position actuators: torque = kp (target - angle), clamped to the stall
torque, plus a joint damping kv = stall / no-load speed, so a servo at full effort runs at
its no-load speed and no faster (a DC motor's torque-speed line); the gears' reflected
motor inertia is the joint armature. Only the feet and the body box touch the floor.
"""

import math
import os

from hexapod.robotfile import LEG_NAMES, check_table

PHYSICS_FIELDS = (
    ("body_g", 10, 100000, "g"),
    ("coxa_g", 0, 10000, "g"),
    ("femur_g", 0, 10000, "g"),
    ("tibia_g", 0, 10000, "g"),
    ("body_thickness", 50, 2000, "0.1 mm"),
    ("foot_friction_permille", 50, 3000, "per mille"),
    ("foot_radius", 10, 300, "0.1 mm"),
)
TIMESTEP_S = 0.002
JOINTS = ("coxa", "femur", "tibia")
# The directional light's shadow box, half-width as a share of the extent (0.6 x 714 mm: the
# default robot's 357 mm reach fits inside, and no far floor does).
SHADOW_CLIP = 0.6
JOINT_AXES = ("0 0 1", "0 -1 0", "0 -1 0")


def import_mujoco():
    """The mujoco module, with offscreen rendering (MUJOCO_GL=egl) chosen before its first import."""
    os.environ.setdefault("MUJOCO_GL", "egl")
    import mujoco

    return mujoco


def check_physics(name, physics):
    """ValueError naming the robot and the field unless physics holds every PHYSICS_FIELDS key in range."""
    check_table("robot %r: " % (name,), "PHYSICS", physics, PHYSICS_FIELDS)
    return physics


def servo_model(servo):
    """The MuJoCo numbers of a checked SERVO dict: stall (N m), kp (N m/rad), kv (N m s/rad), armature (kg m^2)."""
    stall = servo["stall_torque_mnm"] / 1000.0
    speed = (math.pi / 3) / (servo["speed_ms_per_60deg"] / 1000.0)  # rad/s, no load
    return {
        "stall": stall,
        "kp": servo["kp_mnm_per_rad"] / 1000.0,
        "kv": stall / speed,
        "armature": servo["armature_g_cm2"] * 1e-7,
        "speed": speed,
        "mass": servo["mass_g"] / 1000.0,
    }


def _f(v):
    return "%.6g" % v


def _xyz(*v):
    return " ".join(_f(x) for x in v)


def build(geometry, servo, physics, *, flip=None):
    """MJCF text of a checked Geometry with a SERVO and a PHYSICS dict.

    flip=(leg, joint) (1-based leg, joint 0..2) turns that one joint's axis around: a
    deliberately wrong model, for showing the checks catch a convention error.
    """
    sm = servo_model(servo)
    leg = geometry.legs[0]
    m = 1e-4  # 0.1 mm -> m
    coxa, femur, tibia, d1 = leg.coxa * m, leg.femur * m, leg.tibia * m, leg.femur_offset * m
    lim = [v * math.pi / 18000 for v in geometry.limits]
    xs, ys = geometry.mount_x, geometry.mount_y
    half_x = (max(xs) - min(xs)) * m / 2
    half_y = (max(ys) - min(ys)) * m / 2
    half_z = physics["body_thickness"] * m / 2
    foot_r = physics["foot_radius"] * m
    mu = physics["foot_friction_permille"] / 1000.0
    servo_box = _xyz(0.020, 0.010, 0.020)
    # Coxa servos sit in the body; femur servos ride the coxa link, tibia servos the femur.
    body_mass = physics["body_g"] / 1000.0 + 6 * sm["mass"]
    z0 = geometry.body_height * m + foot_r
    # The robot's span with its legs stretched out level: what the render's scale should fit.
    extent = 2 * (max(math.hypot(x, y) for x, y in zip(xs, ys, strict=True)) * m + coxa + femur + tibia)
    out = [
        '<mujoco model="hexapod-%s">' % geometry.name,
        '  <compiler angle="radian" autolimits="true"/>',
        '  <option timestep="%s" integrator="implicitfast"/>' % _f(TIMESTEP_S),
        # Render settings only (the solver never reads them). MuJoCo scales its clip planes and
        # the directional light's shadow box by stat.extent, which the 20 m floor alone set to
        # 4 m: the floor then shadowed itself in black shards on the far floor inside that 8 m
        # box. The robot's size as the extent and a box ~0.9 m across that follows the robot
        # (trackcom) keep every floor pixel that box covers near the camera; docs/physics.md.
        '  <visual><global offwidth="640" offheight="480"/><map shadowclip="%s"/></visual>' % _f(SHADOW_CLIP),
        '  <statistic extent="%s"/>' % _f(extent),
        "  <asset>",
        '    <texture type="skybox" builtin="gradient" rgb1=".95 .96 .98" rgb2=".75 .8 .88" width="32" height="32"/>',
        '    <texture name="grid" type="2d" builtin="checker" rgb1=".82 .84 .86" rgb2=".70 .72 .75" '
        'width="256" height="256"/>',
        '    <material name="grid" texture="grid" texrepeat="8 8" texuniform="true"/>',
        "  </asset>",
        "  <default>",
        '    <joint damping="%s" armature="%s"/>' % (_f(sm["kv"]), _f(sm["armature"])),
        '    <position kp="%s" forcerange="%s %s"/>' % (_f(sm["kp"]), _f(-sm["stall"]), _f(sm["stall"])),
        '    <geom contype="0" conaffinity="0" rgba=".25 .45 .75 1"/>',
        "  </default>",
        "  <worldbody>",
        '    <light pos="0 0 3" dir="0 0 -1" directional="true" mode="trackcom"/>',
        '    <geom name="floor" type="plane" size="20 20 0.1" material="grid" rgba="1 1 1 1" '
        'contype="1" conaffinity="1" friction="%s 0.005 0.0001"/>' % _f(mu),
        '    <body name="body" pos="0 0 %s">' % _f(z0),
        "      <freejoint/>",
        '      <geom name="body" type="box" size="%s" mass="%s" contype="1" rgba=".3 .3 .35 1"/>'
        % (_xyz(half_x, half_y, half_z), _f(body_mass)),
        '      <site name="imu" pos="0 0 0"/>',
    ]
    for i in range(6):
        n = i + 1
        a = geometry.mount_angle[i] * math.pi / 18000
        axes = list(JOINT_AXES)
        if flip is not None and flip[0] == n:
            axes[flip[1]] = " ".join(_f(-float(c)) for c in axes[flip[1]].split())
        r = _f(0.006)
        out += [
            '      <body name="coxa%d" pos="%s" euler="0 0 %s">' % (n, _xyz(xs[i] * m, ys[i] * m, 0), _f(a)),
            '        <joint name="coxa%d" axis="%s" range="%s %s"/>' % (n, axes[0], _f(lim[0]), _f(lim[1])),
            '        <geom type="capsule" fromto="%s" size="%s" mass="%s"/>'
            % (_xyz(0, 0, 0, coxa, 0, d1), r, _f(physics["coxa_g"] / 1000.0)),
            '        <geom type="box" pos="%s" size="%s" mass="%s" rgba=".15 .15 .15 1"/>'
            % (_xyz(coxa, 0, d1), servo_box, _f(sm["mass"])),
            '        <body name="femur%d" pos="%s">' % (n, _xyz(coxa, 0, d1)),
            '          <joint name="femur%d" axis="%s" range="%s %s"/>' % (n, axes[1], _f(lim[2]), _f(lim[3])),
            '          <geom type="capsule" fromto="%s" size="%s" mass="%s"/>'
            % (_xyz(0, 0, 0, femur, 0, 0), r, _f(physics["femur_g"] / 1000.0)),
            '          <geom type="box" pos="%s" size="%s" mass="%s" rgba=".15 .15 .15 1"/>'
            % (_xyz(femur, 0, 0), servo_box, _f(sm["mass"])),
            '          <body name="tibia%d" pos="%s">' % (n, _xyz(femur, 0, 0)),
            '            <joint name="tibia%d" axis="%s" range="%s %s"/>' % (n, axes[2], _f(lim[4]), _f(lim[5])),
            '            <geom type="capsule" fromto="%s" size="%s" mass="%s"/>'
            % (_xyz(0, 0, 0, tibia - foot_r, 0, 0), _f(0.005), _f(physics["tibia_g"] / 1000.0)),
            '            <geom name="foot%d" type="sphere" pos="%s" size="%s" mass="0.002" contype="1" '
            'condim="3" friction="%s 0.005 0.0001" rgba=".9 .5 .1 1"/>' % (n, _xyz(tibia, 0, 0), _f(foot_r), _f(mu)),
            '            <site name="foot%d" pos="%s"/>' % (n, _xyz(tibia, 0, 0)),
            "          </body>",
            "        </body>",
            "      </body>",
        ]
    out += ["    </body>", "  </worldbody>", "  <actuator>"]
    for i in range(6):
        for j in range(3):
            name = "%s%d" % (JOINTS[j], i + 1)
            out.append(
                '    <position name="%s" joint="%s" ctrlrange="%s %s"/>'
                % (name, name, _f(lim[2 * j]), _f(lim[2 * j + 1]))
            )
    out += ["  </actuator>", "</mujoco>", ""]
    return "\n".join(out)


def leg_names():
    """Leg labels 1 RF .. 6 LF, for reports."""
    return ["%d %s" % (i + 1, LEG_NAMES[i]) for i in range(6)]


def robot_physics(module):
    """(Geometry, SERVO, PHYSICS) of a robot file, all checked (ValueError names what is wrong)."""
    from hexapod import geometry

    g = geometry.load(module)
    if g.servo is None:
        raise ValueError("robot %r: SERVO is missing (physics needs the servo spec)" % (g.name,))
    physics = check_physics(g.name, getattr(module, "PHYSICS", None))
    return g, dict(g.servo), physics
