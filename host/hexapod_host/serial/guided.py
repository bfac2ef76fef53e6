"""The jog tool's guided calibration (docs/calibration.md): the 18 servos one after another, each
fit -> sweep -> trim, then the standing check on a flat floor, then save.

Pure like jog.py: keys in, console lines out through link.request(line) -> reply line; nothing here
runs on the board (its heap stays as it is): the procedure is made of the console's own `cal`,
`pulse`, `joint`, `dir`, `trim`, `stand`, `status` and `save` (docs/console.md).

Per servo:
1. fit: the board sends the servo's reference pulse (`pulse L J centre_us`, the untrimmed pulse
   robots/default_cal.py gives for the joint's reference angle); the horn goes on at the
   reference angle (coxa 0, femur 0, tibia -90: the knee at a right angle).
2. sweep: the joint goes +10 degrees then -10 degrees about its reference and back, 2 degrees a
   step; the maker says whether it went the right way first, and a wrong way flips the servo's
   direction (`dir`), then sweeps again.
3. trim: at the reference angle, trim by the us step until the horn sits at the reference.
A servo done is written to the progress file (host side, JSON) so a later `--guided` skips it;
Esc or q at any step quits without `save`: the calibration file on the board is untouched.
"""

import json
import os

from hexapod_host.serial.jog import CAL_FIELDS, JOINTS, STEPS_US, fields

FIT, SWEEP, TRIM, STAND, DONE, QUIT = "fit", "sweep", "trim", "stand", "done", "quit"
# The sweep about the reference, degrees: +10 first, then -10, then back, 2 degrees a step.
SWEEP_DEG = (2, 4, 6, 8, 10, 8, 6, 4, 2, 0, -2, -4, -6, -8, -10, -8, -6, -4, -2, 0)
SWEEP_PAUSE_S = 0.1  # between sweep steps: 20 degrees a second, slow enough to watch
STAND_POLLS = 300  # `status` polls (a frame or more each) waiting for the stand to finish
SERVOS = [(leg, joint) for leg in range(1, 7) for joint in JOINTS]


# What +10 degrees looks like on the robot (design.md: seed 004's DH angles).
def plus(leg, joint):
    """What +10 degrees looks like for this joint (design.md: seed 004's DH angles)."""
    if joint == "coxa":
        return "counter-clockwise seen from above: the foot %s" % ("forward" if leg <= 3 else "backward")
    return "up: the knee rises" if joint == "femur" else "the knee opens: the foot swings out"


# Each phase's steps: (the keys as the terminal names them, what they do, ((key, a button's
# label), ...)). The terminal lists the first two (KEYS); the view's page makes the buttons
# (hexapod_host/view/jog.py): the keys a button sends are the ones Guide.key takes.
ACTIONS = {
    FIT: (
        ("Enter", "the horn is on at the reference angle", (("ENTER", "horn is on"),)),
        ("p", "send the reference pulse again", (("p", "pulse again"),)),
    ),
    SWEEP: (
        ("y", "it went the right way first", (("y", "right way"),)),
        ("n", "the wrong way: flip its direction", (("n", "wrong way: flip"),)),
        ("r", "sweep again", (("r", "sweep again"),)),
    ),
    TRIM: (
        ("+ -", "trim by the step", (("-", "trim -"), ("+", "trim +"))),
        ("< >", "step 1 5 10 50 us", (("<", "step <"), (">", "step >"))),
        ("Enter", "the horn is at the reference angle", (("ENTER", "servo done"),)),
    ),
    STAND: (
        ("y", "level, all six feet down: save (a stand that did not finish: stand again)", (("y", "level: save"),)),
        ("n", "redo a servo (then its leg 1-6 and c f t)", ()),  # the page: its own leg and joint picks
    ),
}
# What each key does in the fit, sweep and trim phases: (Guide's method, its arguments). Every
# key a button of ACTIONS sends is here (tests/test_guided.py); the terminal's [ ] { } trim too,
# as the jog screen's keys do. The standing check's keys take a leg and joint: Guide._stand_key.
STEPS = {
    FIT: {"ENTER": ("_sweep",), "y": ("_sweep",), "p": ("_fit",)},
    SWEEP: {"y": ("_trim_start",), "n": ("_flip",), "r": ("_sweep",)},
    TRIM: {
        **{k: ("_trim", 1) for k in "+}]"},
        **{k: ("_trim", -1) for k in "-{["},
        "<": ("_step_size", -1),
        ">": ("_step_size", 1),
        "ENTER": ("_joint_done",),
        "y": ("_joint_done",),
    },
}
# Each phase's keys, a line each (the screen may be 80 columns).
KEYS = {phase: tuple("%-6s %s" % (keys, what) for keys, what, _ in rows) for phase, rows in ACTIONS.items()}


def centidegrees(text):
    """'-90.00' -> -9000 (the console prints angles with 2 decimals; no float rounds them)."""
    sign = -1 if text.startswith("-") else 1
    whole, _, frac = text.lstrip("+-").partition(".")
    return sign * (int(whole) * 100 + int((frac + "00")[:2]))


def degrees(cdeg):
    """-9000 -> '-90.00', as the console takes it."""
    return "%s%d.%02d" % ("-" if cdeg < 0 else "", abs(cdeg) // 100, abs(cdeg) % 100)


class Guide:
    """The procedure's state: phase, the servo in hand (index into SERVOS), its cal line, what is done."""

    def __init__(self, link, error=Exception, progress=None, sleep=None, pause_s=SWEEP_PAUSE_S):
        self.link = link
        self.error = error  # the link's exception for a dead port or a silent board
        self.progress = progress  # path of the progress file, or None (nothing kept)
        self.sleep = sleep or (lambda s: None)
        self.pause_s = pause_s
        self.phase = FIT
        self.k = 0
        self.cal = {}  # the servo in hand: centre_us, ref_deg, trim, dir, min_us, max_us
        self.done = {}  # (leg, joint) -> (trim, dir)
        self.step_us = 2  # index into STEPS_US
        self.redo = None  # after 'n' at the stand check: the leg picked, waiting for c f t
        self.stood = False  # the standing check's stand finished
        self.started = False  # start() relaxed the robot (a refused start quits at once)
        self.message = ""
        self.error_shown = False
        self.connected = True

    # -- the link ------------------------------------------------------------------------------

    def ask(self, line):
        """The board's reply to line, or None after an err or a dead link (the message says which)."""
        try:
            reply = self.link.request(line)
        except self.error as err:
            self.connected = False
            self._quit("%s: %s" % (line, err))
            return None
        if reply.startswith("err"):
            why = reply[3:].strip()
            self.error_shown = True
            # 'err stand: battery ...' names its command already
            self.message = why if why.startswith(line.split()[0] + ":") else "%s: %s" % (line, why)
            return None
        self.error_shown = False
        return reply

    # -- the steps ------------------------------------------------------------------------------

    def start(self):
        """Relax (the robot supported: every servo limp until its turn), put the servos done in an
        earlier session back as they were, and go to the first one not done."""
        self.done = self._load_progress()
        if not self._relax() or not self._restore():
            # A refused start (the robot walking, a battery cutoff) leaves no guide in a phase whose
            # keys would act on servos it never relaxed: it ends here, the board's word kept.
            if self.phase != QUIT:
                self._quit("guided calibration not started: " + self.message)
            return
        self.started = True
        self._next()

    def _restore(self):
        """The servos done in an earlier session as they were (their trim and direction)."""
        for (leg, joint), (trim, direction) in sorted(self.done.items()):
            if self.ask("trim %d %s %d" % (leg, joint, trim)) is None:
                return False
            if self.ask("dir %d %s %d" % (leg, joint, direction)) is None:
                return False
        return True

    def _next(self):
        """The first servo not done (fit), else the standing check."""
        for k, servo in enumerate(SERVOS):
            if servo not in self.done:
                self.k = k
                self._fit()
                return
        self._stand()

    def _read_cal(self):
        leg, joint = SERVOS[self.k]
        reply = self.ask("cal %d %s" % (leg, joint))
        if reply is None:
            return False
        f = fields(reply, CAL_FIELDS)
        self.cal = {k: int(f[k][0]) for k in ("centre_us", "trim", "dir", "min_us", "max_us")}
        self.cal["ref_cdeg"] = centidegrees(f["ref_deg"][0])
        return True

    def _fit(self):
        self.phase = FIT
        if not self._read_cal():
            return
        leg, joint = SERVOS[self.k]
        if self.ask("pulse %d %s %d" % (leg, joint, self.cal["centre_us"])) is not None:
            self.message = "leg %d %s at its reference pulse %d us: fit the horn at %s deg" % (
                leg,
                joint,
                self.cal["centre_us"],
                degrees(self.cal["ref_cdeg"]),
            )

    def _sweep(self):
        self.phase = SWEEP
        leg, joint = SERVOS[self.k]
        ref = self.cal["ref_cdeg"]
        for d in SWEEP_DEG:
            if self.ask("joint %d %s %s" % (leg, joint, degrees(ref + 100 * d))) is None:
                return
            self.sleep(self.pause_s)
        self.message = "swept +10 deg, then -10 deg and back: did it go the right way first?"

    def _flip(self):
        leg, joint = SERVOS[self.k]
        if self.ask("dir %d %s %d" % (leg, joint, -self.cal["dir"])) is None:
            return
        self.cal["dir"] = -self.cal["dir"]
        self._sweep()
        if self.phase == SWEEP and self.connected and not self.error_shown:
            self.message = "direction now %+d, swept again: the right way first now?" % self.cal["dir"]

    def _trim_start(self):
        self.phase = TRIM
        self.step_us = 2  # 10 us (1 degree) to start each servo: coarse, then finer
        leg, joint = SERVOS[self.k]
        if self.ask("joint %d %s %s" % (leg, joint, degrees(self.cal["ref_cdeg"]))) is not None:
            self.message = "at %s deg with trim %+d us: trim until the horn sits at the reference" % (
                degrees(self.cal["ref_cdeg"]),
                self.cal["trim"],
            )

    def _trim(self, sign):
        leg, joint = SERVOS[self.k]
        trim = self.cal["trim"] + sign * STEPS_US[self.step_us]
        if self.ask("trim %d %s %d" % (leg, joint, trim)) is not None:
            self.cal["trim"] = trim
            self.message = "trim %+d us" % trim

    def _joint_done(self):
        self.done[SERVOS[self.k]] = (self.cal["trim"], self.cal["dir"])
        self._save_progress()
        self._next()

    def _until(self, command, mode):
        """Send command, then poll `status` until the robot's mode is mode; False on an err, a dead
        link, or a mode not reached within STAND_POLLS polls (the message says which)."""
        if self.ask(command) is None:
            return False
        for _ in range(STAND_POLLS):
            reply = self.ask("status")
            if reply is None:
                return False
            if " mode %s " % mode in reply:
                return True
        self.error_shown = True
        self.message = "%s: not %s after %d status polls" % (command, mode, STAND_POLLS)
        return False

    def _relax(self):
        return self._until("relax", "relaxed")

    def _stand(self):
        self.phase = STAND
        self.stood = self._until("stand", "standing")
        if self.stood:
            self.message = "standing: on a flat floor, is the body level with all six feet down?"

    def _save(self):
        reply = self.ask("save")
        if reply is None:
            return
        self.phase = DONE
        self.message = "%s: 18 servos calibrated" % reply[3:]
        if self.progress and os.path.exists(self.progress):
            os.remove(self.progress)  # all done and saved on the board: nothing to resume

    def over(self):
        """Saved, or quit: no key does anything more."""
        return self.phase in (DONE, QUIT)

    def _quit(self, why):
        self.phase = QUIT
        self.message = why

    # -- keys -------------------------------------------------------------------------------------

    def key(self, key):
        """One key (a character, ENTER or ESC) in the phase in hand."""
        if self.phase in (DONE, QUIT):
            return
        if key in ("ESC", "q"):
            self._quit(
                "quit, nothing saved (board file as it was); %d of 18 done%s"
                % (len(self.done), ", kept to resume" if self.progress and self.done else "")
            )
            return
        if self.phase == STAND:
            self._stand_key(key)
            return
        step = STEPS[self.phase].get(key)
        if step is None:
            self._refuse(key)
        else:
            getattr(self, step[0])(*step[1:])

    def _step_size(self, change):
        self.step_us = max(0, min(len(STEPS_US) - 1, self.step_us + change))
        self.message = "trim step %d us" % STEPS_US[self.step_us]

    def _stand_key(self, key):
        if self.redo is None:
            if key == "y" and not self.stood:
                self._stand()  # nothing is saved before the maker has seen it stand
            elif key == "y":
                self._save()
            elif key == "n":
                self.redo = 0
                self.message = "redo which servo? its leg 1-6, then c f t"
            else:
                self._refuse(key)
        elif self.redo == 0 and key in "123456" and len(key) == 1:
            self.redo = int(key)
            self.message = "leg %d: c f t?" % self.redo
        elif self.redo and key in ("c", "f", "t"):
            servo = (self.redo, JOINTS["cft".index(key)])
            self.redo = None
            self.done.pop(servo, None)
            if self._relax():
                self._next()
        else:
            self._refuse(key)

    def _refuse(self, key):
        self.error_shown = True
        self.message = "key %r does nothing here (keys below)" % (key,)

    # -- progress ---------------------------------------------------------------------------------

    def _load_progress(self):
        if not self.progress or not os.path.exists(self.progress):
            return {}
        with open(self.progress) as f:
            rows = json.load(f).get("done", [])
        return {(leg, joint): (trim, direction) for leg, joint, trim, direction in rows}

    def _save_progress(self):
        if not self.progress:
            return
        rows = [[leg, joint, t, d] for (leg, joint), (t, d) in sorted(self.done.items())]
        tmp = self.progress + ".tmp"
        with open(tmp, "w") as f:
            json.dump({"done": rows}, f)
        os.replace(tmp, self.progress)

    # -- the screen ---------------------------------------------------------------------------------

    def render(self):
        """The guided screen as lines of text (jog_tui draws them; tests read them)."""
        leg, joint = SERVOS[self.k]
        if self.phase in (FIT, SWEEP, TRIM):
            head = "guided calibration  servo %d of 18: leg %d %s  step: %s  (%d done)" % (
                self.k + 1,
                leg,
                joint,
                self.phase,
                len(self.done),
            )
        else:
            head = "guided calibration  %s  (%d of 18 servos done)" % (self.phase, len(self.done))
        status = "DISCONNECTED " if not self.connected else ("ERROR " if self.error_shown else "")
        lines = [head, status + self.message, ""]
        if self.cal and self.phase in (FIT, SWEEP, TRIM):
            lines.append(
                "cal  %d us at %s deg  trim %+d  dir %+d  range %d..%d us  step %d us"
                % (
                    self.cal["centre_us"],
                    degrees(self.cal["ref_cdeg"]),
                    self.cal["trim"],
                    self.cal["dir"],
                    self.cal["min_us"],
                    self.cal["max_us"],
                    STEPS_US[self.step_us],
                )
            )
        if self.phase in (FIT, SWEEP):
            lines.append("+10 deg: %s" % plus(leg, joint))
        lines.append("")
        lines += list(KEYS.get(self.phase, ()))
        if self.phase in KEYS:
            lines.append("Esc q  quit: nothing saved (the servos done are kept to resume)")
        return lines
