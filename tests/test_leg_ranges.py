"""Every intermediate of the integer kinematics stays a MicroPython small int (|v| < 2**30).

The core's source is rewritten (AST) so that the result of every arithmetic operation passes
through a checker, then run on the extremes: the longest and shortest legs allowed, the
largest coxa and femur offsets, coordinates at +-COORD_MAX and at every early-exit bound,
points at full extension and minimum reach, and random points; FK over the whole circle.
"""

import ast
import importlib
import inspect
import itertools
import math
import random
import sys
import types

import pytest

from hexapod import fixmath, leg

SMALL = 1 << 30


class Checker:
    """Raises OverflowError for an int (not a bool) outside -2**30 <= v < 2**30; biggest: the largest
    |v| it was given. The rewritten code calls `hook` (its _chk_): for this class a closure that
    lets an int no larger than any seen before through with two comparisons, no method call, no
    max()/abs() (the tick's sweep makes ~10**8 checks: 3/4 of its time went to the method); a
    subclass that extends __call__ is its own hook."""

    def __init__(self):
        self._biggest = [0]
        self.hook = self._fast() if type(self).__call__ is Checker.__call__ else self

    @property
    def biggest(self):
        return self._biggest[0]

    def __call__(self, value):
        if isinstance(value, int) and not isinstance(value, bool):
            if not -SMALL <= value < SMALL:
                raise OverflowError("intermediate %d is not a small int" % value)
            self._biggest[0] = max(self._biggest[0], abs(value))
        return value

    def _fast(self):
        box = self._biggest
        seen = 0  # the largest |v| passed, capped at 2**30 - 1: within +-seen nothing is new and all fits

        def check(value):
            nonlocal seen
            if value.__class__ is int:
                if -seen <= value <= seen:
                    return value
            elif value.__class__ is bool or not isinstance(value, int):
                return value
            if not -SMALL <= value < SMALL:
                raise OverflowError("intermediate %d is not a small int" % value)
            v = -value if value < 0 else value
            if v > box[0]:
                box[0] = v
                seen = v if v < SMALL else SMALL - 1
            return value

        return check


class Wrap(ast.NodeTransformer):
    def _chk(self, node):
        return ast.copy_location(ast.Call(ast.Name("_chk_", ast.Load()), [node], []), node)

    def visit_BinOp(self, node):
        self.generic_visit(node)
        return self._chk(node)

    def visit_UnaryOp(self, node):
        self.generic_visit(node)
        return self._chk(node) if isinstance(node.op, ast.USub) else node

    def visit_AugAssign(self, node):
        self.generic_visit(node)
        load = ast.copy_location(type(node.target)(**{**vars(node.target), "ctx": ast.Load()}), node.target)
        value = self._chk(ast.BinOp(load, node.op, node.value))
        return ast.copy_location(ast.Assign([node.target], value), node)


def instrumented(module, checker, extra):
    tree = Wrap().visit(ast.parse(inspect.getsource(module)))
    ast.fix_missing_locations(tree)
    mod = types.ModuleType(module.__name__)
    mod.__dict__.update(extra, _chk_=checker.hook)
    exec(compile(tree, module.__file__, "exec"), mod.__dict__)
    return mod


def load(checker):
    saved = sys.modules["hexapod.fixmath"]
    try:
        fm = instrumented(fixmath, checker, {})
        sys.modules["hexapod.fixmath"] = fm
        lg = instrumented(leg, checker, {})
    finally:
        sys.modules["hexapod.fixmath"] = saved
    importlib.reload(fixmath)
    return fm, lg


def test_instrumentation_catches_an_overflow():
    chk = Checker()
    fm, _ = load(chk)
    try:
        fm.mul_q15(1 << 35, 32768)
    except OverflowError:
        return
    raise AssertionError("the checker let a big int through")


def test_the_checker_passes_exactly_the_small_ints():
    # The fast hook and the method: the same verdicts, the same largest value, at the very ends.
    for hook in (lambda c: c.hook, lambda c: c.__call__):
        chk = Checker()
        check = hook(chk)
        assert check(True) is True and check(2.5e12) == 2.5e12 and check((1 << 40,)) == (1 << 40,)  # not ints
        assert chk.biggest == 0
        assert check(-7) == -7 and check(5) == 5 and chk.biggest == 7
        assert check(SMALL - 1) == SMALL - 1 and chk.biggest == SMALL - 1
        for bad in (SMALL, -SMALL - 1, 1 << 40, -(1 << 40)):
            with pytest.raises(OverflowError, match="intermediate %d is not a small int" % bad):
                check(bad)
        assert check(-SMALL) == -SMALL and chk.biggest == SMALL  # allowed, and the run's final check fails
        with pytest.raises(OverflowError):
            check(SMALL)  # still refused once -2**30 was seen
        assert check(3) == 3 and chk.biggest == SMALL


def extreme_legs(lg):
    for coxa, femur, tibia, off in itertools.product(
        (0, lg.COXA_MAX),
        (lg.LINK_MIN, 700, lg.LINK_MAX),
        (lg.LINK_MIN, 1300, lg.LINK_MAX),
        (-lg.OFFSET_MAX, 0, lg.OFFSET_MAX),
    ):
        yield lg.Leg(coxa=coxa, femur=femur, tibia=tibia, femur_offset=off, limits=(-18000, 18000) * 3)


def probe_points(g, rnd):
    m = g.reach + g.coxa
    edges = (0, 1, -1, m, m + 1, -m, -m - 1, 2 * m, 30000, -30000, 30001, -30001, g.coxa, -g.coxa)
    for x, y in itertools.product(edges, repeat=2):
        for z in (0, g.femur_offset + g.reach, g.femur_offset - g.reach, 30000, -30000, 30001, g.femur_offset):
            yield x, y, z
    for c in (g.reach, g.reach - 1, g.min_reach, g.min_reach + 1, g.reach // 2):
        for _k in range(40):
            a = rnd.uniform(-math.pi, math.pi)
            p = rnd.uniform(-math.pi / 2, math.pi / 2)
            r = max(0.0, c * math.cos(p) + g.coxa)
            yield round(r * math.cos(a)), round(r * math.sin(a)), round(c * math.sin(p) + g.femur_offset)
    for _ in range(200):
        yield rnd.randint(-m, m), rnd.randint(-m, m), rnd.randint(-m, m)


def test_every_intermediate_fits_a_small_int():
    chk = Checker()
    fm, lg = load(chk)
    rnd = random.Random(11)
    out = [0] * 3
    solved = refused = 0
    for g in extreme_legs(lg):
        for x, y, z in probe_points(g, rnd):
            if g.ik(x, y, z, out) == lg.OK:
                solved += 1
                g.fk(out[0], out[1], out[2], out)
            else:
                refused += 1
        for t in range(-36000, 36001, 1237):
            g.fk(t, -t, t // 2, out)
            g.fk(t, 9000, -18000, out)
    assert solved > 5000 and refused > 5000, (solved, refused)
    print("largest intermediate of IK/FK: %d (%.1f%% of 2**30)" % (chk.biggest, 100 * chk.biggest / SMALL))
    for n in [0, 1, 2, 3, SMALL - 1, (1 << 28) - 1] + [rnd.randrange(SMALL) for _ in range(2000)]:
        fm.isqrt(n)
    for y, x in itertools.product((0, 1, -1, SMALL - 1, -(SMALL - 1), 32767, 32768, -32768), repeat=2):
        fm.atan2(y, x)
    for c in range(-(1 << 20), 1 << 20, 997):
        fm.sin(c)
        fm.cos(c)
    assert chk.biggest < SMALL
