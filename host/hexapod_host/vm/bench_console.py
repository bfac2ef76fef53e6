# Runs inside the MicroPython VM: the cost of a console command frame. The pico board's loop is
# built on the stub machine (main.build), then its robot sends frames to a FrameBuffer so that
# only the board's own work is timed: Console.poll() taking a whole command line from the
# reader, parsing and running it and making the reply, then Robot.tick(). Also an idle frame
# (poll with nothing waiting + tick). One JSON line: per command the median and max us over
# REPEATS frames and the heap bytes one such frame allocates.
import gc
import json
import sys
import time
from array import array

import _stub_clock as clock
import _stub_i2c
import _stub_pins
import _stub_serial
import console
import main
from _stub_i2c import shared_bus
from pca9685_model import PCA9685Model

from hexapod import board as boards
from hexapod import tick

REPEATS = int(sys.argv[1]) if len(sys.argv) > 1 else 50
TIMES = array("i", bytes(4 * REPEATS))  # made first, while the heap is in one piece

clock.reset(0)
_stub_pins.reset()
_stub_i2c.reset()
bus = shared_bus(0)
bus.clock_us = clock.now_us
for c in boards.load("pico")["pca9685"]["chips"]:
    bus.attach(PCA9685Model(c["address"], osc_hz=c["osc_hz"]))
r = main.build(clock=clock)
r.robot.frame = tick.FrameBuffer()
reader = _stub_serial.BufferReader()
con = console.start(r, reader, None, out=lambda line, more=None: None)  # tagged: out(tag, line)

# (setup lines, timed line): the timed line runs REPEATS times from the same state.
CASES = (
    ((), ""),  # idle: nothing waiting
    ((), "get 2"),
    ((), "status"),
    (("foot 2 130 0 -80",), "foot 2 130 5 -80"),
    (("foot 2 130 0 -80",), "nudge 2 0.5 0 0"),
    (("foot 2 130 0 -80",), "joint 2 femur 10"),
    (("foot 2 130 0 -80",), "pulse 2 tibia 1500"),
    (("foot 2 130 0 -80",), "trim 2 femur 5"),
    ((), "foot 2 400 0 0"),
    ((), "sonar"),
    ((), "x" * 120),
    # Tagged requests (docs/console.md): the tag is a word the line's split makes anyway.
    ((), "#7 get 2"),
    ((), "#123456789 status"),
    (("foot 2 130 0 -80",), "#7 nudge 2 0.5 0 0"),
)


def frame(line_bytes, t):
    reader.data = line_bytes  # whole line waiting, as if it arrived since the last frame
    reader.pos = 0
    t0 = time.ticks_us()
    con.poll()
    r.robot.tick(t)
    return time.ticks_diff(time.ticks_us(), t0)


rows = []
t = 0
for setup, line in CASES:
    for s in setup:
        con.do(s)
    data = bytearray(line.encode() + b"\n") if line else bytearray()
    for k in range(REPEATS):
        t += 20
        TIMES[k] = frame(data, t)
    gc.collect()
    gc.disable()
    before = gc.mem_alloc()
    frame(data, t + 20)
    heap = gc.mem_alloc() - before
    gc.enable()
    times = sorted(TIMES)
    row = {"line": line[:24] or "(idle)", "median_us": times[REPEATS // 2], "max_us": times[-1]}
    row["heap_bytes"] = heap
    rows.append(row)
    times = None
    con.do("relax")
    r.robot.mode = tick.RELAXED
print(json.dumps({"repeats": REPEATS, "frames": rows}))
