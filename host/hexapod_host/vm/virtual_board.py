# Runs inside the MicroPython VM: the board's loop (main.build on the stub machine with the
# PCA9685 and HC-SR04 models) with the serial console on stdin/stdout, paced to real time.
# `hexapod virtual-board` starts it on a pseudo-terminal. Arguments: board name, robot name,
# calibration directory ('' = no calibration file), frames to run (-1 = for ever), trace file
# ('' = none; see Trace below), the room's pipes ('R,W': file descriptors; absent or '' = no room),
# and the pacing (absent or '' = real time; 'eager': a line waiting on the console starts the next
# frame at once; see serve).
#
# The room (`--world`, hexapod_host.wall.board_room on the host): before each frame the sonar
# models take their five distances from pipe R (0.1 mm, 0 = nothing heard; the wall simulator's
# rig.set_distances), after it the 18 pulses the core sent go out on pipe W (the rig's Tee), one
# line each; the host moves the body by its feet and casts the beams. Without a room the sonars
# answer fixed distances.
#
# Virtual time drives the models (sonar echoes, the PCA9685's clock); after each frame the
# script sleeps until the real clock has caught up with the virtual one, so a client sees a
# 50 Hz board. One command beyond the firmware's: `model` answers the PCA9685 models' pulse
# widths (us, chip 0x40 channels 0-15 then 0x41), for tests and the curious; and `fault unplug
# 0x41` / `fault no_echo K`, which break a model for `selftest` and `hexapod doctor` to find.
#
# Ctrl-C (0x03) does what it does on a MicroPython board: the board's USB/UART takes it as
# KeyboardInterrupt in the running code (it never reaches sys.stdin), main.py's loop leaves with
# the servos relaxed (or held: the board file's on_exit), prints its `stopped:` line, and the
# board sits at the REPL. Here a small REPL follows: `runner.run()` resumes the loop, Ctrl-D is a
# soft reboot (the loop again, relaxed), any other line is run as Python with `runner` at hand.
import os
import sys
import time

import _stub_clock as clock
import console
import main
import stub_board

BOARD = sys.argv[1] if len(sys.argv) > 1 else "pico"
ROBOT = sys.argv[2] if len(sys.argv) > 2 else "default"
CAL_DIR = sys.argv[3] if len(sys.argv) > 3 else ""
FRAMES = int(sys.argv[4]) if len(sys.argv) > 4 else -1
TRACE = sys.argv[5] if len(sys.argv) > 5 else ""
ROOM = sys.argv[6] if len(sys.argv) > 6 else ""
EAGER = len(sys.argv) > 7 and sys.argv[7] == "eager"

board = stub_board.reset(BOARD)
bus, models = stub_board.pca9685_models(board)
chips = [models[a] for a in sorted(models)]  # the model command: 0x40 first
# Walls 30-70 cm away, one per sensor, so `sonar` has something to show.
sonars = stub_board.sonar_models(board, [3000 + 1000 * k for k in range(5)])

r = main.build(BOARD, ROBOT, clock=clock)
room_in = room_out = tee = None
if ROOM:
    import rig  # the wall simulator's firmware side (host/hexapod_host/wall, on MICROPYPATH)

    fd_in, fd_out = ROOM.split(",")
    # Open for the VM's life. Unbuffered on the unix port (and its flush fsyncs: EINVAL on a pipe).
    room_in = open("/dev/fd/" + fd_in)  # noqa: SIM115
    room_out = open("/dev/fd/" + fd_out, "w")  # noqa: SIM115
    tee = rig.Tee(r.bank)
    r.robot.frame = tee
if CAL_DIR:
    os.chdir(CAL_DIR)


class InterruptReader:
    """The board's stdin as MicroPython's USB CDC serves it: 0x03 raises KeyboardInterrupt."""

    def __init__(self, reader):
        self.reader = reader

    def read_byte(self):
        b = self.reader.read_byte()
        if b == 3:
            raise KeyboardInterrupt
        return b


stdin = console.PollReader()
con = console.start(
    r,
    InterruptReader(stdin),
    os if CAL_DIR else None,
    walk_timeout_ms=board.get("walk_timeout_ms") or 1000,
    write=sys.stdout.write,
)
r.power_up(board, con.cal_source == "file")  # as main.main: relaxed unless calibrated and "boot": "stand"


def model(args):
    parts = ["ok model"]
    for m in chips:
        parts.append("0x%02x" % m.address)
        for ch in range(16):
            parts.append(str(m.pulse_us(ch)))
    return " ".join(parts)


def fault(args):
    # `fault unplug 0x41` takes a chip off the bus (as if unplugged or unpowered); `fault no_echo K`
    # makes sonar K (0..4, drivers.hcsr04 order) hear nothing: for `hexapod doctor`'s tests.
    if len(args) == 2 and args[0] == "unplug" and args[1] in ("0x40", "0x41"):
        bus.detach(int(args[1], 16))
        return "ok fault unplug " + args[1]
    if len(args) == 2 and args[0] == "no_echo" and args[1] in ("0", "1", "2", "3", "4"):
        sonars[int(args[1])].missing_echo = True
        return "ok fault no_echo " + args[1]
    raise ValueError("need unplug 0x40|0x41 or no_echo 0..4")


con._table["model"] = model
con._table["fault"] = fault


class Trace:
    """What the board saw, in its own frames, for tests and benches that must not count in wall
    time (`hexapod view`'s drive tests, `hexapod bench view`). One line per event, flushed:

        L FRAME T_NS WORDS...      a console line arrived (its words, the tag included)
        P FRAME T_NS K=US...       the PCA9685 models' pulse widths differ from the last frame's:
                                   each channel K that changed (0x40's 0-15, then 0x41's) and
                                   its new width (us, the model command's numbers)
        M FRAME T_NS MODE VX VY WZ the robot's mode or the walk it was asked for changed
                                   (tick.MODE_NAMES index; 0.1 mm/s, 0.1 mm/s, cdeg/s)
        F FRAME T_NS               every 50th frame: a reader waiting for frames to pass sees them

    FRAME is runner.frames when it happened (a line is read after the frame's step: the walk it
    asks for moves the servos from the next frame on); T_NS the host's clock (time.time_ns())."""

    def __init__(self, path):
        self.f = open(path, "w")  # noqa: SIM115 (open for the VM's life: closed with it)
        self.pulses = None
        self.state = None
        dispatch = con._dispatch

        def traced(words, tag):
            self.say("L", " ".join(words))
            return dispatch(words, tag)

        con._dispatch = traced  # an instance attribute: the console's own calls come here first

    def say(self, kind, text=""):
        self.f.write("%s %d %d %s\n" % (kind, r.frames, time.time_ns(), text))
        self.f.flush()

    def frame(self):
        pulses = [m.pulse_us(ch) for m in chips for ch in range(16)]
        if self.pulses is not None and pulses != self.pulses:
            old = self.pulses
            changed = ["%d=%d" % (k, p) for k, p in enumerate(pulses) if p != old[k]]
            self.say("P", " ".join(changed))
        self.pulses = pulses
        rb = r.robot
        state = (rb.mode, rb.asked_vx, rb.asked_vy, rb.asked_yaw)
        if state != self.state:
            self.say("M", "%d %d %d %d" % state)
        self.state = state
        if r.frames % 50 == 0:
            self.say("F")


trace = Trace(TRACE) if TRACE else None
print("virtual board %s (robot %s) ready: 50 Hz, console on this line; 'help' lists commands" % (BOARD, ROBOT))


def serve(frames):
    """Frames paced to real time until frames ran (-1: for ever) or Ctrl-C; returns the frames run.
    EAGER: while a frame waits for the real clock, a byte on the console ends the wait (the
    frame after it reads the line), and the pacing starts again from there (no catching up)."""
    t0 = time.ticks_ms()
    v0 = clock.ticks_ms()
    n = 0
    if EAGER:
        import select

        woken = select.poll()
        woken.register(sys.stdin, select.POLLIN)
    try:
        while frames < 0 or n < frames:
            if room_in is not None:
                line = room_in.readline()
                if not line:  # the host's room is gone: so is the host
                    sys.exit(1)
                rig.set_distances(sonars, [int(v) for v in line.split()])
            r.step()
            con.poll()
            if trace is not None:
                trace.frame()
            r.wait()
            if room_out is not None:
                room_out.write(" ".join([str(p) for p in tee.pulses]) + "\n")
            n += 1
            ahead = clock.ticks_diff(clock.ticks_ms(), v0) - time.ticks_diff(time.ticks_ms(), t0)
            if ahead > 0:
                if EAGER and woken.poll(ahead):
                    t0 = time.ticks_ms()
                    v0 = clock.ticks_ms()
                else:
                    time.sleep_ms(ahead)
    except KeyboardInterrupt:
        hold = board.get("on_exit") == "hold"
        r.leave(hold)  # as runner.serve on a board
        print("stopped: servos %s; runner.run() resumes" % ("held" if hold else "relaxed"))
        return -1
    return n


def repl():
    """The board at its REPL, until `runner.run()` or Ctrl-D."""
    print("MicroPython (virtual board); runner.run() resumes the loop, Ctrl-D soft reboots")
    scope = {"runner": r, "console": con}
    line = bytearray()
    while True:
        sys.stdout.write(">>> ")
        line[:] = b""
        while True:
            b = stdin.read_byte()
            if b < 0:
                time.sleep_ms(5)
                continue
            if b == 4:  # soft reboot: main.py again, the robot relaxed
                print("\r\nMPY: soft reboot")
                r.robot.go_limp()
                return
            if b == 3:
                line[:] = b""
                sys.stdout.write("\r\nKeyboardInterrupt\r\n>>> ")
            elif b in (10, 13):
                break
            elif 32 <= b < 127:
                line.append(b)
        sys.stdout.write("\r\n")
        text = bytes(line).decode().strip()
        if text == "runner.run()":
            return
        if not text:
            continue
        try:
            try:
                value = eval(text, scope)
                if value is not None:
                    print(repr(value))
            except SyntaxError:
                exec(text, scope)
        except Exception as e:  # as the REPL: the error printed, the prompt back
            print("%s: %s" % (type(e).__name__, e))


while serve(FRAMES) < 0:
    repl()
