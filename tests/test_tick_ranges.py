"""Every intermediate of the whole tick stays a MicroPython small int (|v| < 2**30).

All core modules (hexapod.*) are imported through an AST rewrite that passes the result of
every arithmetic operation through a checker; then the gait-limit sweep (every gait, extreme
steps, lifts, cycle times and poses, random commands over the full range) runs on them.
"""

import ast
import contextlib
import importlib.abc
import importlib.util
import os
import sys

from hexapod_host import FIRMWARE
from tests.test_gait_limits import CASES, SWEEP
from tests.test_leg_ranges import SMALL, Checker, Wrap


class InstrumentedCore(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Imports hexapod.* from source, rewritten so every operation is checked."""

    def __init__(self, checker):
        self.checker = checker

    def find_spec(self, name, path, target=None):
        if name != "hexapod" and not name.startswith("hexapod."):
            return None
        if name.endswith("_viper"):
            return None  # the viper twins: MicroPython only; the plain modules do not import them on CPython
        parts = name.split(".")
        base = os.path.join(FIRMWARE, *parts)
        is_pkg = os.path.isdir(base)
        origin = os.path.join(base, "__init__.py") if is_pkg else base + ".py"
        return importlib.util.spec_from_file_location(
            name, origin, loader=self, submodule_search_locations=[base] if is_pkg else None
        )

    def create_module(self, spec):
        return None

    def exec_module(self, module):
        with open(module.__spec__.origin) as f:
            tree = Wrap().visit(ast.parse(f.read()))
        ast.fix_missing_locations(tree)
        module._chk_ = self.checker.hook
        exec(compile(tree, module.__spec__.origin, "exec"), module.__dict__)


@contextlib.contextmanager
def instrumented_core(checker):
    """The hexapod package imported afresh through InstrumentedCore(checker) while the block runs;
    the modules that were loaded before are put back after it."""
    saved = {k: v for k, v in sys.modules.items() if k == "hexapod" or k.startswith("hexapod.")}
    finder = InstrumentedCore(checker)
    for k in saved:
        del sys.modules[k]
    sys.meta_path.insert(0, finder)
    try:
        yield
    finally:
        sys.meta_path.remove(finder)
        for k in [k for k in sys.modules if k == "hexapod" or k.startswith("hexapod.")]:
            del sys.modules[k]
        sys.modules.update(saved)


def test_every_intermediate_of_the_tick_fits_a_small_int():
    checker = Checker()
    out = []
    with instrumented_core(checker):
        ns = {"CASES": CASES, "COMMANDS": 8, "print": out.append}
        exec(compile(SWEEP, "<sweep>", "exec"), ns)
        assert sys.modules["hexapod.tick"].__dict__.get("_chk_") is checker.hook  # the rewritten core ran
    assert len(out) == len(CASES)
    ticks = sum(row[2] for row in out)
    assert ticks > 1000
    assert all(row[3] == 0 for row in out)  # and no angle left its limit on the way
    print("largest intermediate of the tick: %d (%.1f%% of 2**30)" % (checker.biggest, 100 * checker.biggest / SMALL))
    assert checker.biggest < SMALL
