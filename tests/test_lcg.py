"""The tests' shared generator (tests/scenarios/lcg.py) and its viper twin draw the same numbers."""

from scenarios.lcg import drawer

# The generator's first states from seed 12345, worked out here as the C library's rand() recurrence
# (multiplier 1103515245, increment 12345, modulo 2**31), not by the code under test.
FIRST = []
_s = 12345
for _ in range(3):
    _s = (_s * 1103515245 + 12345) % (1 << 31)
    FIRST.append(_s)


def test_the_draws_are_the_recurrence_top_bits_on_cpython():
    draw = drawer()
    assert [draw(31), draw(16), draw(1)] == [FIRST[0], FIRST[1] >> 15, FIRST[2] >> 30]


def test_the_viper_draw_gives_the_plain_numbers_on_the_vm(mp):
    # 30,000 draws of every width from 1 to 30 bits, the twin's against the plain class's.
    src = (
        "from scenarios import lcg\n"
        "from scenarios._lcg_viper import Lcg as Fast\n"
        "fast = lcg.drawer()\n"
        "plain = lcg.Lcg().draw\n"
        "bad = sum(fast(1 + n % 30) != plain(1 + n % 30) for n in range(30000))\n"
        "print((lcg._Fast is Fast, bad, lcg.drawer()(30)))\n"
    )
    uses_twin, bad, first = mp.value(src)
    assert uses_twin and bad == 0 and first == FIRST[0] >> 1, (uses_twin, bad, first)
