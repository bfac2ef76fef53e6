"""The serial console: command lines read between 50 Hz frames, one reply line each.

docs/console.md is the protocol. Console.poll() runs once per frame (runner.Runner.run): it
takes the bytes waiting (at most MAX_BYTES a frame) into a preallocated line buffer and runs a
complete line; an idle poll allocates nothing. Console.do(line) is the dispatcher as a plain
call (the REPL, tests): it returns the reply and never raises. Units at the console: mm,
degrees, us, mm/s, deg/s, cm (hexapod.units parses them without floats).

Readers hand over one byte at a time: PollReader (MicroPython: select.poll on sys.stdin),
CircuitPython's SerialReader lives in code.py, the tests' BufferReader in the stubs
(_stub_serial): a board's heap keeps neither.
"""

import sys

from micropython import const

from hexapod import faultlog, follow, gait, release, sensors, tick
from hexapod.body import FINE_SHIFT
from hexapod.leg import describe as leg_describe
from hexapod.units import format_fixed, parse_fixed

LINE_MAX = const(95)  # characters in a line, without its end
MAX_BYTES = const(64)  # bytes taken per frame: a flood cannot stretch a frame
WALK_TIMEOUT_MS = const(1000)
JOINTS = ("coxa", "femur", "tibia")
COMMANDS = (
    "help status stand sit relax foot nudge joint pulse get walk stop gait height sonar wall pid "
    "cal trim dir range save load defaults echo selftest faults stream"
)
TAG_DIGITS = const(9)  # a request tag: '#' and 1..9 digits (docs/console.md, "Request tags")
# Commands that may take longer than a frame (a gait's servo speed guard: 1.5-1.8 s on a Pico; a
# posture move's trial of all its frames; a flash write): a tagged request of one of them gets
# '#TAG working' before the command runs, so a client waits for its reply without a fixed timeout.
SLOW = ("gait", "height", "stand", "sit", "relax", "save", "load", "defaults")
# The jog and calibration commands' modules (CALS): imported at a jog session's first command and
# kept while the session goes on (each import took 24-45 ms on a Pico: the frame overran), let go
# (hexapod.release) CAL_KEEP_MS after its last command or once the robot walks or follows a wall:
# the 5.3 KB of heap they take on a Pico are the walking loop's again. Five modules, not one
# (consolecal's import took 36 ms, the first `foot` after boot 78 ms): each imports in a frame.
CAL = "consolecal"  # save, load, defaults (and the boot's load of a file it must check)
JOG = "consoleparts.jog"  # foot, nudge
JOINT = "consoleparts.joint"  # joint, pulse
EDIT = "consoleparts.caledit"  # cal
CALSET = "consoleparts.calset"  # trim, dir, range: with the four above, a jog session's modules
CALS = (JOG, JOINT, EDIT, CALSET, CAL)
CAL_KEEP_MS = const(30000)
# The reporting commands' modules (consoleparts/more.py: help, echo, faults; sonar.py; `status`, the
# one tools poll, stays here: its import made the first one after 30 s take ~34 ms on an emulated
# Pico) and the setting commands' (consoleparts/setting.py: height, pid, stream; wall.py; `gait`
# stays here, asked while walking): each imported at
# the first of its commands and kept while they keep coming (let go CAL_KEEP_MS after the last
# one: the running loop does not carry them); CircuitPython (Console.compiles, set by code.py)
# compiles one per command and lets it go after each.
MORE = "consoleparts.more"
_CUTOFF = const(2)  # hexapod.battery.CUTOFF
SETTING = "consoleparts.setting"  # height, pid, stream: loaded and let go as MORE
WALL = "consoleparts.wall"  # wall: likewise
SONAR = "consoleparts.sonar"  # sonar: likewise
SELFTEST = "selftest"  # `selftest`: loaded for the command, let go when its job ends
# A line whose command needs a module not loaded yet waits (Console._wait): poll imports the first
# one missing a frame (each import fits a frame's slack on an emulated Pico; one module's import in
# the command's frame made it late), then runs the line in the next frame, its reply the same: the
# consoleparts package first (its own import is a frame), then BEFORE's chain, deepest first (a
# module there needs the one it names loaded before it), then the command's module.
BEFORE = {JOG: "hexapod.jog", "hexapod.jog": EDIT, JOINT: JOG, CALSET: EDIT, CAL: "calstore"}


def load(name, compiles=False):
    """The module `name`, imported: the console's parts loaded on demand (consoleparts, consolecal,
    selftest). compiles: the board compiles a module's source at its import (CircuitPython:
    Console.compiles); a module not loaded yet is then compiled on a collected heap (else the
    collector runs only once an allocation fails, with the parse's first blocks already placed in
    the small holes the loop's heap has). hexapod.release(name) lets it go again. hexapod flash
    ships a module loaded so when its name is a module-level constant of the file (MORE =
    "consoleparts.more": serial.flash._imports). Here, not beside hexapod.release: a Pico keeps 96 B
    more heap free with it among console's globals than among the hexapod package's (the
    resident heap of tests/test_pico.py: 73,104 B against 73,008)."""
    if compiles and name not in sys.modules:
        import gc

        gc.collect()
    __import__(name)
    return sys.modules[name]


def fault_text(log, bank):
    """'none', or 'N logged (oldest first) KIND WHAT frame F[ before_reset]; ...' (runner.faultlog)."""
    n = log.count()
    if not n:
        return "none"
    parts = []
    chips = getattr(bank, "chips", ())
    names = sensors.SENSOR_NAMES
    for i in range(n):
        kind, what, frame, before = log.entry(i)
        if kind == faultlog.SONAR:
            where = " " + names[what] if what < len(names) else ""
        elif kind == faultlog.I2C or kind == faultlog.BROWNOUT:
            where = " 0x%02x" % chips[what].address if what < len(chips) else ""
        else:
            where = ""
        parts.append("%s%s frame %d%s" % (faultlog.KIND_NAMES[kind], where, frame, " before_reset" if before else ""))
    return "%d logged (oldest first) %s" % (n, "; ".join(parts))


class PollReader:
    """MicroPython: the bytes waiting on a stream (sys.stdin), without blocking or allocating."""

    def __init__(self, stream=None):
        import select

        stream = sys.stdin if stream is None else stream
        self._poll = select.poll()
        self._poll.register(stream, select.POLLIN)
        self._src = getattr(stream, "buffer", stream)
        self._one = bytearray(1)

    def read_byte(self):
        """The next byte (0..255), or -1 when none is waiting."""
        for _ in self._poll.ipoll(0):
            if self._src.readinto(self._one) == 1:
                return self._one[0]
            return -1
        return -1


class Console:
    """Command lines -> calls on a runner.Runner; replies through `out` (print on a board)."""

    # True: consolecal stays loaded once imported (no session end lets it go).
    keep_cal = False
    # True: consolecal, loaded when the console starts, stays until the robot walks or follows a
    # wall (no CAL_KEEP_MS timeout): CircuitPython's code.py compiles it at boot, on a heap with
    # room, for the first day's jog session, and lets the loop have its heap once the robot walks
    # (a jog session after that compiles it again at its first command, on the loop's heap). Not
    # compiled at a jog session's first command, nor at boot for the calibration file's load after
    # build(): both measured worse (docs/flashing.md).
    cal_until_walk = False
    # True where the board compiles a module's source at each import (CircuitPython: code.py sets
    # it): consoleparts.more is let go after each of its commands instead of kept CAL_KEEP_MS (the loop's
    # heap over a compile per command), and the modules loaded on demand (consoleparts.more, consolecal,
    # selftest and its bus checks) are compiled on a collected heap: the collector would run only
    # once an allocation failed, with the parse's first blocks already placed in the small holes
    # the loop's heap has (bench.feather: 16 KB more free heap needed without it, 2026-11-28).
    compiles = False
    fs = None  # (os, open): the filesystem console.start was given (cal_store)
    _boot = None  # the boot's calibration file load under way (console.start, _booting)
    _wait = None  # (words, tag): a line waiting for its command's modules (_missing, _waiting)

    def __init__(self, runner, reader=None, out=print, store=None, walk_timeout_ms=WALK_TIMEOUT_MS, write=None):
        """runner: runner.Runner; reader: has read_byte(); store: calstore.Store or None (no
        file: save/load answer err; console.start gives the board's filesystem instead, fs: see
        cal_store); walk_timeout_ms: a console walk's life without renewal; write: raw text out
        without a line end (sys.stdout.write), for `echo on`."""
        self.runner = runner
        self.robot = runner.robot
        self.reader = reader
        self.out = out
        self.store = store
        self.walk_timeout_ms = walk_timeout_ms
        self._buf = bytearray(LINE_MAX)
        self._view = memoryview(self._buf)
        self._n = 0
        self._over = 0  # characters typed past LINE_MAX (dropped, but a backspace takes them back)
        self._bad = -1  # the first non-text byte of the line being read
        self._bad_at = 0  # its position in the line
        self.write = write
        self.echo = False  # typed characters sent back (a person in a terminal; off for tools)
        self._cr = False
        self._walking = False  # a console walk runs, expiring at _deadline (ticks_ms)
        self._deadline = 0
        self._held = False  # a held frame was announced (once, until frames are sent again)
        self._battery = 0  # hexapod.battery.OK: the battery state last announced (a notice at each change)
        self.lines = 0  # lines answered
        self._job = None  # a multi-line reply under way (selftest): step() once a frame, abort(), done
        self._job_tag = None  # its request's tag: each of its lines carries it
        self._late = None  # "gait"/"height" being checked over frames (wait=False): its reply waits
        self._late_tag = None  # that request's tag: its late reply carries it
        self.telemetry = None  # stream.Stream once `stream on` made one (tests hand theirs in)
        # The robot file's calibration (robots/<robot>_cal.py): (centre_us, direction, min_us,
        # max_us) per servo; centre_us is the pulse at the servo's reference angle (ref_cdeg).
        self.base = tuple((s.centre_us, s.direction, s.min_us, s.max_us) for s in self.robot.servos)
        self.trims = [0] * 18
        self.cal_source = "defaults"
        # consolecal stays loaded for a jog session until then (ticks_ms); -1: not loaded
        self._cal_until = 0 if self.cal_until_walk and CAL in sys.modules else -1
        self._more_until = -1  # consoleparts.more stays loaded until then (ticks_ms); -1: not loaded
        self._table = {
            "help": MORE,
            "status": self._status,
            "stand": self._stand,
            "sit": self._sit,
            "relax": self._relax,
            "foot": JOG,
            "nudge": JOG,
            "joint": JOINT,
            "pulse": JOINT,
            "get": self._get,
            "walk": self._walk,
            "stop": self._stop,
            "gait": self._gait,
            "height": SETTING,
            "sonar": SONAR,
            "wall": WALL,
            "pid": SETTING,
            "cal": EDIT,
            "trim": CALSET,
            "dir": CALSET,
            "range": CALSET,
            "save": CAL,
            "load": CAL,
            "defaults": CAL,
            "echo": MORE,
            "selftest": self._selftest,
            "faults": MORE,
            "stream": SETTING,
        }

    # -- the frame's part ---------------------------------------------------------------

    def poll(self):
        """Once per frame: announce a held frame once, take waiting bytes, run a complete line,
        expire a stale walk. A telemetry line first: it shows the frame just done. (While the boot's
        calibration load is under way, _boot_step stands in for this: console.start.)"""
        t = self.telemetry
        if t is not None:
            t.frame(self.runner)
        if self.robot.reason:
            if not self._held:
                self._held = True
                self.out(self.held_line())
        elif self._held:
            self._held = False
        b = self.runner.battery
        if b is not None and b.state != self._battery:
            self._battery = b.state
            self.out(self.battery_line())
        if self._walking:
            clock = self.runner.clock
            if clock.ticks_diff(clock.ticks_ms(), self._deadline) >= 0:
                self._walking = False
                if self.robot.mode == tick.WALKING and not self.runner.follower.mode:
                    self.robot.stop()
        if self._cal_until >= 0 and self._cal_over():
            self._cal_until = -1
            release(*CALS, CAL if self.compiles else "calstore")  # CircuitPython keeps calstore (a compile)
        if self._more_until >= 0:
            clock = self.runner.clock
            if clock.ticks_diff(clock.ticks_ms(), self._more_until) >= 0:
                self._more_until = -1
                release(MORE, SETTING, WALL, SONAR)
        if self._job is not None:
            self._job_step()
        if self._late is not None and not self.robot.configuring():
            self._late_done()
        if self._wait is not None and self._waiting():
            return  # no byte read while a line waits: the lines after it keep their order
        reader = self.reader
        if reader is None:
            return
        for _ in range(MAX_BYTES):
            b = reader.read_byte()
            if b < 0:
                return
            if b == 10 or b == 13:
                if b == 10 and self._cr:  # the \n of a \r\n
                    self._cr = False
                    continue
                self._cr = b == 13
                self._end_line()
                if self._wait is not None:
                    return  # the rest stays in the port until the waiting line has run
                continue
            self._cr = False
            if b == 8 or b == 127:  # backspace (terminals send either): the line's last character goes
                self._erase()
                continue
            if b == 35:  # '#' starts a tagged request: what came before it on the line is dropped
                self._restart()
            if self._n >= LINE_MAX:
                self._over += 1  # not echoed either: the terminal shows where the line stopped
            else:
                self._buf[self._n] = b
                self._n += 1
                if self.echo and (32 <= b <= 126 or b == 9):
                    self.write(chr(b) if b != 9 else " ")
            if ((b < 32 and b != 9) or b > 126) and self._bad < 0:
                self._bad = b
                self._bad_at = self._n + self._over - 1

    def _erase(self):
        if self._over:
            self._over -= 1
        elif self._n:
            self._n -= 1
            b = self._buf[self._n]
            if self.echo and (32 <= b <= 126 or b == 9):  # only what was echoed is rubbed out
                self.write("\b \b")
        if self._bad >= 0 and self._n + self._over <= self._bad_at:
            self._bad = -1  # the non-text byte itself was taken back

    def _restart(self):
        """Drop the line typed so far (half-typed text, a stray byte): a tagged request starts
        from a clean line without any control byte (docs/console.md)."""
        if self.echo and self._n:
            self.write("\r\n")
        self._n = 0
        self._over = 0
        self._bad = -1

    def _end_line(self):
        n = self._n
        self._n = 0
        if self.echo:
            self.write("\r\n")
        tag = None
        if self._over or self._bad >= 0:
            k = tag_length(self._buf, n)
            if k > 0:  # the refusal still reaches the client waiting on this tag
                tag = bytes(self._buf[:k]).decode()
        if self._over:
            reply = "err line too long (at most %d characters)" % LINE_MAX
        elif self._bad >= 0:
            reply = "err non-text byte 0x%02x in line (allowed: printable ASCII)" % self._bad
        elif n == 0:
            return
        else:
            if self._job is not None:  # a new line ends a multi-line reply under way, with its end line
                self._job_end(self._job.abort())
            # From the preallocated view: one copy fewer than bytes(buf[:n]).decode() (64-96 bytes
            # less a line, bench tick's console rows).
            words = str(self._view[:n], "ascii").replace("\t", " ").split()
            if self._buf[0] == 35 and tag_length(self._buf, n) > 0:
                tag = words[0]  # a word the split made anyway: echoing it copies no reply
            if not self.compiles and self._missing(words, tag) is not None:
                self._wait = (words, tag)  # its modules first, one a frame (_waiting)
                return
            reply = self._dispatch(words, tag)
            if reply is None:
                return
        self._over = 0
        self._bad = -1
        self.lines += 1
        self._say(tag, reply)

    def _missing(self, words, tag):
        """The first module not loaded yet (BEFORE's order) that the line's command needs; None when
        all are loaded, or the command is not one loaded on demand."""
        k = 0 if tag is None else 1
        name = self._table.get(words[k]) if len(words) > k else None
        if type(name) is not str:
            return None
        if "consoleparts" not in sys.modules:
            return "consoleparts"
        missing = None
        while name is not None:
            if name not in sys.modules:
                missing = name
            name = BEFORE.get(name)
        return missing

    def _waiting(self):
        """poll while a line waits for its command's modules: True when one was imported, else the
        line run (False: poll reads on). An import that fails runs the line at once: the command's
        own import says why in its reply."""
        words, tag = self._wait
        name = self._missing(words, tag)
        if name is not None:
            try:
                load(name)
                return True
            except Exception:
                pass
        self._wait = None
        reply = self._dispatch(words, tag)
        if reply is not None:
            self.lines += 1
            self._say(tag, reply)
        return False

    def _say(self, tag, line):
        """One line out, after its request's tag when it had one (out(tag, line): print puts a
        space between, so the reply is not copied to a new string)."""
        if tag is None:
            self.out(line)
        else:
            self.out(tag, line)

    # -- the dispatcher -------------------------------------------------------------------

    def do(self, line):
        """Run one command line; the reply line ('ok ...' or 'err ...'), None for a blank line.
        A tagged line ('#7 get 2') gets its reply after the tag ('#7 ok leg 2 ...'). The boot's
        calibration load, if still under way, is finished first."""
        while self._boot is not None:
            next(self._boot)
        words = line.replace("\t", " ").split()
        raw = words[0].encode() if words else b""
        tag = words[0] if tag_length(raw, len(raw)) > 0 else None
        reply = self._dispatch(words, tag)
        return reply if tag is None or reply is None else tag + " " + reply

    def _dispatch(self, words, tag):
        """The reply to a line's words (tag: words[0] is the request's tag, else None)."""
        if not words:
            return None
        if words[0].startswith("#"):
            if tag is None:
                return "err bad tag %r: allowed '#' and 1..%d digits, then a space and the command" % (
                    words[0][:20],
                    TAG_DIGITS,
                )
            if len(words) == 1:
                return "err nothing after the tag (a tagged request is '#N command ...')"
            word = words[1]
            args = words[2:]
        else:
            word = words[0]
            args = words[1:]
        fn = self._table.get(word)
        if fn is None:
            return "err unknown command %r (help lists them)" % (word[:20],)
        if tag is not None and word in SLOW:
            self.out(tag, "working")  # sent before the command runs: the client waits on
        try:
            if fn in CALS:
                reply = self._calibration(word, args)
            elif fn is MORE or fn is SETTING or fn is WALL or fn is SONAR:
                reply = self._part(fn, word, args)
            else:
                reply = fn(args)
        except ValueError as e:
            return "err %s: %s" % (word, e)
        except Exception as e:  # the loop must go on whatever a command hits
            return "err %s: internal error %s %s" % (word, type(e).__name__, e)
        if reply is None:  # a multi-line reply started, or a gait's check: poll() prints the rest
            if word == self._late:
                self._late_tag = tag
            else:
                self._job_tag = tag
            return None
        if reply[:4] == "err " and not reply.startswith("err " + word + ":"):
            reply = "err %s: %s" % (word, reply[4:])  # every err names its command
        return reply

    def _status(self, args):
        """`status`, here (not in consoleparts.more): the command tools poll answers without an import."""
        from runner import BOOT_WORDS, counters  # (imported here: CircuitPython compiles console before runner)

        self._args(args, 0, "no arguments")
        r = self.runner
        f = r.follower
        left = 0
        if self._walking:
            left = r.clock.ticks_diff(self._deadline, r.clock.ticks_ms())
            left = left if left > 0 else 0
        on = f.mode != follow.OFF
        b = r.battery
        if b is None:
            state = level = "n/a"
        else:
            from hexapod import battery

            state = battery.STATE_NAMES[b.state]
            level = b.level_mv
        return (
            "ok %s faults %d mode %s gait %s "
            "walk_ms %d wall %s wall_mode %s wall_d %s wall_angle %s wall_error %s wall_out %s wall_faults %d "
            "cal %s boot %s battery %s battery_mv %s"
            % (
                counters(r),
                r.robot.faults,
                tick.MODE_NAMES[r.robot.mode],
                gait.NAMES[r.robot.gait],
                left,
                f.side if on else "off",
                follow.MODE_NAMES[f.mode],
                format_fixed(f.distance, 1) if on and f.distance >= 0 else "-",  # no distance (yet)
                format_fixed(f.angle if on else 0, 2),
                format_fixed(f.error if on else 0, 1),
                format_fixed(f.output if on else 0, 2),
                f.fault_total if on else 0,
                self.cal_source,
                BOOT_WORDS[r.boot],
                state,
                level,
            )
        )

    # -- parsing ----------------------------------------------------------------------------

    def _args(self, args, n, usage):
        if len(args) != n:
            raise ValueError("need %s, got %d argument%s" % (usage, len(args), "" if len(args) == 1 else "s"))

    def _leg(self, text):
        if text not in ("1", "2", "3", "4", "5", "6"):
            raise ValueError("leg %r, allowed 1..6" % (text[:20],))
        return int(text) - 1

    def _num(self, name, text, places, lo, hi, unit):
        try:
            v = parse_fixed(text, places)
        except ValueError:
            raise ValueError("%s %r is not a decimal number (%s)" % (name, text[:20], unit)) from None
        if v < lo or v > hi:
            lo = format_fixed(lo, places)
            raise ValueError("%s %s is outside %s..%s %s" % (name, text[:20], lo, format_fixed(hi, places), unit))
        return v

    # -- replies --------------------------------------------------------------------------

    def leg_line(self, leg):
        """'ok leg L angles C F T pulses PC PF PT foot X Y Z' for leg 0..5."""
        r = self.robot
        k = 3 * leg
        a = r.angles
        foot = [0, 0, 0]
        r.geometry.legs[leg].fk(a[k], a[k + 1], a[k + 2], foot, 0)
        p = r.pulses
        return "ok leg %d angles %s %s %s pulses %d %d %d foot %s %s %s" % (
            leg + 1,
            format_fixed(a[k], 2),
            format_fixed(a[k + 1], 2),
            format_fixed(a[k + 2], 2),
            p[k],
            p[k + 1],
            p[k + 2],
            format_fixed(foot[0], 1),
            format_fixed(foot[1], 1),
            format_fixed(foot[2], 1),
        )

    def _refused(self, code):
        r = self.robot
        if code == tick.JOG_IK:
            return "err " + leg_describe(r.jog_code, r.jog_excess)
        if code == tick.JOG_SERVO:
            return "err leg %d %s: the pulse would be %d us %s its calibrated %d..%d us" % self._servo_past()
        if code == tick.PATH_IK:
            return "err leg %d would not get there: %s on the way; place it with 'foot' first" % (
                r.path_leg + 1,
                leg_describe(r.jog_code, r.jog_excess),
            )
        if code == tick.PATH_SERVO:
            return (
                "err leg %d %s would not get there: its pulse would go %d us %s its calibrated %d..%d us"
                % self._servo_past()
            )
        return "err " + tick.describe(code)

    def _servo_past(self):
        """(leg, joint, us, below|above, min_us, max_us): the servo the last jog or posture check
        refused, how far past its range it would have gone, and the range."""
        r = self.robot
        k = r.jog_servo
        s = r.servos[k]
        return (k // 3 + 1, JOINTS[k % 3], r.jog_excess, "below" if r.jog_code == 1 else "above", s.min_us, s.max_us)

    def held_line(self):
        """The notice for a held frame (the robot's reason, fault_leg, ...): never 'ok' or 'err'."""
        r = self.robot
        if r.reason == tick.FRAME_SERVO:
            k = r.fault_servo
            s = r.servos[k]
            why = "%s pulse %d us %s its calibrated %d..%d us" % (
                JOINTS[k % 3],
                r.fault_excess,
                "below" if r.fault_code == 1 else "above",
                s.min_us,
                s.max_us,
            )
        elif r.reason == tick.FRAME_IK:
            why = leg_describe(r.fault_code, r.fault_excess)
        else:
            why = tick.describe(r.reason)
        return "held: leg %d: %s; the servos keep the last frame until it clears (mode %s)" % (
            r.fault_leg,
            why,
            tick.MODE_NAMES[r.mode],
        )

    def battery_line(self):
        """The notice for a battery state change: never 'ok' or 'err'."""
        from hexapod import battery as batteries  # loaded with the monitor: a board without one never loads it

        b = self.runner.battery
        v = batteries.volts
        if b.state == batteries.LOW:
            return "battery: low, %s V (below %s V for 1 s): walking capped at %d mm/s and %d deg/s; charge soon" % (
                v(b.level_mv),
                v(b.warn_mv),
                batteries.LOW_SPEED // 10,
                batteries.LOW_YAW // 100,
            )
        if b.state == batteries.CUTOFF:
            return "battery: cutoff, %s V (below %s V for 1 s): sitting down, then relaxed; %s" % (
                v(b.level_mv),
                v(b.cutoff_mv),
                "stand, walk and wall refused until above %s V" % v(b.resume_mv),
            )
        return "battery: ok, %s V (above %s V for 1 s): stand, walk and wall allowed, no speed cap" % (
            v(b.low_mv),
            v(b.resume_mv),
        )

    def _battery_ok(self):
        """ValueError naming the battery and its voltage while it is cut off: every command that
        would drive a servo (stand, sit, walk, wall, the jog) waits for a charged pack."""
        b = self.runner.battery
        if b is not None and b.state == _CUTOFF:
            from hexapod import battery as batteries

            v = batteries.volts
            raise ValueError(
                "battery %s V, cut off below %s V (%d cells); charge it: allowed again after 1 s above %s V"
                % (v(b.mv), v(b.cutoff_mv), b.cells, v(b.resume_mv))
            )

    def _mode_reply(self, code):
        if code:
            return self._refused(code)
        return "ok mode " + tick.MODE_NAMES[self.robot.mode]

    def _no_follow(self):
        if self.runner.follower.mode:
            raise ValueError("the robot is following a wall; 'wall off' first")

    # -- commands -------------------------------------------------------------------------

    def _stand(self, args):
        self._args(args, 0, "no arguments")
        self._no_follow()
        self._battery_ok()
        return self._mode_reply(self.robot.stand_up())

    def _sit(self, args):
        self._args(args, 0, "no arguments")
        self._no_follow()
        self._battery_ok()
        return self._mode_reply(self.robot.sit_down())

    def _relax(self, args):
        self._args(args, 0, "no arguments")
        self._no_follow()
        return self._mode_reply(self.robot.relax())

    def _get(self, args):
        self._args(args, 1, "L (leg 1..6)")
        return self.leg_line(self._leg(args[0]))

    def _walk(self, args):
        self._args(args, 3, "VX VY WZ (mm/s, mm/s, deg/s)")
        vx = self._num("vx", args[0], 1, -3000, 3000, "mm/s")
        vy = self._num("vy", args[1], 1, -3000, 3000, "mm/s")
        wz = self._num("wz", args[2], 2, -9000, 9000, "deg/s")
        self._no_follow()
        self._battery_ok()
        code = self.robot.walk(vx, vy, wz)
        if code:
            return self._refused(code)
        clock = self.runner.clock
        self._walking = bool(vx or vy or wz)
        self._deadline = clock.ticks_add(clock.ticks_ms(), self.walk_timeout_ms)
        return "ok walk %s %s %s timeout_ms %d" % (
            format_fixed(vx, 1),
            format_fixed(vy, 1),
            format_fixed(wz, 2),
            self.walk_timeout_ms,
        )

    def _stop(self, args):
        self._args(args, 0, "no arguments")
        self._walking = False
        if self.runner.follower.mode:
            self.runner.follow_off()
        return self._mode_reply(self.robot.stop())

    def _gait(self, args):
        # Here, not in consoleparts.setting: a gait asked while walking must not wait for a module's
        # import (21.9 ms on the emulated Pico: the frame overran).
        if args:
            self._args(args, 1, "a gait name (%s)" % ", ".join(gait.NAMES))
            if args[0] not in gait.NAMES:
                raise ValueError("%r, allowed %s" % (args[0][:20], ", ".join(gait.NAMES)))
            # Checked over the next frames (the servo guard's solves), the robot walking on
            # meanwhile and the console answering other lines: the reply comes when it is done.
            return self._later("gait", self.robot.set_gait(gait.NAMES.index(args[0]), wait=False))
        return self._ok_late("gait")

    def _later(self, word, code):
        """A gait's or height's reply: refused now, or None while it is checked (poll answers)."""
        if code:
            return self._refused(code)
        if self.robot.configuring():
            self._late = word
            return None
        return self._ok_late(word)

    def _ok_late(self, word):
        r = self.robot
        if word == "gait":
            return "ok gait " + gait.NAMES[r.gait]
        return "ok height " + format_fixed(-(r.walker.ground >> FINE_SHIFT), 1)

    def _late_done(self):
        word = self._late
        self._late = None
        code = self.robot.job_code
        reply = self._refused(code) if code else self._ok_late(word)
        if reply[:4] == "err " and not reply.startswith("err %s:" % word):
            reply = "err %s: %s" % (word, reply[4:])
        self.lines += 1
        self._say(self._late_tag, reply)
        self._late_tag = None

    def _part(self, name, word, args):
        """A reporting or setting command (consoleparts.more or .setting, name): its module stays
        CAL_KEEP_MS after it (poll lets it go), or goes at once where the board compiles it
        (compiles). Where consolecal waits for the robot to walk (cal_until_walk), `wall` lets it
        go before its module's compile (a jog command after it compiles consolecal again)."""
        if self.cal_until_walk and word == "wall":
            release(*CALS)
        part = load(name, self.compiles)
        try:
            return part.command(self, word, args)
        finally:
            part = None
            if self.compiles:
                release(name)
            else:
                clock = self.runner.clock
                self._more_until = clock.ticks_add(clock.ticks_ms(), CAL_KEEP_MS)

    def _booting(self, board):
        """The boot's calibration file load (console.start), a generator whose steps poll runs one a
        frame (each inside the frame's slack on an emulated Pico: calstore's import, the file's read
        and check, the rows six at a time through Robot.calibrate). A version 2
        file on a robot sending no pulse (every boot) is put in force here as consolecal.put_file
        would (no refusal can come but at the first servo, before any change): consolecal's import
        (~26 ms on a Pico) only for any other file. calstore goes again when the boot loaded it.
        Then runner.power_up(board, calibrated), when board is given. A step that raises
        (a Ctrl-C) leaves a new load in its place: the next poll or do starts it over."""
        cs = "calstore" in sys.modules
        try:
            store = self.cal_store()
            if store is not None:
                yield
                try:
                    found = store.load()
                except ValueError as e:
                    reply = "ok defaults (%s)" % (e,)
                else:
                    reply = None
                    robot = self.robot
                    if found[2] == 2 and not any(robot.pulses):
                        new = found[0]
                        for k in range(18):
                            if k % 6 == 0:
                                yield
                            t, d, lo, hi = new[k]
                            if robot.calibrate(k, self.base[k][0] + t, d, lo, hi):
                                break
                            self.trims[k] = t
                        else:
                            self.cal_source = "file"
                            reply = "ok loaded"
                    if reply is None:
                        reply = self._calibration("boot", found)
                if reply.startswith("ok defaults ("):
                    self.out("cal: %s; the robot file's calibration is in use" % reply[13:-1])
                elif not reply.startswith("ok loaded"):
                    self.out("cal: " + reply[4:])
        except BaseException:
            self._boot = self._booting(board)
            raise
        if not cs:
            release("calstore")
        del self._boot, self.poll  # Console.poll again (console.start put _boot_step in its place)
        if board is not None:
            self.runner.power_up(board, self.cal_source == "file")
        yield

    def _boot_step(self):
        """poll while the boot's calibration load is under way: one step of it (_booting), and no
        byte read, so no command runs before the file's calibration is in force (the bytes wait in
        the port's buffer). The load's end takes this stand-in away: poll itself pays nothing."""
        next(self._boot)

    def cal_store(self):
        """The calibration file's calstore.Store: the one handed in, else one on the filesystem
        console.start was given (calstore is on the heap only while a user needs it: the boot's
        load, a calibration session, selftest's check), else None (no file here)."""
        if self.store is not None or self.fs is None:
            return self.store
        from calstore import Store

        store = Store(*self.fs)
        if self.compiles:  # CircuitPython keeps calstore (a compile) and this Store: code.py lets its __init__ go
            self.store = store
        return store

    def _calibration(self, word, args):
        """A jog or calibration command (consoleparts.jog, .caledit, consolecal: CALS): the session's
        modules stay on the heap (poll lets them go, _cal_over); the boot's file load ("boot") lets
        consolecal go at once."""
        cal = load(self._table.get(word, CAL), self.compiles)
        try:
            return cal.command(self, word, args)
        finally:
            if not self.keep_cal:
                if word == "boot":
                    release(CAL, CAL if self.compiles else "calstore")
                else:
                    clock = self.runner.clock
                    self._cal_until = clock.ticks_add(clock.ticks_ms(), CAL_KEEP_MS)

    def _cal_over(self):
        """True when the jog session is over: CAL_KEEP_MS without a jog or calibration command, or
        the robot walks or follows a wall (none of those commands runs then)."""
        if self.robot.mode == tick.WALKING or self.runner.follower.mode:
            return True
        if self.cal_until_walk:
            return False
        clock = self.runner.clock
        return clock.ticks_diff(clock.ticks_ms(), self._cal_until) >= 0

    # -- multi-line replies (selftest) ------------------------------------------------------

    def _selftest(self, args):
        st = load(SELFTEST, self.compiles)  # only now: the module leaves the heap again when the job ends
        try:
            job = st.start(self, args)
        except Exception:
            release_selftest()
            raise
        if self._job is not None:
            self._job_end(self._job.abort())
        self._job = job
        return None

    def _job_step(self):
        """Once a frame while a multi-line reply is under way: its lines, then (done) the end."""
        job = self._job
        try:
            lines = job.step()
        except Exception as e:  # the loop must go on: the reply still ends with its end line
            try:  # noqa: SIM105 (no contextlib on MicroPython)
                job.abort()  # puts back what the job borrowed (the sonar round robin)
            except Exception:
                pass
            self._job_end("err selftest: internal error %s %s" % (type(e).__name__, e))
            return
        for line in lines:
            self._say(self._job_tag, line)
        if job.done:
            self._job_end(None)

    def _job_end(self, line):
        if line is not None:
            self._say(self._job_tag, line)
        self._job = None
        self._job_tag = None
        self.lines += 1
        release_selftest()  # its heap goes back once the job is dropped


def release_selftest():
    """selftest (and the bus checks' or the servo sweep's module, when the job loaded it) out of sys.modules."""
    sys.modules.pop(SELFTEST, None)
    release(
        "consoleparts.selftestsweep",
        "consoleparts.selftestbus",
        "consoleparts.selftestboard",
        "consoleparts.selftestsonar",
    )


def tag_length(buf, n):
    """The length of the request tag at the start of buf's first n bytes ('#' and 1..TAG_DIGITS
    digits, then a space, a tab or the end): 0 when the line has none, -1 when it is malformed.
    Integers only: nothing allocated."""
    if n == 0 or buf[0] != 35:
        return 0
    k = 1
    while k < n and 48 <= buf[k] <= 57:
        k += 1
    if k == 1 or k > TAG_DIGITS + 1 or (k < n and buf[k] != 32 and buf[k] != 9):
        return -1
    return k


def start(runner, reader, os=None, opener=open, out=print, walk_timeout_ms=WALK_TIMEOUT_MS, write=None, board=None):
    """Attach a console to runner (runner.console) and load the calibration file (os: the
    filesystem module, None: none). Prints one 'cal: ...' line when the file cannot be used.
    write: raw text out (sys.stdout.write) for `echo on`; None: echo is refused. board (the board
    file, for a boot that does not stand: runner.bring_up): the load is left to the console's
    first polls, a step a frame, and runner.power_up(board, calibrated) follows it there."""
    c = Console(runner, reader, out, None, walk_timeout_ms, write)
    runner.console = c
    if os is not None:
        c.fs = (os, opener)
    c._boot = c._booting(board)
    c.poll = c._boot_step
    if board is None:
        while c._boot is not None:
            next(c._boot)
    return c
