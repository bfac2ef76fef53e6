"""The core is bit-identical on CPython and in the MicroPython VM, and allocates nothing there."""

import math
import random

from hexapod.leg import COORD_MAX
from hexapod_host.testing.runtimes import HEAP_PROBE

GEOMETRIES = [(300, 450, 620, 0), (300, 850, 1250, 320), (1500, 2500, 2500, 1500), (0, 100, 120, 0)]

SOLVE = """
import sys
from hexapod.leg import Leg
legs = [Leg(coxa=g[0], femur=g[1], tibia=g[2], femur_offset=g[3]) for g in GEOMETRIES]
out = [0] * 6
for line in sys.stdin:
    w = [int(v) for v in line.split()]
    leg = legs[w[0]]
    code = leg.ik(w[1], w[2], w[3], out, 0)
    leg.fk(w[4], w[5], w[6], out, 3)
    print(code, leg.excess if code else 0, out[0], out[1], out[2], out[3], out[4], out[5])
"""


def vectors(n, seed=3):
    """n lines: geometry index, a foot point (mostly reachable, some far/near/absurd), FK angles."""
    rnd = random.Random(seed)
    lines = []
    for k in range(n):
        gi = k % len(GEOMETRIES)
        coxa, femur, tibia, off = GEOMETRIES[gi]
        if k % 10 == 9:
            x, y, z = (rnd.randint(-COORD_MAX - 50, COORD_MAX + 50) for _ in range(3))
        else:
            c = rnd.uniform(abs(femur - tibia) - 3, femur + tibia + 3)
            a, p = rnd.uniform(-math.pi, math.pi), rnd.uniform(-math.pi / 2, math.pi / 2)
            r = c * math.cos(p) + coxa
            x, y, z = round(r * math.cos(a)), round(r * math.sin(a)), round(c * math.sin(p) + off)
        t = (rnd.randint(-18000, 18000), rnd.randint(-9000, 9000), rnd.randint(-18000, 0))
        lines.append("%d %d %d %d %d %d %d" % ((gi, x, y, z) + t))
    return "\n".join(lines) + "\n"


def test_ten_thousand_ik_fk_vectors_bit_identical(both_runtimes):
    source = "GEOMETRIES = %r\n%s" % (GEOMETRIES, SOLVE)
    cp, mp = both_runtimes(source, stdin=vectors(12000))
    rows = cp.splitlines()
    assert len(rows) == 12000
    codes = {row.split()[0] for row in rows}
    assert {"0", "1", "2", "9"} <= codes, codes  # solved, too far, too close, out of range all seen
    assert cp == mp


ALLOC = (
    HEAP_PROBE
    + """
from hexapod.leg import Leg
leg = Leg(coxa=300, femur=850, tibia=1250, femur_offset=320)
feet = ((1200, 300, -800), (1300, 0, -700), (1100, -400, -900), (1250, 200, -600), (1000, 100, -1000),
        (1400, -100, -500), (9999, 0, 0), (700, 0, 320), (-1200, 300, -800), (0, 0, 99999))
out = [0] * 18


def six(n):
    for _ in range(n):
        i = 0
        for p in feet:
            leg.ik(p[0], p[1], p[2], out, i % 18)
            leg.fk(out[0], out[1], out[2], out, 3)
            i += 3


print(heap_bytes(six, 200))
"""
)


def test_solving_all_six_legs_allocates_nothing(mp):
    assert mp.value(ALLOC, heapsize="128k") == 0


def test_allocation_probe_sees_an_allocation(mp):
    """The probe is not blind: a float in the loop shows up as heap bytes."""
    leaky = ALLOC.replace("leg.fk(out[0], out[1], out[2], out, 3)", "out[3] = int(out[0] * 0.5)")
    assert mp.value(leaky, heapsize="128k") > 0
