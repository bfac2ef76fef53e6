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
# Arguments: [frames (default 500)].
import gc
import json
import sys
from array import array

try:
    import _stub_clock as clock  # the host's stub machine
except ImportError:
    import time as clock

import main
import runner

FRAMES = int(sys.argv[1]) if len(sys.argv) > 1 else 500
# (frame, vx 0.1 mm/s, vy, yaw cdeg/s); None: stop. Frame 0 stands up.
COMMANDS = ((60, 1200, 0, 0), (160, 0, 0, 3000), (230, 600, 600, 0), (300, -800, 0, 0), (400, None, 0, 0))
BUSY = array("i", [0] * FRAMES)  # us from a frame's start to the end of its step
START = array("i", [0] * FRAMES)  # us from the first frame's start
LATE = array("i", [0])  # frames begun a whole period after the last with the background sender still busy
COMMAND_US = array("i", [0] * len(COMMANDS))  # each command's time (Robot.walk/stop) after its frame's step, us


def loop(r, frames):
    bg = getattr(r.bank, "_sender", None)
    k = 0
    t_first = clock.ticks_us()
    for n in range(frames):
        t0 = clock.ticks_us()
        # (a frame begun at once after an overrun may find the last bursts still going out)
        if bg is not None and bg._st[3] and n and clock.ticks_diff(t0, t_first) - START[n - 1] >= 19990:
            LATE[0] += 1
        r.step()
        BUSY[n] = clock.ticks_diff(clock.ticks_us(), t0)
        START[n] = clock.ticks_diff(t0, t_first)
        if k < len(COMMANDS) and COMMANDS[k][0] == n:
            # after the step, in the frame's slack, where Runner.run polls the console
            c = COMMANDS[k]
            if c[1] is None:
                r.robot.stop()
            else:
                r.robot.walk(c[1], c[2], c[3])
            COMMAND_US[k] = clock.ticks_diff(clock.ticks_us(), t0) - BUSY[n]
            k += 1
        r.wait()


def summary(free_after_boot, heap, bg=None):
    busy = sorted(BUSY)
    gaps = sorted(START[n + 1] - START[n] for n in range(FRAMES - 1))
    return {
        "frames": FRAMES,
        "frame_median_us": busy[FRAMES // 2],
        "frame_max_us": busy[-1],
        "frame_p99_us": busy[(FRAMES * 99) // 100],
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
    }


r = main.build(clock=clock)
r.robot.set_gait(0)
r.robot.stand_up()
gc.collect()
free = gc.mem_free() if hasattr(gc, "mem_free") else 0
# The collector stays off: a collection inside a frame would count as the frame's time, and any
# byte a frame allocates shows. gc.mem_alloc() walks the whole heap (16 ms on the Pico), so it
# runs only before and after the loop; the status line is printed after it for the same reason.
weigh = hasattr(gc, "mem_alloc")
gc.disable()
before = gc.mem_alloc() if weigh else 0
loop(r, FRAMES)
heap = (gc.mem_alloc() - before) / FRAMES if weigh else -1
gc.enable()
print(runner.status_line(r))
print(json.dumps(summary(free, heap, getattr(r.bank, "_sender", None))))
