# Runs inside the MicroPython VM: times and weighs the fixed-point six-leg solve against
# the same solve written with floats (math.atan2/acos/sqrt), in one run. Prints one JSON line.
import gc
import json
import math
import time

from hexapod.leg import Leg

COXA, FEMUR, TIBIA, OFFSET = 300, 850, 1250, 320  # seed 004's leg, 0.1 mm
FEET = (
    (1200, 300, -800),
    (1300, 0, -700),
    (1100, -400, -900),
    (1250, 200, -600),
    (1000, 100, -1000),
    (1400, -100, -500),
)


def float_ik(x, y, z, out, i):
    """The textbook float solve (seed 003 eq. 1-9, atan2 form), same frame, cdeg out."""
    t1 = math.atan2(y, x)
    h = math.sqrt(x * x + y * y) - COXA
    v = z - OFFSET
    c2 = h * h + v * v
    c = math.sqrt(c2)
    b = math.acos((FEMUR * FEMUR + c2 - TIBIA * TIBIA) / (2 * FEMUR * c))
    g = math.acos((FEMUR * FEMUR + TIBIA * TIBIA - c2) / (2 * FEMUR * TIBIA))
    out[i] = int(math.degrees(t1) * 100 + 0.5)
    out[i + 1] = int((math.degrees(math.atan2(v, h) + b)) * 100 + 0.5)
    out[i + 2] = int((math.degrees(g) - 180) * 100 + 0.5)


def six_fixed(leg, out):
    i = 0
    for p in FEET:
        leg.ik(p[0], p[1], p[2], out, i)
        i += 3


def six_float(leg, out):
    i = 0
    for p in FEET:
        float_ik(p[0], p[1], p[2], out, i)
        i += 3


def measure(fn, leg, out, rounds):
    fn(leg, out)
    gc.collect()
    gc.disable()
    before = gc.mem_alloc()
    fn(leg, out)
    heap = gc.mem_alloc() - before
    gc.enable()
    gc.collect()
    best = None
    for _ in range(5):
        t0 = time.ticks_us()
        for _ in range(rounds):
            fn(leg, out)
        us = time.ticks_diff(time.ticks_us(), t0)
        if best is None or us < best:
            best = us
    return best / rounds, heap


def main(rounds=2000):
    leg = Leg(coxa=COXA, femur=FEMUR, tibia=TIBIA, femur_offset=OFFSET)
    out_fixed = [0] * 18
    out_float = [0] * 18
    fixed_us, fixed_bytes = measure(six_fixed, leg, out_fixed, rounds)
    float_us, float_bytes = measure(six_float, leg, out_float, rounds)
    worst = 0
    for k in range(18):
        d = abs(out_fixed[k] - out_float[k])
        worst = d if d > worst else worst
    print(
        json.dumps(
            {
                "bench": "ik",
                "runtime": "micropython",
                "legs": 6,
                "rounds": rounds,
                "fixed_us": round(fixed_us, 2),
                "float_us": round(float_us, 2),
                "ratio": round(fixed_us / float_us, 3),
                "fixed_bytes": fixed_bytes,
                "float_bytes": float_bytes,
                "max_diff_cdeg": worst,
            }
        )
    )


main()
