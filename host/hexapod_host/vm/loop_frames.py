# The whole loop as main.py builds it (main.build: board file, PCA9685 driver, HC-SR04 driver,
# Runner), on the emulated Pico with its emulated chips, or on the host's stub machine (the caller
# sets the stubs up first and has `_stub_clock` on the path). Stands up, walks a tripod through
# forward, turn, crab and back, and stops; one Runner.step + Runner.wait per 20 ms frame, as
# Runner.run. Prints main.py's status line at the end, then one JSON line: the frame's time
# (ping, follower, tick, both bursts) in us, the period (and how many of the gaps between frame
# starts lie within 10 and 100 us of 20 ms), the slack, the heap; with the Pico's background I2C
# sender (drivers/_i2c_rp2.py) its counts and how many frames began a whole period after the last
# with its bursts still on the bus. The script's walk commands run after their frame's step, in the
# slack where Runner.run polls the console; their own time is `commands_us`.
# The "drive" scenario drives as a person with a joystick would: a walk command five times a
# second (ramps, reversals, crabbing, turning), gait changes while walking, stops, and height and
# pose changes while standing, all asked as the console asks them (wait=False: checked over the
# frames' slack); its frame time counts the commands made in that frame, and it also reports each
# configure's frames (asked to done) and codes.
# The "stream" scenario is the default one with the console's telemetry on at 25 Hz (`stream on 25`,
# docs/console.md): Console.poll after each step writes a line every second frame, counted in the
# frame's time; on the board through select.poll on its USB CDC (stream.PollWriter), on the host
# straight to stdout.
# Arguments: [frames (default 500)] [scenario: default, drive or stream].
import gc
import json
import sys
from array import array

try:
    import _stub_clock as clock  # the host's stub machine
except ImportError:
    import time as clock

FRAMES = int(sys.argv[1]) if len(sys.argv) > 1 else 500
SCENARIO = sys.argv[2] if len(sys.argv) > 2 else "default"
# The per-frame records first, while the heap is in one piece (made after the imports, 2,000
# frames' 8 KB blocks found no room on the emulated Pico: MemoryError); no list made on the way.
BUSY = array("i", bytes(4 * FRAMES))  # us from a frame's start to the end of its step
START = array("i", bytes(4 * FRAMES))  # us from the first frame's start
GAPS = array("i", bytes(4 * (FRAMES - 1)))  # the periods, for the summary

import main  # noqa: E402
import runner  # noqa: E402

import hexapod  # noqa: E402

if SCENARIO == "stream":
    # The console's modules before the loop is built, while the heap has blocks big enough for
    # their code (imported after main.build they found none on the emulated Pico: MemoryError).
    import console

    from drivers import stream
# (frame, vx 0.1 mm/s, vy, yaw cdeg/s); None: stop. Frame 0 stands up.
COMMANDS = ((60, 1200, 0, 0), (160, 0, 0, 3000), (230, 600, 600, 0), (300, -800, 0, 0), (400, None, 0, 0))
LATE = array("i", [0])  # frames begun a whole period after the last with the background sender still busy
COMMAND_US = array("i", [0] * len(COMMANDS))  # each command's time (Robot.walk/stop) after its frame's step, us
# drive: (frame, what, args); "walk" (vx, vy, yaw), "stop", "gait" (gait), "height" (0.1 mm),
# "pose" (roll, pitch cdeg). The walks come every 10 frames while walking.
JOY = ((1200, 0, 0), (1500, 0, 1500), (600, 600, 0), (0, 1200, 0), (-800, 0, 0), (0, 0, 3000), (900, -400, -1000))
DRIVE = (
    (110, "gait", (2, 0)),  # ripple while walking (its own cycle: from the guard table)
    (200, "gait", (0, 0)),  # back to the tripod
    (300, "gait", (0, 1200)),  # the tripod at 1.2 s: not in the table, checked over ~1,100 frames
    (440, "stop", 0),
    (600, "pose", (300, 0)),  # asked while that is still being checked: refused
    (1750, "height", 700),  # checked over ~2,000 frames, standing
    (1850, "gait", (1, 0)),  # asked meanwhile: refused
)
JOB = array("i", [0, 0])  # frames begun with a configure under way, the longest of them (us)
PENDING = [-1, 0]  # the drive's configure awaited: its DRIVE_LOG row, its frame (made here: the loop is weighed)
DRIVE_LOG = []  # (frame, what, code at once, frames until done, job code)


def drive(robot, n, pending):
    """The drive scenario's commands for frame n (after the step, as the console's); True when it
    made one (Runner.run then leaves a walking configure's step for the next frame)."""
    made = False
    if pending[0] >= 0 and not robot.configuring():
        DRIVE_LOG[pending[0]][3] = n - pending[1]
        DRIVE_LOG[pending[0]][4] = robot.job_code
        pending[0] = -1
    if 60 <= n < 440 and n % 10 == 0:
        c = JOY[(n // 10) % len(JOY)]
        robot.walk(c[0], c[1], c[2])
        made = True
    for f, what, arg in DRIVE:
        if f != n:
            continue
        made = True
        if what == "stop":
            code = robot.stop()
        elif what == "gait":
            code = robot.set_gait(arg[0], arg[1] or None, wait=False)
        elif what == "height":
            code = robot.set_height(arg, wait=False)
        else:
            code = robot.set_pose(roll=arg[0], pitch=arg[1], wait=False)
        DRIVE_LOG.append([n, what, code, -1, -1])
        if code == 0 and what != "stop" and robot.configuring():
            pending[0] = len(DRIVE_LOG) - 1
            pending[1] = n
    return made


def streaming(r):
    """The stream scenario's console (no reader) streaming at 25 Hz; its reply printed. The
    boot-only modules go first, as main.main lets them go before its console comes."""
    hexapod.release(*hexapod.BOOT_ONLY, "robots." + main.ROBOT, "robots.%s_cal" % main.ROBOT)
    gc.collect()
    con = console.start(r, None, None, write=sys.stdout.write)
    if sys.implementation.name == "cpython":  # the host has no MicroPython stream.write(buf, n)

        class Out:
            def write(self, buf, n):
                sys.stdout.write(bytes(buf[:n]).decode())
                return n

        con.telemetry = stream.Stream(Out())
    print(con.do("stream on 25"))
    return con


def loop(r, frames, con=None):
    bg = getattr(r.bank, "_sender", None)
    k = 0
    pending = PENDING
    t_first = clock.ticks_us()
    driving = SCENARIO == "drive"
    r.next_us = t_first  # as Runner.run: the frames count from the loop's start
    robot = r.robot
    robot.defer = True  # as Runner.run: a walking configure's step after the frame's commands
    for n in range(frames):
        busy = r.robot._job is not None  # (read before the frame's clock starts: not the frame's time)
        t0 = clock.ticks_us()
        # (a frame begun at once after an overrun may find the last bursts still going out)
        if bg is not None and bg._st[3] and n and clock.ticks_diff(t0, t_first) - START[n - 1] >= 19990:
            LATE[0] += 1
        r.step()
        if con is not None:
            con.poll()  # the telemetry line, when this frame is due one
        made = driving and drive(robot, n, pending)
        if robot.owed:
            robot.pay(made)  # as Runner.run after its console's poll
        BUSY[n] = clock.ticks_diff(clock.ticks_us(), t0)
        if busy:
            JOB[0] += 1
            if BUSY[n] > JOB[1]:
                JOB[1] = BUSY[n]
        START[n] = clock.ticks_diff(t0, t_first)
        if not driving and k < len(COMMANDS) and COMMANDS[k][0] == n:
            # after the step, in the frame's slack, where Runner.run polls the console
            c = COMMANDS[k]
            if c[1] is None:
                r.robot.stop()
            else:
                r.robot.walk(c[1], c[2], c[3])
            COMMAND_US[k] = clock.ticks_diff(clock.ticks_us(), t0) - BUSY[n]
            k += 1
        r.wait()


def _sorted(a):
    """a (an array) sorted in place (Shell's gaps): a list of 1,600 frames would need one
    contiguous block the board's heap may no longer have after the loop."""
    gap = len(a) // 2
    while gap:
        for i in range(gap, len(a)):
            v = a[i]
            j = i
            while j >= gap and a[j - gap] > v:
                a[j] = a[j - gap]
                j -= gap
            a[j] = v
        gap = gap // 2 if gap > 2 else gap - 1
    return a


def summary(r, free_after_boot, heap, bg=None, con=None):
    worst_at = 0
    for n in range(FRAMES):
        if BUSY[n] > BUSY[worst_at]:
            worst_at = n
    over = [[n, BUSY[n]] for n in range(FRAMES) if BUSY[n] > 6000]  # issue 22's goal: none
    for n in range(FRAMES - 1):
        GAPS[n] = START[n + 1] - START[n]
    busy = _sorted(BUSY)
    gaps = _sorted(GAPS)
    return {
        "frames": FRAMES,
        "frame_median_us": busy[FRAMES // 2],
        "frame_max_us": busy[-1],
        "frame_max_at": worst_at,
        "frame_p99_us": busy[(FRAMES * 99) // 100],
        "frames_over_6ms": over,
        "period_min_us": gaps[0],
        "period_max_us": gaps[-1],
        "period_median_us": gaps[len(gaps) // 2],
        "period_p1_us": gaps[len(gaps) // 100],
        "period_p99_us": gaps[(len(gaps) * 99) // 100],
        "periods_within_10us": sum(1 for g in gaps if -10 <= g - 20000 <= 10),
        "periods_within_100us": sum(1 for g in gaps if -100 <= g - 20000 <= 100),
        "slack_min_us": 20000 - busy[-1],
        "slack_median_us": 20000 - busy[FRAMES // 2],
        "heap_free_after_boot": free_after_boot,
        "heap_bytes_per_frame": heap,
        "sender": list(bg.stats) if bg is not None else None,  # refills, writes done, NACKs
        "frames_begun_with_bus_busy": LATE[0],
        "commands_us": list(COMMAND_US),
        "scenario": SCENARIO,
        "drive": DRIVE_LOG if SCENARIO == "drive" else None,
        "job_steps": r.robot.job_steps,
        "configure_frames": JOB[0],
        "configure_frame_max_us": JOB[1],
        "overruns": r.robot.overruns,
        "stream_sent_dropped": [con.telemetry.sent, con.telemetry.dropped] if con is not None else None,
    }


r = main.build(clock=clock)
r.robot.set_gait(0)
r.robot.stand_up()
con = streaming(r) if SCENARIO == "stream" else None
gc.collect()
free = gc.mem_free() if hasattr(gc, "mem_free") else 0
# The collector stays off: a collection inside a frame would count as the frame's time, and any
# byte a frame allocates shows. gc.mem_alloc() walks the whole heap (16 ms on the Pico), so it
# runs only before and after the loop; the status line is printed after it for the same reason.
weigh = hasattr(gc, "mem_alloc")
gc.disable()
before = gc.mem_alloc() if weigh else 0
loop(r, FRAMES, con)
heap = (gc.mem_alloc() - before) / FRAMES if weigh else -1
gc.enable()
gc.collect()  # the summary's sorted copies need the heap the loop's commands left behind
print(runner.status_line(r))
print(json.dumps(summary(r, free, heap, getattr(r.bank, "_sender", None), con)))
