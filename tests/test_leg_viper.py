"""The viper solver (hexapod/_leg_viper.py) equals the plain one (hexapod.leg.solve) exactly.

Run inside the MicroPython VM, where the viper emitter exists: 150,000+ feet over extreme
and ordinary legs, every result compared: reason code, excess and the three angles.
"""

# draw(bits): the LCG both runtimes share (tests/scenarios/lcg.py), for the VM sources below
LCG = "from scenarios.lcg import Lcg\n\ndraw = Lcg().draw\n"

EQUAL = (
    LCG
    + """
from array import array
from hexapod import leg as L
from hexapod import _leg_viper as F

geoms = []
for coxa in (0, 300, 1500):
    for femur in (100, 450, 850, 2500):
        for tibia in (100, 620, 1250, 2500):
            for off in (-1500, -320, 0, 320, 1500):
                geoms.append((coxa, femur, tibia, off))
legs = [L.Leg(coxa=c, femur=f, tibia=t, femur_offset=o) for c, f, t, o in geoms]
assert legs[0]._solver is F.solve, "the VM should pick the viper solver"
edges = (0, 1, -1, 30000, -30000, 30001, -30001, 2500, -2500, 9000)
count = 0
differ = 0
solved = 0
for k in range(150000 + len(edges) ** 3):
    leg = legs[k % len(legs)]
    if k < len(edges) ** 3:
        x = edges[k % 10]
        y = edges[(k // 10) % 10]
        z = edges[k // 100]
    else:
        m = leg.reach + leg.coxa + 20
        x = draw(16) % (2 * m + 1) - m
        y = draw(16) % (2 * m + 1) - m
        z = draw(16) % (2 * m + 1) - m + leg.femur_offset
    g1 = array("i", leg._g)
    g2 = array("i", leg._g)
    c1 = L.solve(x, y, z, g1)
    c2 = F.solve(x, y, z, g2)
    same = c1 == c2 and (g1[L.G_EXCESS] == g2[L.G_EXCESS] if c1 else g1[L.G_T1 :] == g2[L.G_T1 :])
    if not same:
        differ += 1
        if differ < 5:
            print("differ", (x, y, z), leg.coxa, leg.femur, leg.tibia, leg.femur_offset, c1, c2, list(g1), list(g2))
    count += 1
    solved += c1 == 0
print((count, solved, differ))
"""
)


def test_viper_solver_equals_plain_solver(mp):
    count, solved, differ = mp.value(EQUAL)
    assert count > 150000 and solved > 30000, (count, solved)
    assert differ == 0
