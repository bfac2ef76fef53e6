"""The firmware on an emulated Raspberry Pi Pico (real MicroPython rp2 firmware in rp2040js):
Thumb viper code equals the plain solver and CPython bit for bit, every module imports as .mpy,
the robot's frames equal the host's. Skipped only where Node.js or the firmware is missing.
"""

import math
import os
import random
import struct

import pytest

from hexapod import leg as L
from hexapod_host import FIRMWARE
from hexapod_host.pico import emulator as pico
from hexapod_host.testing.runtimes import CPythonRuntime

REASON = pico.missing()
pytestmark = pytest.mark.skipif(REASON is not None, reason=REASON or "")


@pytest.fixture
def fs(pico_fs):
    """The staged firmware's littlefs image (what a flash puts on the board): conftest's, one a test process."""
    return pico_fs


def on_board(source, fs):
    status, out, err, stats = pico.run_source(source, fs=fs, timeout=300)
    assert status == 0, out + err
    print(stats)
    return out, stats


# Seed 004's leg with the servos' full travel, and one whose limits bind inside the reach.
LEGS = (
    dict(coxa=300, femur=850, tibia=1250, femur_offset=320, limits=L.DEFAULT_LIMITS),
    dict(coxa=300, femur=850, tibia=1250, femur_offset=320, limits=(-4000, 3500, -3000, 6000, -15000, -3000)),
)


def shell_feet(leg, n, rng):
    """n feet around the leg: a third within a unit of the outer shell, a third of the inner,
    the rest anywhere in a box around the reach (0.1 mm)."""
    feet = []
    for k in range(n):
        yaw = rng.uniform(-1.8, 1.8)  # the coxa limits are +-40 and +-90 deg: both sides of each
        pitch = rng.uniform(-2.2, 2.2)
        kind = k % 3
        if kind == 0:
            c = leg["femur"] + leg["tibia"] + rng.uniform(-1.5, 1.5)
        elif kind == 1:
            c = abs(leg["femur"] - leg["tibia"]) + rng.uniform(-1.5, 1.5)
        else:
            c = rng.uniform(0, leg["femur"] + leg["tibia"] + 200)
        h = leg["coxa"] + c * math.cos(pitch)
        x, y = h * math.cos(yaw), h * math.sin(yaw)
        z = leg["femur_offset"] + c * math.sin(pitch)
        feet.append((round(x), round(y), round(z)))
    return feet


def solve_source(legs, feet):
    """Firmware-side source: each foot through Leg.ik with the plain solver and with the viper
    one (where the port has it); one line per foot: code, excess (on refusal), three angles, twice."""
    return """
import sys
from array import array
from hexapod import leg as L
fast = L.solve
if sys.implementation.name == "micropython":
    from hexapod import _leg_viper as F
    fast = F.solve
LEGS = %r
# x, y, z per foot as 16-bit words: a bytes literal compiles fast on the board, a tuple does not.
FEET = [array("h", b) for b in %r]
for spec, feet in zip(LEGS, FEET):
    plain = L.Leg(**spec)
    plain._solver = L.solve
    quick = L.Leg(**spec)
    quick._solver = fast
    o1 = array("i", [0, 0, 0])
    o2 = array("i", [0, 0, 0])
    for k in range(0, len(feet), 3):
        x, y, z = feet[k], feet[k + 1], feet[k + 2]
        c1 = plain.ik(x, y, z, o1)
        c2 = quick.ik(x, y, z, o2)
        e1 = plain.excess if c1 else 0
        e2 = quick.excess if c2 else 0
        print(c1, e1, o1[0], o1[1], o1[2], c2, e2, o2[0], o2[1], o2[2])
print("viper", fast is not L.solve)
""" % (legs, [struct.pack("<%dh" % (3 * len(f)), *[v for p in f for v in p]) for f in feet])


# Past the 3 m coordinate bound, at it, and the leg's own origin.
EDGE_FEET = [(30001, 0, 0), (0, -30001, 0), (0, 0, 30001), (30000, 0, 0), (0, 0, 0), (300, 0, 320)]


def test_viper_on_thumb_equals_plain_solver_and_cpython(fs):
    rng = random.Random(9)
    legs = [dict(s, limits=tuple(s["limits"])) for s in LEGS]
    feet = [EDGE_FEET + shell_feet(s, 1000, rng) for s in legs]
    source = solve_source(legs, feet)
    board, stats = on_board(source, fs)
    host = CPythonRuntime().run(source)
    assert board.splitlines()[-1] == "viper True"  # the Thumb viper solver ran, not the fallback
    assert host.splitlines()[-1] == "viper False"  # CPython has only the plain solver
    rows = [tuple(int(v) for v in line.split()) for line in board.splitlines()[:-1]]
    assert len(rows) == 2 * (1000 + len(EDGE_FEET))
    differ = [r for r in rows if r[:5] != r[5:]]
    assert not differ, differ[:5]  # viper == plain on Thumb: code, excess, angles
    assert board.splitlines()[:-1] == host.splitlines()[:-1]  # and both == CPython, line for line
    # The feet reach both shells from both sides and draw every answer a leg can give.
    codes = {r[0] for r in rows}
    assert codes == set(range(L.OUT_OF_RANGE + 1)), codes
    inside = [r for r in rows if r[0] == L.OK]
    assert len(inside) > 250  # and hundreds of angle triples compared, not only refusals


def staged_modules():
    """Every module a flash puts on the board as .mpy (dotted names), from the staged tree."""
    with pico.tempfile.TemporaryDirectory() as tmp:
        pico.stage(tmp)
        names = []
        for root, _, files in os.walk(tmp):
            for f in files:
                if f.endswith(".mpy"):
                    rel = os.path.relpath(os.path.join(root, f), tmp)[:-4]
                    names.append(rel.replace(os.sep, ".").removesuffix(".__init__"))
    return sorted(names)


def test_every_module_imports_as_mpy_with_the_heap_left(fs):
    names = staged_modules()
    expected = {"runner", "boards.pico", "robots.default", "drivers.pca9685", "drivers.hcsr04"}
    core = {"hexapod." + f[:-3] for f in os.listdir(os.path.join(FIRMWARE, "hexapod")) if f.endswith(".py")}
    core = {n.removesuffix(".__init__") for n in core}
    assert expected | core <= set(names) and not [n for n in names if ".cp_" in n]
    # The console imports stream at the first `stream` (telemetry, kept while the console lives),
    # selftest for `selftest` (dropped after the command): selftest last, on top of a streaming board;
    # consoleparts.selftestbus, selftestboard and selftestsonar come with the checks (one after the
    # other), consoleparts.selftestsweep with `selftest servos L` only: the last row has all four
    # (more than either job loads). consoleparts.more, .sonar, .setting and .wall (the reporting and the setting
    # commands) come at the first of theirs and stay 30 s after the last: first of the on-demand
    # ones (a `status` just before `selftest` leaves one loaded).
    on_demand = ["consoleparts.more", "consoleparts.sonar", "consoleparts.setting", "consoleparts.wall"]
    on_demand += ["drivers.stream", "selftest"]
    on_demand += ["consoleparts.selftestbus", "consoleparts.selftestboard", "consoleparts.selftestsonar"]
    on_demand.append("consoleparts.selftestsweep")
    # hexapod.jog (the Robot's jog moves; Robot.calibrate is resident) comes with the first jog
    # command, or with the sweep (Robot.jog_joint): the last row has it too.
    on_demand.append("hexapod.jog")
    resident_names = [n for n in names if n not in on_demand and n != "drivers._stream_viper"]  # stream's twin: with it
    # A jog session's commands (consoleparts.jog, .joint, .caledit, .calset): loaded for the session,
    # let go after it, never at boot (consolecal, the file's, is: below).
    session = ("consoleparts.jog", "consoleparts.joint", "consoleparts.caledit", "consoleparts.calset")
    resident_names = [n for n in resident_names if n not in session]
    # The calibration commands' module comes and goes: console.start reads the calibration file
    # with it at boot and lets it go (its names stay: qstrs), each calibration command likewise;
    # calstore (the file's read and check) as well: the boot's load, a calibration session (with
    # consolecal) and selftest's check take it, and let it go.
    for name in ("calstore", "consolecal"):
        resident_names.remove(name)
        resident_names.append(name)
    source = """
import gc
gc.collect()
print("free", gc.mem_free())
def load(names):
    for name in names:
        m = __import__(name, None, None, ("x",))
        gc.collect()
        print(name, getattr(m, "__file__", "?"), gc.mem_free())


# In a function: its frame is gone by the release, so no stale pointer on the VM's stack keeps a
# released module alive for the conservative collector.
load(%r)
import hexapod
hexapod.release(*hexapod.BOOT_ONLY, "robots.default", "robots.default_cal")  # as main.main does
hexapod.release("consolecal", "calstore")  # as console.start does
gc.collect()
print("resident", gc.mem_free())
load(%r)
""" % (resident_names, on_demand)
    out, _ = on_board(source, fs)
    lines = out.splitlines()
    free0 = int(lines[0].split()[1])
    k = len(resident_names) + 1
    rows = [line.split() for line in lines[1:k] + lines[k + 1 :]]
    resident = int(lines[k].split()[1])
    assert [r[0] for r in rows] == resident_names + on_demand
    for name, path, _ in rows:
        assert path.endswith(".mpy") and path.replace("/", ".")[:-4].removesuffix(".__init__") == name, (name, path)
    left = int(rows[len(resident_names) - 1][2])
    streaming = int(rows[len(resident_names) + on_demand.index("drivers.stream")][2])
    in_selftest = int(rows[-1][2])
    print(
        "heap: %d bytes free at start, %d after importing the %d resident modules, %d once main.main has"
        " released the boot-only ones, %d once `stream` loaded its module, %d while `selftest servos` runs too"
        % (free0, left, len(resident_names), resident, streaming, in_selftest)
    )
    # A Pico has ~240 KB of heap. The loop allocates nothing a frame; what the running set must leave
    # free is room for what comes on demand: `selftest` (its module and checks: 10.3 KB measured on
    # 2026-11-27) above its own floor below (45 KB), plus one more qstr pool. MicroPython keeps every
    # name a loaded module interns for good (hexapod.release frees code, never names) in pools that
    # double: the 7th, 8.2 KB, opened when the running names passed ~1,260 (the fault log, the
    # link's tags and issue 19's split together: 1,311), and the next, ~16 KB, opens near 2,500
    # names. 45 + 10.3 + 16 = 71.3 KB: 72 KB (30 % of the heap) stays free while the loop runs.
    # History: 100 KB until 2026-11-24 (the viper tick paths and the background I2C sender took
    # ~12 KB for a 3x faster frame: docs/pico.md); 90 KB (3/8) until the 7th pool opened.
    assert free0 > 200000 and resident > 72000, (free0, left, resident)
    assert resident - left > 7000  # the validators' and the robot's files' code really went
    # While `selftest` runs its checks (never during a walk: nothing else needs the heap then),
    # 3/16 of the heap (45 KB) is still free: the new qstr pool its names may open included.
    assert in_selftest > 45000, in_selftest


# Stand up, then walk: forward, crab, ... (0.1 mm/s, cdeg/s), a new command every 40 ticks from tick 60.
WALK_SOURCE = """
import robots.default as robot_file
from hexapod import geometry, tick
g = geometry.load(robot_file)
frames = tick.FrameBuffer()
robot = tick.Robot(g, tick.default_servos(g), frames)
robot.stand_up()
t = 0
codes = 0
for k in range(%d):
    if k >= 60 and k %% 40 == 20:
        c = ((1200, 0, 0), (600, 600, 0), (0, 0, 3000), (900, -300, -1500), (-800, 200, 1000))[(k // 40) %% 5]
        robot.walk(c[0], c[1], c[2])
    codes += robot.tick(t) != 0
    print(" ".join([str(p) for p in frames.pulses]))
    t += 20
print("frames", frames.frames, "held", codes, "mode", robot.mode)
"""


def test_stand_up_and_walk_frames_equal_the_hosts(fs):
    source = WALK_SOURCE % 130
    board, _ = on_board(source, fs)
    host = CPythonRuntime().run(source)
    assert board == host
    lines = board.splitlines()
    frames = [[int(v) for v in line.split()] for line in lines[:-1]]
    assert len(frames) == 130 and lines[-1] == "frames 130 held 0 mode 4"  # walking (tick.WALKING)
    # Every pulse inside the servos' 600..2400 us (seed 001), and the legs really moved; the
    # soft start's first 16 frames give the middle and rear pairs no pulse yet (0).
    assert all(600 <= p <= 2400 for f in frames[16:] for p in f)
    assert [sum(1 for p in f if p) for f in frames[:17:8]] == [6, 12, 18]
    assert all(p == 0 or 600 <= p <= 2400 for f in frames[:16] for p in f)
    assert len({tuple(f) for f in frames[60:]}) > 40
