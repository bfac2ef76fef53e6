# Runs inside the MicroPython VM: times and weighs the fixed-point six-leg solve against
# the same solve written with floats (math.atan2/acos/sqrt), in one run. Prints one JSON line.
import gc
import json
import math
import sys
import time

from hexapod import leg as leg_module
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


def heap_bytes(fn, leg, out):
    fn(leg, out)
    gc.collect()
    gc.disable()
    before = gc.mem_alloc()
    fn(leg, out)
    after = gc.mem_alloc()
    gc.enable()
    return after - before


def time_us(fn, leg, out, rounds):
    gc.collect()
    t0 = time.ticks_us()
    for _ in range(rounds):
        fn(leg, out)
    return time.ticks_diff(time.ticks_us(), t0) / rounds


def best_interleaved(cases, rounds, repeats=7):
    """Best time per call of each case; cases take turns, so machine load hits all alike."""
    best = [None] * len(cases)
    for _ in range(repeats):
        for k in range(len(cases)):
            us = time_us(cases[k][0], cases[k][1], cases[k][2], rounds)
            if best[k] is None or us < best[k]:
                best[k] = us
    return best


def main(rounds=2000, repeats=7):
    leg = Leg(coxa=COXA, femur=FEMUR, tibia=TIBIA, femur_offset=OFFSET)
    out_fixed = [0] * 18
    out_float = [0] * 18
    # The same solve without the viper emitter, as CircuitPython and ports without viper run it.
    viper = leg._solver is not leg_module.solve
    plain = Leg(coxa=COXA, femur=FEMUR, tibia=TIBIA, femur_offset=OFFSET)
    plain._solver = leg_module.solve
    out_plain = [0] * 18
    cases = ((six_fixed, leg, out_fixed), (six_float, leg, out_float), (six_fixed, plain, out_plain))
    fixed_bytes, float_bytes, plain_bytes = (heap_bytes(*c) for c in cases)
    fixed_us, float_us, plain_us = best_interleaved(cases, rounds, repeats)
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
                "viper": viper,
                "plain_us": round(plain_us, 2),
                "plain_bytes": plain_bytes,
                "plain_ratio": round(plain_us / float_us, 3),
                "fixed_bytes": fixed_bytes,
                "float_bytes": float_bytes,
                "max_diff_cdeg": worst,
            }
        )
    )


# Arguments: [rounds] [repeats] (the emulated Pico runs this with a few rounds, once: its clock
# has no noise to filter out).
main(*[int(a) for a in sys.argv[1:3]])
