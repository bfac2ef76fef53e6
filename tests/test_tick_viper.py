"""The tick's viper twins equal their plain code exactly, on the host MicroPython VM and on the
emulated Pico (Thumb code). The frame (hexapod/_tick_viper.py, Robot._output): thousands of random
feet in and out of reach, level and posed bodies, joint limits that bind, and servo ranges whose
min or max sits exactly on the pulse a frame needs (taken) or one microsecond inside it (refused).
The walker's steps (hexapod/_walk_viper.py: swings, stance, move, begin, aim) and the pose check
(hexapod/_body_viper.py: settled) against Walker's and Body's plain methods.
"""

import ast

import pytest
from scenarios import on_board

from hexapod_host.pico import emulator as pico

# draw(bits): the LCG both runtimes share (tests/scenarios/lcg.py), for the sources below. Each
# source runs with CASES and SIDE: "both" compares the viper twin with its plain code case by case
# (the VM); "plain" or "viper" runs one side alone and prints, last, the digest (scenarios/digest.py)
# of every value the comparison uses, in order: the plain side's digest is what the viper's must
# be. Both sides make the same draws, so the Pico runs only the viper side (its Thumb code) and the
# host VM the plain code, whose results are the same on every MicroPython VM.
LCG = """from scenarios.digest import fold
from scenarios.lcg import drawer

draw = drawer()
PLAIN = SIDE != "viper"
VIPER = SIDE != "plain"
BOTH = PLAIN and VIPER
assert SIDE in ("both", "plain", "viper"), "SIDE %r: one of both, plain, viper" % SIDE
h = 0
plain = fast = before = code = None  # what one side alone never makes


def tally(n, plain, fast, *shown):
    # A case done: its values into the digest; with both sides, a difference counted (the first
    # three printed, with what the script shows of the case).
    global h, count, differ
    if BOTH and plain != fast:
        differ += 1
        if differ < 4:
            print("differ", n, *shown, plain, fast)
    h = fold(h, plain if PLAIN else fast)
    count += 1
"""

CASES = (
    LCG
    + """
import robots.default as robot_file
from hexapod import geometry, tick
from hexapod._tick_viper import output

G = geometry.load(robot_file)
# Leg 1 gets limits that bind inside the reach (all three joints), the others keep the file's.
G.legs[0].limits = (-1500, 1500, -1500, 2500, -12000, -6000)
r = tick.Robot(G, tick.default_servos(G), tick.FrameBuffer())
w = r.walker
count = taken = differ = limit_held = range_held = edge_taken = edge_held = 0


def pick(n):
    # Feet near neutral (most solve); one leg in four cases anywhere in a box past the reach.
    wild = draw(8) % 24
    for i in range(6):
        spread = 16 * (2600 if i == wild else 300)
        w.fx[i] = w.nx[i] + draw(16) % (2 * spread + 1) - spread
        w.fy[i] = w.ny[i] + draw(16) % (2 * spread + 1) - spread
        w.fz[i] = w.ground + (draw(16) % (2 * spread + 1) - spread) // 2
    if n % 3 == 0:
        for k in range(9):
            r.body.target[k] = 0
        r.body.jump()
    else:
        pose = [draw(10) % 401 - 200, draw(10) % 401 - 200, draw(10) % 401 - 200,
                draw(12) % 1001 - 500, draw(12) % 1001 - 500, draw(12) % 1001 - 500,
                draw(12) % 1001 - 500, draw(12) % 1001 - 500, draw(12) % 1001 - 500]
        r.body.set_target(pose)
        r.body.jump()


for k in range(18):
    r.servos[k].min_us = 500
    r.servos[k].max_us = 2500
moved = r.servos[0]
for n in range(CASES):
    pick(n)
    # Every range at 500-2500 us again: a case moves one at most (setting all 18 a case was
    # bytecode the Pico ran for nothing).
    moved.min_us = 500
    moved.max_us = 2500
    edge = n % 4
    if edge:
        # The frame's pulse of one servo becomes its range's end: exactly on it, or 1 us past. A
        # side alone places it with its own frame: were viper and plain ever to differ there, the
        # cases would part and so would the digests (nothing lost).
        if (r._output_plain() == tick.OK) if PLAIN else (output(r) == 0):
            k = draw(10) % 18
            s = moved = r.servos[k]
            on = r.pulses[k]
            if edge == 1:
                s.min_us = on
            elif edge == 2:
                s.max_us = on
            else:
                s.min_us = on + 1 if draw(1) else 500
                s.max_us = on - 1 if s.min_us == 500 else 2500
    old_a = list(r.angles)
    old_p = list(r.pulses)
    if VIPER:
        fast = (output(r) == 0, list(r.angles), list(r.pulses))
    if BOTH:
        r.angles[:] = old_a
        r.pulses[:] = old_p
    if PLAIN:
        code = r._output_plain()
        # What the viper twin must give: the plain frame's angles and pulses when it is taken, the
        # last frame's left as they were when it is refused.
        if code == tick.OK:
            plain = (True, list(r.angles), list(r.pulses))
            taken += 1
            edge_taken += edge in (1, 2)
        else:
            plain = (False, old_a, old_p)
            limit_held += code == tick.FRAME_IK and 3 <= r.fault_code <= 8
            range_held += code == tick.FRAME_SERVO
            edge_held += edge == 3 and code == tick.FRAME_SERVO
    tally(n, plain, fast, code)
print((count, taken, limit_held, range_held, edge_taken, edge_held, differ, h))
"""
)


SWINGS = (
    LCG
    + """
import robots.default as robot_file
from hexapod import geometry, walk
from hexapod.fixmath import cos, sin
from hexapod._walk_viper import swings

w = walk.Walker(geometry.load(robot_file))
count = differ = clamped = landed = done = short = 0
budget = walk.in_budget


def counted(walker, i, t, cv):
    # The plain swing's budget clamp, counted: how many of the cases land short.
    global short
    moved = budget(walker, i, t, cv)
    short += moved
    return moved


walk.in_budget = counted


def state(i):
    return (w.su[i], w.fx[i], w.fy[i], w.fz[i], list(w._xy), w.px[i], w.py[i], w.done[i])


def start(i, su, fx, fy):
    # Either side's swing starts from the same state: the foot where it was last tick, what the
    # swing writes cleared.
    w.su[i] = su
    w.fx[i] = fx
    w.fy[i] = fy
    w.fz[i] = w.px[i] = w.py[i] = w.done[i] = 0
    w._xy[0] = w._xy[1] = 0


for n in range(CASES):
    i = draw(8) % 6
    wt = 2 + draw(8) % 40  # swing ticks: the short swings (<= 3) take the stroke's other branch
    w.su[i] = draw(8) % wt
    home = n % 8 == 0  # no turn, no shift: the swing lands on neutral (the STOPPING branch)
    turn = 0 if home else draw(14) % 18001 - 9000
    w._aim[0] = cos(turn)
    w._aim[1] = sin(turn)
    w._aim[2] = 0 if home else draw(14) % 19201 - 9600
    w._aim[3] = 0 if n % 16 == 0 else draw(14) % 19201 - 9600  # half the homes land beside neutral
    w._carry[0] = draw(14) % 19201 - 9600
    w._carry[1] = draw(14) % 19201 - 9600
    w._carry[2] = draw(12) % 6001 - 3000
    w.sx[i] = w.nx[i] + draw(14) % 16001 - 8000
    w.sy[i] = w.ny[i] + draw(14) % 16001 - 8000
    w.rho[i] = 50 + draw(10) % 700  # small discs: both reach clamps bind often
    # The swing's servo budget: from none to more than any swing here needs, the lift-off's
    # distance from the coxa past the guard's band (srho) easing it or not.
    w.swing_max[i] = draw(12) % 3500
    w.srho[i] = draw(10) % 700
    w.stroke_gain = 32768 + draw(15)
    w.lift = 100 + draw(9) % 501
    w.ground = -(draw(12) % 1500 + 300) << 4
    # The landing's ground frame: heading anywhere, the body anywhere (< walk._REANCHOR).
    w.psi = draw(22) % 3600000
    w.bx = draw(22) % 4000001 - 2000000
    w.by = draw(22) % 4000001 - 2000000
    w.state = walk.STOPPING if draw(1) else walk.WALKING
    still = draw(1)
    w.done[i] = 0
    if home:
        w.rho[i] = 800
        if n % 32 == 0:  # its last tick, walking home (the STOPPING landing's test)
            w.su[i] = wt - 1
            w.state = walk.STOPPING
            still = 1
        # The foot exactly on its plan of the last tick (as the plain swing works it out): no re-aim.
        w.target(i, w._xy)
        w._in_reach(i, w._xy)
        w.carry_at(w.sx[i], w.sy[i], w._cv, 0)
        w.carry_at(w._xy[0], w._xy[1], w._cv, 2)
        w._swing_at(i, w.su[i], wt, w._plan)
        fx = w.fx[i] = w._plan[0]
        fy = w.fy[i] = w._plan[1]
    else:
        # Where the foot was last tick: near lift-off, off the plan by less or more than the
        # re-aim allows a tick (walk.REPLAN_STEP, 64 fine), so every branch runs.
        spread = 100 if n % 2 else 6000
        fx = w.fx[i] = w.sx[i] + draw(14) % (2 * spread + 1) - spread
        fy = w.fy[i] = w.sy[i] + draw(14) % (2 * spread + 1) - spread
    su = w.su[i]
    if PLAIN:
        start(i, su, fx, fy)
        plain = (w._swings(i, i + 1, wt, still),) + state(i)
        rim = (w.rho[i] << 4) ** 2 - (64 * w.rho[i])  # the reach disc's rim squared (fine), ~2 in
        clamped += (plain[5][0] - w.nx[i]) ** 2 + (plain[5][1] - w.ny[i]) ** 2 >= rim
        landed += plain[1] < 0
        done += plain[8]
    if VIPER:
        start(i, su, fx, fy)
        fast = (swings(w, i, i + 1, wt, still),) + state(i)
    tally(n, plain, fast)
print((count, clamped, landed, done, short, differ, h))
"""
)


STANCES = (
    LCG
    + """
import robots.default as robot_file
from hexapod import geometry, walk
from hexapod._walk_viper import stance

w = walk.Walker(geometry.load(robot_file))
reach = w.geometry.neutral_reach
count = differ = held = banded = 0
for n in range(CASES):
    for i in range(6):
        w.su[i] = -1 if draw(2) else draw(4)
        w.px[i] = w.nx[i] + draw(15) % 8001 - 4000
        w.py[i] = w.ny[i] + draw(15) % 8001 - 4000
        w.fx[i] = w.nx[i] + draw(14) % 16001 - 8000
        w.fy[i] = w.ny[i] + draw(14) % 16001 - 8000
        # Every other case a reach disc too wide to hold: only the ease band (5-35 mm) can.
        w.rho[i] = 200 + draw(10) % 800 if n % 2 else 30000
        b = 50 + draw(9) % 300
        w.band[i + 12] = (reach - b) * (reach - b)
        w.band[i + 18] = (reach + b) * (reach + b)
        w.ax[i] = w.ay[i] = 0
    bx = draw(16) % 200001 - 100000  # the ground frame's origin may lie far away (< _REANCHOR)
    by = draw(16) % 200001 - 100000
    for i in range(6):
        w.px[i] += bx
        w.py[i] += by
    cd = draw(16) % 72001 - 36000 if n % 4 == 0 else draw(10) % 1001 - 500  # turned a little, or anywhere
    if PLAIN:
        h1 = w._stance(bx, by, cd)  # 1 + the leg that holds, or 0
        plain = (h1, list(w.ax), list(w.ay))
        held += 1 if h1 else 0
        banded += 1 if h1 and n % 2 == 0 else 0
    if BOTH:
        for i in range(6):
            w.ax[i] = w.ay[i] = 0
    if VIPER:
        fast = (stance(w, bx, by, cd), list(w.ax), list(w.ay))
    tally(n, plain, fast)
print((count, held, banded, differ, h))
"""
)


MOVES = (
    LCG
    + """
import robots.default as robot_file
from hexapod import geometry, walk
from hexapod.fixmath import cos, mul_q15, sin
from hexapod._walk_viper import move

w = walk.Walker(geometry.load(robot_file))
count = differ = held = still = anchored = lifted = 0
FIELDS = ("held", "bx", "by", "cx", "cy", "psi", "_early")
LISTS = ("fx", "fy", "px", "py", "ax", "ay", "su", "sx", "sy")


def state():
    return tuple(getattr(w, f) for f in FIELDS) + tuple(list(getattr(w, f)) for f in LISTS)


def put(a, v):
    for j in range(len(v)):  # the walker's state is array("i"): no slice assignment from a list
        a[j] = v[j]


for n in range(CASES):
    # Mostly the wave (3), where a held foot may lift early (Walker._maybe_lift), at any phase.
    if n % 16 == 1:
        w.clock.set(draw(2) % 4 if n % 64 == 1 else 3, 500 + draw(12) % 4000)
    w.phase = draw(12) % w.clock.cycle_ticks
    w._early = draw(6)
    for i in range(6):
        w.su[i] = -1 if draw(2) else draw(4)
        w.sx[i] = w.sy[i] = 0
        w.fx[i] = w.nx[i] + draw(14) % 16001 - 8000
        w.fy[i] = w.ny[i] + draw(14) % 16001 - 8000
        w.rho[i] = 400 + draw(10) % 800
        w.ax[i] = w.ay[i] = 0
    # Walking at anything accepted, or not moving at all (the carries alone change).
    quiet = n % 8 == 0
    w.vel[0] = 0 if quiet else draw(13) % 6001 - 3000
    w.vel[1] = 0 if quiet else draw(13) % 6001 - 3000
    w.vel[2] = 0 if quiet else draw(15) % 18001 - 9000
    w.psi = draw(22) % 3600000 if n % 4 else (draw(1) * (3600000 - 20000) + draw(14) % 20000)  # or near the wrap
    w.cx = draw(10) % 1000
    w.cy = draw(10) % 1000
    w.held = draw(4)
    # The ground frame's origin near the body, or just inside or past the re-anchoring bound.
    far = 4194304 - 4000 if n % 3 == 0 else 0  # walk._REANCHOR, 2**22
    w.bx = (far + draw(13) % 8001) * (1 if draw(1) else -1)
    w.by = draw(16) % 200001 - 100000
    # Stance feet near neutral seen from the body at its heading (the others anywhere: held).
    c = cos((w.psi + 50) // 100)
    s = sin((w.psi + 50) // 100)
    for i in range(6):
        x = w.nx[i] + draw(14) % 14001 - 7000
        y = w.ny[i] + draw(14) % 14001 - 7000
        w.px[i] = w.bx + mul_q15(x, c) - mul_q15(y, s)
        w.py[i] = w.by + mul_q15(x, s) + mul_q15(y, c)
    before = state() if PLAIN else None  # the plain side's counters, the VM's rewind
    if PLAIN:
        w._move_body()
        plain = state()
        held += plain[0] != before[0]
        still += plain[1:3] == before[1:3] and plain[0] == before[0]
        anchored += plain[1] == 0 and before[1] != 0
        lifted += plain[len(FIELDS) + 6] != before[len(FIELDS) + 6]
    if BOTH:
        for f, v in zip(FIELDS, before[: len(FIELDS)]):
            setattr(w, f, v)
        for f, v in zip(LISTS, before[len(FIELDS) :]):
            put(getattr(w, f), v)
    if VIPER:
        move(w)
        fast = state()
    tally(n, plain, fast, before)
print((count, held, still, anchored, lifted, differ, h))
"""
)


def check_moves(result, cases):
    count, held, still, anchored, lifted, differ = result
    assert count == cases and held > cases // 10 and still > cases // 20 and anchored > cases // 50, result
    assert lifted > cases // 100, result  # some held feet lift early instead
    assert count - held - still > cases // 5, result  # moved
    assert differ == 0, result


STARTS = (
    LCG
    + """
import robots.default as robot_file
from hexapod import body, geometry, walk
from hexapod._body_viper import settled
from hexapod._walk_viper import aim, begin

g = geometry.load(robot_file)
w = walk.Walker(g)
b = body.Body(g)
count = differ = still = lifted = made = level = 0
FIELDS = ("vel", "su", "sx", "sy", "done", "_aim", "_aim_key", "_carry", "goal")


def state():
    return [list(getattr(w, f)) for f in FIELDS]


def put(a, v):
    for j in range(len(v)):  # the walker's state is array("i"): no slice assignment from a list
        a[j] = v[j]


for n in range(CASES):
    # The ramp near and far from its command (each axis reaches it, or steps by its limit).
    for k in range(3):
        top = walk.YAW_RATE_MAX if k == 2 else walk.SPEED_MAX
        w.cmd[k] = draw(15) % (2 * top + 1) - top if n % 5 else 0
        w.vel[k] = w.cmd[k] + (draw(8) % 301 - 150 if n % 3 else 0) if n % 7 else 0
        # The ramp heads for goal: the command, or less of it while a gait change settles.
        w.goal[k] = w.cmd[k] * (1000 if n % 3 else draw(10) % 1001) // 1000
    w.state = (walk.STARTING, walk.WALKING, walk.STOPPING)[draw(2) % 3]
    w.pending = draw(3) == 0
    w.clock.set(draw(2) % 4, 500 + draw(12) % 4000)  # the gaits' start phases, their stance and swing ticks
    w.phase = w.clock.start[draw(3) % 6] if n % 2 else draw(8) % w.clock.cycle_ticks  # often a leg's start
    for i in range(6):
        w.su[i] = -1 if draw(1) else draw(4)
        w.fx[i] = w.nx[i] if draw(2) == 0 else w.nx[i] + 16
        w.fy[i] = w.ny[i]
        w.done[i] = draw(1)
    if n % 4 == 0:
        w._aim_key[0] = w.cmd[0]  # the same command as the last tick, or another
        w._aim_key[1] = w.cmd[1]
        w._aim_key[2] = w.cmd[2]
        w._aim_key[3] = w.clock.stance_ticks
    if PLAIN:
        key = list(w._aim_key)
        before = state()  # the plain side's counters, the VM's rewind
        w._ramp()
        v = w.vel
        s1 = not (v[0] or v[1] or v[2])
        w._lift_all(s1)
        w._aim_swings()
        plain = state() + [s1]
        still += s1
        lifted += plain[1] != before[1]
        made += plain[6] != key
    if BOTH:
        for f, v in zip(FIELDS, before):
            put(getattr(w, f), v)
    if VIPER:
        r = begin(w)
        s2 = r & 1
        if r > 1:
            w._lift_due(r, s2)
        aim(w)
        fast = state() + [bool(s2)]
    # The pose check: settled or one value off.
    for k in range(9):
        b.pose[k] = b.target[k] = draw(10) % 401 - 200
    if n % 2:
        k = draw(4) % 9
        b.pose[k] += 1 if draw(1) else -1
    if PLAIN:
        plain.append(bool(b.settled()))
        level += b.settled()
    if VIPER:
        fast.append(bool(settled(b)))
    tally(n, plain, fast, before)
print((count, still, lifted, made, level, differ, h))
"""
)


def check_starts(result, cases):
    count, still, lifted, made, level, differ = result
    assert count == cases and cases // 20 < still < cases // 2 and lifted > cases // 20, result
    assert cases // 10 < made < cases - cases // 10 and cases // 3 < level < cases - cases // 3, result
    assert differ == 0, result


def check_stances(result, cases):
    count, held, banded, differ = result
    assert count == cases and cases // 10 < held < cases - cases // 10, result
    assert cases // 20 < banded < cases // 2 - cases // 20, result  # the ease band alone holds some, not all
    assert differ == 0, result


def check_swings(result, cases):
    count, clamped, landed, done, short, differ = result
    assert count == cases and clamped > cases // 10 and landed > cases // 50 and done > cases // 100, result
    assert cases // 10 < short < cases - cases // 10, result  # the budget moves some touch-downs, not all
    assert differ == 0, result


def check(result, cases):
    count, taken, limit_held, range_held, edge_taken, edge_held, differ = result
    assert count == cases
    # Every branch is exercised: frames taken (some at a range's very end), held for a joint
    # limit, held for a pulse range (some 1 us past an end).
    assert taken > cases // 5 and limit_held > cases // 50 and range_held > cases // 20, result
    assert edge_taken > cases // 20 and edge_held > cases // 50, result
    assert differ == 0, result


# Each viper path against its plain code: the script, its checks, the cases on the host VM and on
# the emulated Pico.
PATHS = {
    "frame": (CASES, check, 4000, 1000),
    "swings": (SWINGS, check_swings, 20000, 2000),
    "stance": (STANCES, check_stances, 10000, 1000),
    "move": (MOVES, check_moves, 10000, 1000),
    "ramp_lift_aim_pose": (STARTS, check_starts, 10000, 1000),
}


def source(path, cases, side):
    return "CASES = %d\nSIDE = %r\n" % (cases, side) + PATHS[path][0]


@pytest.mark.parametrize("path", sorted(PATHS))
def test_viper_path_equals_plain_code_on_the_vm(mp, path):
    _, checks, cases, _ = PATHS[path]
    checks(mp.value(source(path, cases, "both"))[:-1], cases)


def test_robot_on_the_vm_uses_the_viper_frame_swing_and_stance(mp):
    src = (
        "from hexapod import tick, walk as w\n"
        "print((tick._output_fast, tick._settled_fast, w._swings_fast, w._move_fast, w._begin_fast, w._aim_fast))"
    )
    assert "None" not in mp.run(src)


@pytest.mark.skipif(pico.missing() is not None, reason=pico.missing() or "")
@pytest.mark.parametrize("path", sorted(PATHS))
def test_viper_paths_equal_plain_code_on_the_emulated_pico(mp, path):
    # 1,000 frames (6,000 leg solves, 18,000 pulses), 2,000 swings, 1,000 stances, moves and starts:
    # the viper twins (Thumb code) on the Pico, their plain code on the host VM (the same on every
    # MicroPython VM), the digests of their results equal. One path a test (a boot each, as before
    # in one test): the two test workers share the five.
    _, checks, _, cases = PATHS[path]
    with pico.flashed(extra=on_board("_lcg_viper.py", "digest.py", "lcg.py")) as fs:
        status, out, err, _ = pico.run_source(source(path, cases, "viper"), fs=fs, timeout=600)
    assert status == 0, (path, out + err)
    board = ast.literal_eval(out.strip().splitlines()[-1])
    plain = mp.value(source(path, cases, "plain"))
    checks(plain[:-1], cases)
    assert board[0] == cases and board[-1] == plain[-1], (path, board, plain)
