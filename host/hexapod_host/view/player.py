"""Steps a source in real time (or faster) in the background and keeps its latest snapshot for
the pages to draw; the page's buttons call start, pause, step and set_speed."""

import asyncio
import math
import sys
import time
import traceback
from collections import deque
from itertools import islice

UPDATE_S = 0.04  # the background task publishes a snapshot this often: 25 updates a second
SPEEDS = (0.25, 0.5, 1.0, 2.0, 4.0, 8.0)  # simulated seconds per real second
MAX_FRAMES = 100  # frames one update may step: a slow machine falls behind instead of freezing the page
PLOT_S = 20.0  # the plots keep this many seconds of updates (20 s of the source at 1x, 160 s at 8x)
TRAIL_MM = 5.0  # a new trail point once the body is this far from the last one
SPEED_S = 0.5  # the body's speed is its travel over this much of the source's time
RATE_S = 1.0  # the frame rate is the frames counted over this much of the host's time
COUNTERS = ("overruns", "held", "bus_failed", "sonar_faults")
# One history row per snapshot published (None where the source has no such value: the page shows
# "-"): time s; the followed side's front and rear readings, the set point, the PID's error (mm) and
# output (deg/s); the walk asked (mm/s, the telemetry's vx vy) and the body's own speed (mm/s, a
# source with a room); the battery (V); the source's frames per second of the host's clock; the
# firmware's frame time, the last frame's and the worst since the line before (us, a board's
# telemetry); the loop's counters.
COLUMNS = (
    "time_s",
    "front_mm",
    "rear_mm",
    "setpoint_mm",
    "error_mm",
    "output_dps",
    "asked_mm_s",
    "body_mm_s",
    "battery_v",
    "frames_per_s",
    "frame_us",
    "frame_us_max",
) + COUNTERS


class Player:
    """One source, stepped by run() (an asyncio task) at `speed` while running."""

    def __init__(self, source, speed=1.0, running=True, recorder=None, clock=time.monotonic):
        self.source = source
        self.recorder = recorder  # record.Recorder: every snapshot published goes into it
        self.listeners = []  # called after each snapshot published (the tabs' redraws)
        self.described = source.describe()
        self.speed = self._checked(speed)
        self.running = running
        self.updates = 0  # snapshots published
        self.frames = 0  # frames stepped
        self.history = deque(maxlen=int(PLOT_S / UPDATE_S))
        # The tabs' plots take only the rows added since their last look (new_rows): rows counts
        # every row ever added, epoch every time the history starts over.
        self.rows = 0
        self.epoch = 0
        self.trail = []
        self.clock = clock  # the host's clock (s), for the frame rate; tests give their own
        self._moves = deque()  # (time_s, x, y) of the body over the last SPEED_S
        self._frames = deque()  # (host s, frame) over the last RATE_S
        self._due = 0.0  # frames owed to real time, fractional
        self._stopped = False
        self.publish()

    @staticmethod
    def _checked(speed):
        if speed not in SPEEDS:
            raise ValueError("speed: %r, allowed %s" % (speed, ", ".join("%g" % s for s in SPEEDS)))
        return float(speed)

    def set_speed(self, speed):
        self.speed = self._checked(speed)

    def start(self):
        """Run on; a finished trial gives way to the next one."""
        if self.done():
            self.source.restart()
            self._start_over()
        self.running = True

    def pause(self):
        self.running = False

    def step(self):
        """One frame, while paused (a finished trial stays finished)."""
        if not self.running and self.source.steppable and not self.done():
            self._frame()
            self.publish()

    def done(self):
        return self.source.done()

    def seek(self, seconds):
        """Jump to `seconds` into a source that can (a replay); the trail and plots start over."""
        self.source.seek(seconds)
        self._start_over()

    def _start_over(self):
        """A new trial or a jump: the trail, the plots and the rates begin again."""
        self.trail, self._due = [], 0.0
        self.history.clear()
        self.epoch += 1
        self._moves.clear()
        self._frames.clear()
        self.publish()

    def _frame(self):
        self.source.step()
        self.frames += 1

    def advance(self, dt):
        """Step the frames dt seconds of real time owe at the current speed, then publish."""
        if self.running and not self.done():
            self._due = min(self._due + dt * self.speed / self.source.frame_s, MAX_FRAMES)
            while self._due >= 1.0 and not self.done():
                self._frame()
                self._due -= 1.0
            if self.done():
                self.running = False
        self.publish()

    def publish(self):
        self.snap = s = self.source.snapshot()
        self.updates += 1
        if self.recorder is not None:
            self.recorder.write(s)
        self._tell()
        b = s["body"]
        if not self.trail or abs(b["x"] - self.trail[-1][0]) + abs(b["y"] - self.trail[-1][1]) > TRAIL_MM:
            self.trail.append((b["x"], b["y"]))
        f = s["follow"]
        front, rear = (1, 2) if f["side"] != "right" else (3, 4)
        x = s.get("extra", {})
        walk, mv = x.get("walk"), x.get("battery_mv")
        counters = s.get("counters", {})
        self.history.append(
            (
                s["time_s"],
                s["distances"][front],
                s["distances"][rear],
                f["setpoint_mm"] if f["mode"] != "off" else None,
                f["error_mm"],
                f["output_dps"],
                None if walk is None else round(math.hypot(walk[0], walk[1]), 1),
                # a room, or a board's dead reckoning (board.py); an older board recording has neither
                self._body_speed(s) if "walls" in self.described or "odometry" in self.described else None,
                None if mv is None else mv / 1000,
                self._frame_rate(s["frame"]),
                x.get("frame_us"),
                x.get("frame_us_max"),
                *(counters.get(k) for k in COUNTERS),
            )
        )
        self.rows += 1

    def new_rows(self, seen):
        """What a plot that has seen `seen` (this function's last mark, None for nothing yet) lacks:
        (fresh, rows, mark). fresh: start over with rows (a new tab, the history started over, or
        more rows added than the history keeps); otherwise rows are the ones added since, oldest
        first (none when nothing was added). mark: what to pass next time."""
        mark = (self.epoch, self.rows)
        h = self.history
        if seen is None or seen[0] != self.epoch or self.rows - seen[1] > len(h):
            return True, list(h), mark
        n = self.rows - seen[1]
        return False, list(islice(h, len(h) - n, len(h))), mark

    def _body_speed(self, s):
        """The body's travel (mm) over the last SPEED_S of the source's time, per second; None
        until it has some time to measure over."""
        b, t = s["body"], s["time_s"]
        moves = self._moves
        if moves and t < moves[-1][0]:  # the source's clock went back (a new trial)
            moves.clear()
        if not moves or t > moves[-1][0]:  # paused: the same time again, nothing new to measure
            moves.append((t, b["x"], b["y"]))
        while len(moves) > 2 and t - moves[1][0] >= SPEED_S:
            moves.popleft()
        t0, x0, y0 = moves[0]
        t1, x1, y1 = moves[-1]
        return round(math.hypot(x1 - x0, y1 - y0) / (t1 - t0), 1) if t1 > t0 else None

    def _frame_rate(self, frame):
        """The source's frames per second of the host's clock over the last RATE_S (the emulated
        Pico runs slower than real time; the simulator at its speed); None until measurable."""
        now, frames = self.clock(), self._frames
        if frames and frame < frames[-1][1]:
            frames.clear()
        frames.append((now, frame))
        while len(frames) > 2 and now - frames[1][0] >= RATE_S:
            frames.popleft()
        h0, f0 = frames[0]
        return round((frame - f0) / (now - h0), 1) if now > h0 else None

    def _tell(self):
        """Each listener once; one that raises is dropped (a broken tab must not stop the source)."""
        for fn in list(self.listeners):
            try:
                fn()
            except Exception:
                traceback.print_exc()
                sys.stderr.write("hexapod view: a page stopped following the player after the error above\n")
                self.listeners.remove(fn)

    async def run(self):
        """The background task: advance by the real time elapsed, UPDATE_S apart, until stop()."""
        last = due = time.monotonic()
        while not self._stopped:
            due += UPDATE_S  # on a fixed beat: the work of an update does not stretch the period
            await asyncio.sleep(max(0.0, due - time.monotonic()))
            now = time.monotonic()
            due = max(due, now - UPDATE_S)  # after a stall, no burst of catch-up updates
            self.advance(now - last)
            last = now

    def stop(self):
        self._stopped = True
        try:
            self.source.close()
        finally:
            if self.recorder is not None:
                self.recorder.close()
