"""The console's `selftest` (docs/console.md): hardware checks, and one leg's servos swept.

Imported by console.py only when the command runs, and dropped from sys.modules when it ends, so
the board's heap carries none of this in normal running; the servo sweep's job lives in
consoleparts/selftestsweep.py, imported for `selftest servos L` only (a smaller compile for the checks on
CircuitPython, which compiles a module's source at each import). Nothing here runs in the 50 Hz tick: a
job's step() runs in Console.poll(), after the frame was sent.

Checks (one reply line each, `ok <check> ...` or `err <check> ...: <hint>`), then the end line
`ok selftest N checks, M failed` (`err selftest ...` when M > 0):
  board, version, i2c (the bus's scan), pca9685 <address> for each chip of the board file (it
  answers; MODE1 and PRE_SCALE read back as the driver wrote them), sonar <name> for each of
  the five (the loop's own round robin pings each once while the test watches: no extra ping,
  no blocking), calibration (the file and its CRC), reset_cause, heap, supply.
The hardware checks send no servo pulse and write no PCA9685 register (register reads only).

`selftest servos L` sweeps leg L's coxa, femur and tibia one after the other, each +-10 degrees
around the angle it holds and back, at SWEEP_CDEG_PER_S, every step through Robot.jog_joint
(the robot file's joint limits and each servo's calibrated range apply); only while sitting.
"""

from console import load

from hexapod import VERSION, release, sensors, tick

# The checks' parts (consoleparts/), each a module of its own (on CircuitPython, which compiles a
# module's source at each import, a smaller compile each), loaded for its step and let go after it:
BUS = "consoleparts.selftestbus"  # the bus's checks (the first step)
BOARD = "consoleparts.selftestboard"  # the board's own checks (the first step, after the bus's)
SONAR = "consoleparts.selftestsonar"  # the sonar checks (the last step)


class _Watch:
    """Stands in for the runner's sonar round robin while the test watches: the first result of
    each sensor is kept (status, distance), everything else passes through unchanged."""

    def __init__(self, inner, n):
        self.inner = inner
        self.status = [-1] * n
        self.distance = [sensors.NO_DISTANCE] * n
        self.left = n

    def tick(self, dist, status):
        i = self.inner.tick(dist, status)
        if i >= 0 and self.status[i] < 0:
            self.status[i] = status[i]
            self.distance[i] = dist[i]
            self.left -= 1
        return i


class Checks:
    """The hardware checks as a console job: step() once a frame returns the lines ready."""

    def __init__(self, console):
        self.con = console
        self.runner = console.runner
        self.count = 0
        self.failed = 0
        self.done = False
        self.frames = 0
        r = self.runner
        n = len(r.distances)
        self.watch = _Watch(r.sonars.ring, n)
        # every sensor fired and collected inside the window: a round robin cycle and one tick more
        self.limit = len(getattr(r.sonars.ring, "slots", ())) + 2
        r.sonars.ring = self.watch

    def _line(self, out, ok, text):
        self.count += 1
        if not ok:
            self.failed += 1
        out.append(("ok " if ok else "err ") + text)

    def step(self):
        out = []
        if self.frames == 0:
            self._instant(out)
        self.frames += 1
        w = self.watch
        if w.left == 0 or self.frames >= self.limit:
            self._restore()
            self._run(SONAR, out)
            out.append(self.end())
            self.done = True
        return out

    def _restore(self):
        if self.runner.sonars.ring is self.watch:
            self.runner.sonars.ring = self.watch.inner

    def abort(self):
        """A new line came in: the end line now (the checks done so far were printed)."""
        self._restore()
        self.done = True
        return "err selftest: cut short by a new line after %d checks, %d failed" % (self.count, self.failed)

    def end(self):
        return "%s selftest %d checks, %d failed" % ("err" if self.failed else "ok", self.count, self.failed)

    # -- the checks ---------------------------------------------------------------------------

    def _instant(self, out):
        r = self.runner
        board = getattr(r, "board", None)
        self._line(
            out,
            True,
            "board %s robot %s" % (board["name"] if board else "n/a", getattr(r.robot.geometry, "name", "n/a")),
        )
        self._line(out, True, "version " + VERSION)
        chips = getattr(r.bank, "chips", None) or []
        self._run(BUS, out, board, chips)
        self._run(BOARD, out, getattr(r, "battery", None))

    def _run(self, name, out, *args):
        """The checks of the part `name` (its run(checks, out, *args)): loaded for them (where the
        board compiles, on a collected heap: console.load) and let go after, so that the next
        part's compile gets its heap."""
        part = load(name, self.con.compiles)
        part.run(self, out, *args)
        part = None
        release(name)


def start(console, args):
    """The job for `selftest` args (a list of words); ValueError (nothing changed) for bad ones."""
    if not args:
        return Checks(console)
    if args[0] != "servos":
        raise ValueError("%r, allowed nothing (the hardware checks) or 'servos L' (leg 1..6)" % (args[0][:20],))
    if len(args) != 2:
        raise ValueError("need servos L (leg 1..6), got %d argument%s" % (len(args) - 1, "" if len(args) == 2 else "s"))
    leg = console._leg(args[1])
    r = console.robot
    if console.runner.follower.mode:
        raise ValueError("the robot is following a wall; 'wall off' first")
    if r.mode != tick.SITTING:
        raise ValueError(
            "the robot is %s; servos are swept only while it sits (body on the ground, no leg carries it): 'sit' first"
            % tick.MODE_NAMES[r.mode]
        )
    from consoleparts.selftestsweep import Sweep  # only for this job: dropped with selftest when it ends

    return Sweep(console, leg)
