# Runs inside the MicroPython VM: times Robot.tick() per gait while walking, turning and
# changing speed, and counts the heap bytes the ticks allocate; then the wall follower's frame
# (Follower.update + Robot.tick). Prints one JSON line per row.
# Arguments: [module dir to put first on sys.path (the .mpy build)] [ticks per gait] [repeats]
# [rows: "gaits" (default) or "wall": the follower's modules do not fit the 128 KB heap beside
# the gaits' run, so the wall-follow row is a run of its own] [histogram size, us (default 4000)].
#
# Each gait replays the same command sequence `repeats` times on a fresh robot. "raw" figures
# are the worst of every pass (host scheduler noise included); the per-tick figures keep,
# for each tick of the sequence, its fastest pass: what the code costs, without the noise.
import gc
import json
import sys
import time
from array import array

TICKS = int(sys.argv[2]) if len(sys.argv) > 2 else 10000
REPEATS = int(sys.argv[3]) if len(sys.argv) > 3 else 5
ROWS = sys.argv[4] if len(sys.argv) > 4 else "gaits"
# Longer ticks share the last bucket (the max is kept exactly); the emulated Pico passes 20000.
HIST_US = int(sys.argv[5]) if len(sys.argv) > 5 else 4000
# The two big buffers come first, while the heap is still in one piece.
BEST = bytearray(2 * TICKS)  # fastest pass of each tick, us, 16-bit little-endian
HIST = array("H", bytes(2 * HIST_US))  # tick durations, one bucket per microsecond

if len(sys.argv) > 1 and sys.argv[1]:
    sys.path.insert(0, sys.argv[1])

import robots.default as robot_file  # noqa: E402
from hexapod import geometry, tick  # noqa: E402
from hexapod.gait import NAMES  # noqa: E402

if ROWS == "wall":
    from hexapod import follow  # noqa: E402  (before the robot: the heap is tight)

# Commands cycled every 100 ticks: forward, crab, turn in place, arc, back (0.1 mm/s, cdeg/s).
COMMANDS = ((1200, 0, 0), (600, 600, 0), (0, 0, 3000), (900, -300, -1500), (-800, 200, 1000))
GEOMETRY = geometry.load(robot_file)


ROBOT = tick.Robot(GEOMETRY, tick.default_servos(GEOMETRY), tick.FrameBuffer())
FOLLOWER = []


def standing_robot(gait):
    """The one robot, stopped at its neutral stance: each pass replays from the same state."""
    robot = ROBOT
    if robot.mode == tick.STANDING:
        t = 0
    else:
        t = 20 * standing.stand(robot, lambda n: robot.tick(20 * n))
    robot.set_gait(gait)
    robot.walk(1200, 0, 0)
    for _ in range(200):  # warm up: every code path of the walk has run once
        robot.tick(t)
        t += 20
    return robot, t


def weighed(before):
    """Heap bytes allocated since gc.mem_alloc() read before; the collector back on."""
    heap = gc.mem_alloc() - before
    gc.enable()
    return heap


def settle(robot, t):
    """Tick the robot (20 ms apart from t) until it no longer walks: after a weighed pass."""
    while robot.mode == tick.WALKING:
        robot.tick(t)
        t += 20


def finish(robot, t, before, worst, fol=None):
    """A weighed pass's (heap bytes, worst raw us, faults); then the robot (or its follower fol)
    stopped and the robot settled."""
    heap = weighed(before)
    if fol is None:
        robot.stop()
    else:
        fol.off()
    settle(robot, t)
    return heap, worst, robot.faults


def timed(best, n, t0, first, worst):
    """keep_best for tick n begun at t0 (ticks_us); returns the larger of worst and its time."""
    d = keep_best(best, n, time.ticks_diff(time.ticks_us(), t0), first)
    return d if d > worst else worst


def keep_best(best, n, d, first):
    """Tick n's time d (us, clamped to 16 bits) kept in best if first or faster; returns the clamped d."""
    if d > 65535:
        d = 65535
    if first or d < best[2 * n] | best[2 * n + 1] << 8:
        best[2 * n] = d & 255  # 16-bit little-endian in a bytearray: no big temporary
        best[2 * n + 1] = d >> 8
    return d


def one_pass(gait, best, first):
    """One replay of the sequence; returns (heap bytes, worst raw us, faults)."""
    robot, t = standing_robot(gait)
    gc.collect()
    gc.disable()
    before = gc.mem_alloc()
    worst = 0
    k = 0
    for n in range(TICKS):
        if n % 100 == 0:
            c = COMMANDS[k]
            k = k + 1 if k + 1 < len(COMMANDS) else 0
            robot.walk(c[0], c[1], c[2])
        t0 = time.ticks_us()
        robot.tick(t)
        worst = timed(best, n, t0, first, worst)
        t += 20
    return finish(robot, t, before, worst)


def percentile(hist, count, num, den):
    """Smallest bucket (us) at or below which num/den of the count lies."""
    need = (count * num + den - 1) // den
    seen = 0
    for us in range(len(hist)):
        seen += hist[us]
        if seen >= need:
            return us
    return len(hist) - 1


def run_gait(gait, best, hist):
    heap = 0
    raw = 0
    faults = 0
    for r in range(REPEATS):
        h, w, f = one_pass(gait, best, r == 0)
        heap = h if h > heap else heap
        raw = w if w > raw else raw
        faults = f
    result = summary(best, hist, raw)
    result["gait"] = NAMES[gait]
    result["heap_bytes_per_tick"] = heap / TICKS
    result["faults"] = faults
    return result


def summary(best, hist, raw):
    """Median, p99 and max of the per-tick fastest passes, and the raw worst, in us."""
    for us in range(HIST_US):
        hist[us] = 0
    worst = 0
    for n in range(TICKS):
        d = best[2 * n] | best[2 * n + 1] << 8
        hist[d if d < HIST_US - 1 else HIST_US - 1] += 1
        worst = d if d > worst else worst
    median = percentile(hist, TICKS, 1, 2)
    return {
        "ticks": TICKS,
        "repeats": REPEATS,
        "median_us": median,
        "p99_us": percentile(hist, TICKS, 99, 100),
        "max_us": worst,
        "max_over_median": round(worst / median, 3),
        "raw_max_us": raw,
        "raw_max_over_median": round(raw / median, 3),
    }


# The wall-follow row: each frame the follower takes one sonar result (round robin, drivers.hcsr04
# order, 0.1 mm) from a wall that wobbles and an inside corner that comes and goes, runs its PID
# and commands the walk; then the tick. Timed and weighed together: the core's whole frame.
SLOTS = (0, 4, 1, 3, 2)
DIST = [-1] * 5
STATUS = [5] * 5


def sonar(n, k):
    """Sensor k's result at frame n into STATUS and DIST (written in place: nothing allocated)."""
    c = n // 5
    STATUS[k] = 0
    if k == 0 and c % 300 > 270:
        DIST[k] = 3900 + c % 30 * 10  # an inside corner now and then
    elif k == 1 or k == 2:  # noqa: SIM109 (a tuple test may allocate)
        DIST[k] = 800 + (c * 37) % 23 * 10 - 110 + (k - 1) * ((c // 13) % 5 - 2) * 20
    else:
        STATUS[k] = 1  # nothing in range
        DIST[k] = -1


def one_wall_pass(best, first):
    robot, t = standing_robot(0)
    fol = FOLLOWER[0]
    fol.follow("left", 800)
    for n in range(200):
        k = SLOTS[n % 5]
        sonar(n, k)
        fol.update(t, k, DIST, STATUS)
        robot.tick(t)
        t += 20
    gc.collect()
    gc.disable()
    before = gc.mem_alloc()
    worst = 0
    for n in range(TICKS):
        k = SLOTS[n % 5]
        sonar(n, k)
        t0 = time.ticks_us()
        fol.update(t, k, DIST, STATUS)
        robot.tick(t)
        worst = timed(best, n, t0, first, worst)
        t += 20
    return finish(robot, t, before, worst, fol)


def run_wall(best, hist):
    FOLLOWER.append(follow.Follower(ROBOT))
    heap = 0
    raw = 0
    for r in range(REPEATS):
        h, w, f = one_wall_pass(best, r == 0)
        heap = h if h > heap else heap
        raw = w if w > raw else raw
    result = summary(best, hist, raw)
    result["row"] = "wall-follow"
    result["heap_bytes_per_frame"] = heap / TICKS
    result["faults"] = f
    result["pid_updates"] = FOLLOWER[0].updates  # in the last pass
    return result


def main():
    # One JSON line per gait, printed as soon as it is measured: the robot, the core and the
    # two buffers fill most of a 128 KB heap, and one report for all gaits may not fit.
    if ROWS == "wall":
        print(json.dumps(run_wall(BEST, HIST)))
        return
    for gait in range(len(NAMES)):
        result = run_gait(gait, BEST, HIST)
        gc.collect()
        print(json.dumps(result))


# Imported last, after the core's code is loaded: imported first it moved that code on the emulated
# Pico and the figures with it (wall row median 2253 -> 2416 us at --ticks 100; here 2274), likely
# through MicroPython's map lookup cache, which is indexed by bytecode address.
import standing  # noqa: E402

main()
