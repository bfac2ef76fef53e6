"""The support polygon and the centre of mass the 3-D view draws, from the same posed legs the
scene draws (source.pose: pulses -> servo maps inverted -> FK). Pure: no UI.

- The polygon: the stance feet in leg order (legs 1-6 run clockwise seen from above, so the
  feet down are its corners), on the ground.
- The centre of mass: the robot file's PHYSICS and SERVO masses (what the MuJoCo model,
  physics/mjcf.py, is built from) placed on the posed legs: the body with its six coxa servos at
  its centre, each link's mass at its middle, the femur servo at the femur joint, the tibia
  servo at the knee, the foot's 2 g at the foot. Projected onto the ground.
- The margin: hexapod.stability.support_margin (the firmware's own routine, in 0.1 mm) of the
  centre of mass inside the polygon: positive inside, negative outside, None with fewer than
  three feet down.
"""

import robots.default
from hexapod.stability import NO_SUPPORT, support_margin

NEAR_MM = 20.0  # a centre of mass closer than this to the polygon's edge is drawn "near"
FOOT_G = 2.0  # physics/mjcf.py's foot sphere


def masses(robot=robots.default):
    """(body g, per leg: coxa link, femur servo, femur link, tibia servo, tibia link, foot g)."""
    p, servo_g = robot.PHYSICS, robot.SERVO["mass_g"]
    body = p["body_g"] + 6 * servo_g  # the coxa servos sit in the body
    return body, (p["coxa_g"], servo_g, p["femur_g"], servo_g, p["tibia_g"], FOOT_G)


MASSES = masses()


def centre_of_mass(legs, weights=MASSES):
    """The centre of mass (x, y, z mm, body frame) of the body and its legs posed as `legs`
    (per leg its coxa axis, femur joint, knee, foot; body frame, mm)."""
    body_g, leg_g = weights
    total = body_g
    sx = sy = sz = 0.0  # the body's own mass sits at the origin
    for coxa_axis, femur_joint, knee, foot in legs:
        points = (
            [(coxa_axis[k] + femur_joint[k]) / 2 for k in range(3)],
            femur_joint,
            [(femur_joint[k] + knee[k]) / 2 for k in range(3)],
            knee,
            [(knee[k] + foot[k]) / 2 for k in range(3)],
            foot,
        )
        for g, p in zip(leg_g, points, strict=True):
            sx, sy, sz, total = sx + g * p[0], sy + g * p[1], sz + g * p[2], total + g
    return sx / total, sy / total, sz / total


def support(legs, stance, weights=MASSES):
    """What the view draws under the robot (body frame, mm): {"polygon": [[x, y], ...] the
    stance feet in leg order, "com": [x, y, z] the centre of mass, "margin_mm": its distance
    inside the polygon (negative outside; None with fewer than three feet down), "state": "ok",
    "near" (within NEAR_MM of an edge), "out" (outside) or "none" (no support)}."""
    com = centre_of_mass(legs, weights)
    feet = [leg[3] for leg in legs]
    # support_margin works in the firmware's 0.1 mm integers.
    xs = [round(f[0] * 10) for f in feet]
    ys = [round(f[1] * 10) for f in feet]
    m = support_margin(xs, ys, [bool(s) for s in stance], round(com[0] * 10), round(com[1] * 10))
    margin = None if m == NO_SUPPORT else m / 10
    if margin is None:
        state = "none"
    elif margin < 0:
        state = "out"
    else:
        state = "near" if margin < NEAR_MM else "ok"
    polygon = [[f[0], f[1]] for f, s in zip(feet, stance, strict=True) if s]
    return {"polygon": polygon, "com": list(com), "margin_mm": margin, "state": state}
