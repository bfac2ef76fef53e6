"""Default build: seed 004's leg (coxa 30, femur 85, tibia 125 mm, femur joint 32 mm up)
on a 175 x 155 mm rectangular body like seed 004's. Plain data, read by hexapod.geometry.load.

Units: lengths 0.1 mm, angles centidegrees. Body frame: x forward, y left, z up, origin
at the body centre at coxa height. Legs 1 RF, 2 RM, 3 RR, 4 LR, 5 LM, 6 LF.
"""

NAME = "default"

COXA = 300  # coxa axis to femur axis, 0.1 mm (seed 004 a1)
FEMUR = 850  # femur axis to tibia axis (a2)
TIBIA = 1250  # tibia axis to the foot (a3)
FEMUR_OFFSET = 320  # femur axis above the coxa origin (d1)

# Joint limits, cdeg: coxa min, max, femur min, max, tibia min, max (seed 001's 180-degree servos).
LIMITS = (-9000, 9000, -9000, 9000, -18000, 0)

# Coxa axis (x, y) in the body frame, 0.1 mm, and mount angle (leg's outward direction,
# counter-clockwise from +x), cdeg: corner legs at the corners, middle legs mid-side.
MOUNTS = (
    (875, -775, -4500),  # 1 RF
    (0, -775, -9000),  # 2 RM
    (-875, -775, -13500),  # 3 RR
    (-875, 775, 13500),  # 4 LR
    (0, 775, 9000),  # 5 LM
    (875, 775, 4500),  # 6 LF
)

NEUTRAL_REACH = 1300  # neutral foot: this far out from the coxa axis along the mount, 0.1 mm
BODY_HEIGHT = 800  # coxa joints above the ground when standing, 0.1 mm
BODY_HEIGHT_MIN = 600  # allowed range of the body height setting
BODY_HEIGHT_MAX = 1000
SIT_HEIGHT = 300  # coxa joints above the ground with the body resting on it, 0.1 mm
FOOT_CLEARANCE = 100  # how far feet lift off the ground while the body rests, 0.1 mm

# The servos (MG996R class at 6 V), integers: stall torque (mN m), no-load speed (ms per 60
# degrees), mass (g), position gain of the servo's loop (mN m per rad), the motor's inertia
# seen at the horn through the gears (armature, g cm^2) and how much of the no-load speed
# the walk may use. The MuJoCo model (hexapod sim physics) uses all of it.
SERVO = {
    "stall_torque_mnm": 1100,
    "speed_ms_per_60deg": 170,
    "mass_g": 55,
    "kp_mnm_per_rad": 20000,
    "armature_g_cm2": 20000,
    # Optional: the walk turns no joint faster than this share of the no-load speed, scaling
    # commands and refusing gait/cycle/lift settings that would need more (docs/physics.md).
    # 400 (282 cdeg a tick) keeps the tripod at or under 80 % of stall in physics; its stance
    # femurs already spend ~75 % holding the body up. Leave it out to walk unguarded.
    "planner_share_permille": 400,
    # Optional: on three feet (the tripod) a stance foot goes at most this much (0.1 mm) farther
    # from its coxa axis than neutral. Stepping sideways 30 mm out, the middle femur holding
    # the body peaked at 84 % of stall in physics; 15 mm out, at most 79.4 % (docs/physics.md).
    "stance_out_max": 150,
}

# Each gait's cycle time (ms) until set_params sets another: tripod, tetrapod, ripple, wave.
# The fastest walk the servo guard above allows at a 30 mm step and lift (docs/physics.md);
# optional, 1000 each when absent. Slower-swinging gaits need longer cycles.
GAIT_CYCLE_MS = (1000, 2220, 2280, 4320)

# For physics only (host/hexapod_host/physics/mjcf.py): masses without the servos (g), the body's
# thickness (0.1 mm), the foot's friction with the floor (per mille) and its sphere (0.1 mm).
PHYSICS = {
    "body_g": 600,
    "coxa_g": 15,
    "femur_g": 20,
    "tibia_g": 25,
    "body_thickness": 400,
    "foot_friction_permille": 900,
    "foot_radius": 50,
}
