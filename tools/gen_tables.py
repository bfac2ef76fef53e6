"""Print the literal lookup tables of firmware/hexapod/fixmath.py.

The firmware has no floats at run time, so its tables are integer literals made here
with CPython's math module; tests/test_fixmath.py checks that the literals still match.
"""

import math

ATAN_STEPS = 256  # intervals of tan over [0, 1]
SIN_STEPS = 360  # intervals of sin over [0, 90] degrees (0.25 degree each)
DEG = 10000  # table unit: 1e-4 degree
ONE = 1 << 15  # Q15 one


def atan_table():
    """atan(i / ATAN_STEPS) in 1e-4 degree, for i = 0 .. ATAN_STEPS."""
    return tuple(round(math.degrees(math.atan(i / ATAN_STEPS)) * DEG) for i in range(ATAN_STEPS + 1))


def sin_table():
    """sin(i * 90 / SIN_STEPS degrees) in Q15, for i = 0 .. SIN_STEPS."""
    return tuple(round(math.sin(math.radians(i * 90 / SIN_STEPS)) * ONE) for i in range(SIN_STEPS + 1))


def literal(name, values, per_line=12):
    lines = ["%s = (" % name]
    for i in range(0, len(values), per_line):
        lines.append("    " + ", ".join(str(v) for v in values[i : i + per_line]) + ",")
    lines.append(")")
    return "\n".join(lines)


if __name__ == "__main__":
    print(literal("_ATAN", atan_table()))
    print(literal("_SIN", sin_table()))
