"""Console transcripts for tests/test_console.py: replies, jogging, refusals, the line reader's
limits, walk expiry, backspace and echo, on the console bench (scenarios.console_rig)."""

import _stub_clock as clock
from scenarios.console_rig import Board

from hexapod import walk


def replies(lines, after_stand=0):
    """A fresh board's replies to lines (after_stand frames run after a `stand`), then its
    PCA9685 channels (us) and its unsafe servos: [replies, channels, unsafe]."""
    b = Board()
    out = []
    for line in lines:
        out.append(b.say(line))
        if line == "stand":
            b.frames(after_stand)
    return [out, b.channels(), b.unsafe()]


def wall_forms(lines, frames=60):
    """A fresh board, stood up (frames run after the stand), its left wall parallel at 125 mm: per
    line, its reply, the follower's form and the walk command it gives (vx, vy, yaw) after frames
    more frames."""
    b = Board()
    b.say("stand")
    b.frames(frames)
    for k in (1, 2):  # the left wall parallel, 5 mm beyond a 12 cm set point; nothing ahead
        b.sonar[k].set_distance(1250)
    b.sonar[0].set_distance(30000)
    out = []
    for line in lines:
        reply = b.say(line)
        b.frames(frames)
        f = b.r.follower
        rb = b.r.robot
        out.append([reply, f.form, [rb.asked_vx, rb.asked_vy, rb.asked_yaw]])
    return out


def refusals(jog, bad):
    """After `jog` and 3 frames, each bad line: [replies, lines after which the state
    (scenarios.rig.servo_state) was not as before, unsafe servos]."""
    b = Board()
    b.say(jog)
    b.frames(3)
    before = b.state()
    out = []
    changed = []
    for line in bad:
        out.append(b.say(line))
        if b.state() != before:
            changed.append(line)
    return [out, changed, b.unsafe()]


def reader_limits():
    """Line ends, an over-long line (64 bytes read a frame), non-text bytes, a 95-character line:
    [replies, [replies after one frame of the long line, replies], replies, first 30 characters]."""
    b = Board()
    out = [b.lines(b"get 1\r\nget 2\rget 3\n\n\r\n", 1)]
    b.reader.feed(b"x" * 96 + b"\nget 4\n")
    n = len(b.replies)
    b.frames(1)  # 64 bytes a frame: the long line is not over yet
    n1 = len(b.replies) - n
    b.frames(2)
    out.append([n1, b.replies[n:]])
    out.append(b.lines(b"get 1\xff\xfe\n\x00\x1b[A\nget\t5\n", 2))
    out.append(b.lines(b"x" * 95 + b"\n", 3)[0][:30])
    return out


def walk_expiry():
    """Stand, `walk 60 0 0`, renewed 30 frames in: [the walk's reply, [ms from the last walk
    line to the walker stopping]]."""
    b = Board()
    b.stand()
    reply = b.say("walk 60 0 0")
    t_walk = clock.ticks_ms()
    seen = []
    for k in range(100):
        if k == 30:
            b.say("walk 60 0 5")  # renewed 0.6 s in: a new 1 s
            t_walk = clock.ticks_ms()
        b.frame()
        state = b.robot.walker.state
        if state == walk.STOPPING or state == walk.STOPPED:
            seen.append(clock.ticks_diff(clock.ticks_ms(), t_walk))
            break
    return [reply, seen]


def idle_heap():
    """Heap bytes (VM) of 200 idle console polls and of 50 frames, after a jog."""
    from scenarios.heap import heap_bytes

    b = Board()
    b.say("foot 2 130 0 -80")
    con = b.con

    def idle(n):
        for _ in range(n):
            con.poll()

    return [heap_bytes(idle, 200), heap_bytes(b.frames, 50)]


def jog_one_leg(start):
    """From `start` ("relaxed" or "standing"), `foot 2 140 10 -70`: [its reply, [channels
    before, channels after, unsafe servos]]."""
    b = Board()
    if start == "standing":
        b.stand()
    b.frames(2)
    before = b.channels()
    reply = b.say("foot 2 140 10 -70")
    b.frames(2)
    return [reply, [before, b.channels(), b.unsafe()]]


def backspace_and_echo(chunks):
    """Each (bytes, frames) chunk fed with `echo` writing to a list: [[replies, raw echo], ...]."""
    b = Board()
    raw = []
    b.con.write = raw.append
    out = []
    for data, n in chunks:
        del b.replies[:]
        del raw[:]
        b.reader.feed(data)
        b.frames(n)
        out.append([list(b.replies), "".join(raw)])
    return out


def echo_words(lines):
    """Each line's reply on a console with no raw output; then `echo on off` with one: [replies,
    that reply, echo after it]."""
    b = Board()
    out = b.says(lines)
    b.con.write = print
    return [out, b.say("echo on off"), b.con.echo]


def wall_status(echo_mm10):
    """status, stand (120 frames), the two left sonars at echo_mm10 (None: no echo), `wall left
    12`, frames, status: [first status, stand, wall's reply, last status]."""
    b = Board()
    # `wall`'s modules loaded (no frame run): it runs in the frame it is read, not after its
    # modules' imports (a frame each, Console._waiting), so the sonars' phase is as it was.
    import console

    console.load(console.WALL)
    out = [b.say("status"), b.say("stand")] if echo_mm10 is None else [b.say("stand")]
    b.frames(120)
    for k in (1, 2):
        if echo_mm10 is None:
            b.sonar[k].missing_echo = True
        else:
            b.sonar[k].set_distance(echo_mm10)
    out.append(b.say("wall left 12"))
    b.frames(10 if echo_mm10 is None else 30)
    out.append(b.say("status"))
    return out


def _untagged(x):
    """A reply without its tag (a random '#12 ' starts a tagged request: its reply is '#12 ok ...')."""
    return x.split(" ", 1)[1] if x.startswith("#") and " " in x else x


def random_bytes(data):
    """data fed to the line reader, frames run until it is read, then 2 more; every frame's
    unsafe servos kept. Returns [frames ran, unsafe servos, replies neither ok nor err, replies
    naming an internal error, replies]."""
    b = Board()
    b.reader.feed(data)
    bad = []
    n0 = b.r.frames
    while b.reader.pos < len(data):
        b.frames(1)
        bad += b.unsafe()
    b.frames(2)
    odd = [x for x in map(_untagged, b.replies) if not (x == "ok" or x.startswith("ok ") or x.startswith("err "))]
    return [b.r.frames - n0 > 0, bad, odd, [x for x in b.replies if "internal" in x], len(b.replies)]


def status_imports():
    """[`status`'s reply starts "ok frames ", consoleparts.more loaded after it, after `help`]."""
    import sys

    b = Board()
    out = [b.say("status").startswith("ok frames ")]
    out.append("consoleparts.more" in sys.modules)
    b.say("help")
    out.append("consoleparts.more" in sys.modules)
    return out


# The modules the console loads on demand (console.BEFORE), in no particular order.
ON_DEMAND = (
    "consoleparts",
    "consoleparts.more",
    "consoleparts.setting",
    "consoleparts.wall",
    "consoleparts.sonar",
    "drivers._stream_viper",
    "drivers.stream",
    "calstore",
    "consoleparts.caledit",
    "consoleparts.calset",
    "hexapod.jog",
    "consoleparts.jog",
    "consoleparts.joint",
    "consolecal",
)


def deferred_imports(lines, frames=12):
    """Each of lines (bytes) fed on a fresh standing board, then `frames` frames: per frame, the
    on-demand modules it imported and the replies it sent, as [[names], [replies]] (frames with
    neither left out but counted: None in their place). The same lines' replies through do() on a
    second board that has every module loaded, and both boards' servo_state at the end."""
    import sys

    import console

    def run(b, data):
        out = []
        for _ in range(frames):
            before = [m for m in ON_DEMAND if m in sys.modules]
            n = len(b.replies)
            b.reader.feed(data)
            data = b""
            b.frame()
            new = [m for m in ON_DEMAND if m in sys.modules and m not in before]
            out.append([new, b.replies[n:]] if new or len(b.replies) > n else None)
        return out

    b = Board()
    b.stand()
    got = [run(b, data) for data in lines]
    state = b.state()
    c = Board()
    c.stand()
    for name in ON_DEMAND:
        console.load(name)
    direct = []
    for data in lines:
        direct += [c.con.do(line) for line in data.decode().split("\n") if line]
    return [got, direct, state == c.state()]
