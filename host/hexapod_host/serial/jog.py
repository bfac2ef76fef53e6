"""The jog tool's command layer, pure: a key -> console command lines; a reply line -> the view.

No terminal and no serial port here (jog_tui.py draws, the link talks): tests drive Jog with
a fake link. The protocol is docs/console.md; keys are listed in KEYS and docs/jog.md.
Steps are decimal text sent as typed, so no float ever rounds a step.
"""

import time

JOINTS = ("coxa", "femur", "tibia")
# A `cal` reply's fields (docs/console.md): ok leg L joint J centre_us C ref_deg R trim T dir D ...
CAL_FIELDS = ("leg", "joint", "centre_us", "ref_deg", "trim", "dir", "min_us", "max_us")
STEPS_MM = ("0.5", "1", "5", "10")  # foot steps, mm
STEPS_US = (1, 5, 10, 50)  # servo nudge and trim steps, us
# Arrow keys in the leg frame: x outward along the mount, y to the left of it, z up.
MOVES = {
    "UP": (1, 0, 0),
    "DOWN": (-1, 0, 0),
    "LEFT": (0, 1, 0),
    "RIGHT": (0, -1, 0),
    "PGUP": (0, 0, 1),
    "PGDN": (0, 0, -1),
}
KEYS = (
    ("1-6", "pick the leg"),
    ("arrows", "foot x (up/down: out/in), y (left/right)"),
    ("PgUp PgDn", "foot z up / down"),
    ("+ -", "foot step 0.5 1 5 10 mm"),
    ("c f t", "pick the servo: coxa femur tibia"),
    ("[ ]", "servo pulse - / + step us"),
    ("< >", "us step 1 5 10 50"),
    ("0", "servo to its reference angle"),
    ("{ }", "trim - / + step us"),
    ("d", "flip the servo's direction"),
    ("g", "get (refresh)"),
    ("s", "save calibration"),
    ("G", "guided calibration of all 18 servos (docs/calibration.md)"),
    (":", "type any console command"),
    ("q", "quit"),
)


class View:
    """What the screen shows: the leg picked, its last leg line and cal line, steps, the last answer."""

    def __init__(self):
        self.leg = 1
        self.joint = 0  # index into JOINTS
        self.step_mm = 1  # index into STEPS_MM
        self.step_us = 2  # index into STEPS_US
        self.angles = None  # ('12.34', ...) degrees as the board printed them
        self.pulses = None  # (1500, ...) us, 0 = limp
        self.foot = None  # ('130.0', '0.0', '-80.0') mm, leg frame
        # {'centre_us': 1500, 'ref_deg': '-90.00', 'trim': 0, 'dir': 1, 'min_us': 600, 'max_us': 2400}
        self.cal = None
        self.message = ""
        self.error = False
        self.connected = True
        self.quit = False
        self.history = []  # (command, reply), newest last


def fields(reply, names):
    """{name: [values up to the next name]} of a reply's tokens."""
    out, key = {}, None
    for tok in reply.split()[1:]:
        if tok in names:
            key = tok
            out[key] = []
        elif key is not None:
            out[key].append(tok)
    return out


def apply(view, command, reply):
    """Update the view from one command's reply line."""
    view.history = (view.history + [(command, reply)])[-8:]
    if reply.startswith("err"):
        view.error = True
        view.message = "%s: %s" % (command, reply[3:].strip())
        return
    view.error = False
    words = reply.split()
    if words[1:2] == ["leg"] and "angles" in words:
        f = fields(reply, ("leg", "angles", "pulses", "foot"))
        if f.get("leg") == [str(view.leg)] and all(len(f.get(k, ())) == 3 for k in ("angles", "pulses", "foot")):
            view.angles = tuple(f["angles"])
            view.pulses = tuple(int(p) for p in f["pulses"])
            view.foot = tuple(f["foot"])
        view.message = "%s: ok" % command
    elif words[1:2] == ["leg"] and "joint" in words:
        f = fields(reply, CAL_FIELDS)
        if f.get("leg") == [str(view.leg)] and f.get("joint") == [JOINTS[view.joint]]:
            view.cal = {k: int(f[k][0]) for k in ("centre_us", "trim", "dir", "min_us", "max_us") if f.get(k)}
            if f.get("ref_deg"):
                view.cal["ref_deg"] = f["ref_deg"][0]
        view.message = "%s: ok" % command
    else:
        view.message = "%s: %s" % (command, reply)


def refresh(view):
    return ["get %d" % view.leg, "cal %d %s" % (view.leg, JOINTS[view.joint])]


def commands_for(view, key):
    """Console lines for one key (may change the view's steps, leg, joint first); [] when none."""
    leg, joint = view.leg, JOINTS[view.joint]
    if key in ("1", "2", "3", "4", "5", "6"):
        view.leg = int(key)
        view.angles = view.pulses = view.foot = view.cal = None
        return refresh(view)
    if key in MOVES:
        step = STEPS_MM[view.step_mm]
        d = [("-" + step) if s < 0 else (step if s else "0") for s in MOVES[key]]
        return ["nudge %d %s %s %s" % (leg, d[0], d[1], d[2])]
    if key in ("+", "-"):
        view.step_mm = max(0, min(len(STEPS_MM) - 1, view.step_mm + (1 if key == "+" else -1)))
        view.message = "foot step %s mm" % STEPS_MM[view.step_mm]
        return []
    if key in ("<", ">"):
        view.step_us = max(0, min(len(STEPS_US) - 1, view.step_us + (1 if key == ">" else -1)))
        view.message = "servo step %d us" % STEPS_US[view.step_us]
        return []
    if key in ("c", "f", "t"):
        view.joint = "cft".index(key)
        view.cal = None
        return ["cal %d %s" % (leg, JOINTS[view.joint])]
    if key in ("[", "]"):
        pulse = view.pulses[view.joint] if view.pulses else 0
        if not pulse:
            return _refuse(view, "leg %d %s is limp: give it a position first (0, or move the foot)" % (leg, joint))
        du = STEPS_US[view.step_us] * (1 if key == "]" else -1)
        return ["pulse %d %s %d" % (leg, joint, pulse + du)]
    if key == "0":
        if view.cal is None or "ref_deg" not in view.cal:
            return _refuse(view, "no calibration read for leg %d %s yet (press g)" % (leg, joint))
        return ["joint %d %s %s" % (leg, joint, view.cal["ref_deg"]), "cal %d %s" % (leg, joint)]
    if key in ("{", "}"):
        if view.cal is None or "trim" not in view.cal:
            return _refuse(view, "no calibration read for leg %d %s yet (press g)" % (leg, joint))
        du = STEPS_US[view.step_us] * (1 if key == "}" else -1)
        return ["trim %d %s %d" % (leg, joint, view.cal["trim"] + du), "get %d" % leg]
    if key == "d":
        if view.cal is None or "dir" not in view.cal:
            return _refuse(view, "no calibration read for leg %d %s yet (press g)" % (leg, joint))
        return ["dir %d %s %d" % (leg, joint, -view.cal["dir"]), "get %d" % leg]
    if key == "g":
        return refresh(view)
    if key == "s":
        return ["save"]
    if key == "q":
        view.quit = True
        return []
    return _refuse(view, "key %r does nothing here (keys: %s)" % (key, ", ".join(k for k, _ in KEYS)))


def _refuse(view, why):
    view.error = True
    view.message = why
    return []


PROMPT_MAX = 84  # characters the link sends in one request (link.check_line: 95 less the tag)


def prompt_key(text, key):
    """One key at the ':' prompt: (the text so far, state), state None (typing), "done" (Enter) or
    "cancel" (Esc, Ctrl-C). key: a printable character, or ENTER, BACKSPACE, ESC, CTRL-C. A control
    key is never part of the line: Ctrl-C (0x03) reaching the board stops its loop and drops the
    robot (MicroPython's KeyboardInterrupt)."""
    if key == "ENTER":
        return text, "done"
    if key in ("ESC", "CTRL-C"):
        return "", "cancel"
    if key == "BACKSPACE":
        return text[:-1], None
    if len(key) == 1 and " " <= key <= "~" and len(text) < PROMPT_MAX:
        return text + key, None
    return text, None


def typed(line):
    """A console line typed after ':' (blank: nothing). ValueError for a control or non-ASCII
    character anywhere in it: nothing of it is sent."""
    for ch in line:
        if not " " <= ch <= "~" and ch != "\t":
            why = "not sent: the line holds the control character 0x%02x (only printable text is sent)"
            raise ValueError(why % ord(ch))
    line = line.strip()
    return [line] if line else []


def render(view, port=""):
    """The screen as lines of text (jog_tui draws them; tests read them)."""
    joint = JOINTS[view.joint]
    lines = [
        "hexapod jog  %s  leg %d  servo %s  step %s mm / %d us"
        % (port, view.leg, joint, STEPS_MM[view.step_mm], STEPS_US[view.step_us])
    ]
    if view.foot:
        lines.append("foot   x %8s  y %8s  z %8s  mm (leg frame)" % view.foot)
        lines.append("angles coxa %8s  femur %8s  tibia %8s  deg" % view.angles)
        lines.append("pulses coxa %8d  femur %8d  tibia %8d  us" % view.pulses)
    else:
        lines += ["foot   ?", "angles ?", "pulses ?"]
    c = view.cal
    if c and len(c) == 6:
        lines.append(
            "cal    %s: centre %d at %s deg trim %+d dir %+d range %d..%d us"
            % (joint, c["centre_us"], c["ref_deg"], c["trim"], c["dir"], c["min_us"], c["max_us"])
        )
    else:
        lines.append("cal    %s: ?" % joint)
    status = "DISCONNECTED " if not view.connected else ("ERROR " if view.error else "")
    lines.append(status + view.message)
    lines.append("")
    lines += ["%-10s %s" % kv for kv in KEYS]
    return lines


class Jog:
    """Keys in, console lines out through link.request(line) -> reply line; the view follows."""

    def __init__(self, link, error=Exception, progress=None, sleep=time.sleep):
        self.link = link
        self.error = error  # the link's exception for a dead port or a silent board
        self.view = View()
        self.progress = progress  # the guided calibration's progress file (guided.Guide)
        self.sleep = sleep
        self.guide = None  # a guided.Guide while the guided calibration runs

    def send(self, lines):
        """Send lines in order, stopping at the first err; the status line keeps the first line's answer
        (the rest only refresh the view)."""
        first = None
        for line in lines:
            try:
                reply = self.link.request(line)
            except self.error as err:
                self.view.connected = False
                self.view.error = True
                self.view.message = "%s: %s" % (line, err)
                return
            apply(self.view, line, reply)
            if reply.startswith("err"):
                return
            first = first or self.view.message
        if first:
            self.view.message = first

    def start(self):
        self.send(refresh(self.view))

    def key(self, key):
        """A jog key, or while the guided calibration runs, a key of its (ENTER and ESC by name)."""
        if self.guide is not None:
            self.guide.key(key)
            self._guide_ended()
            return
        if key == "G":
            from hexapod_host.serial import guided  # guided takes jog's tables: imported once both exist

            self.guide = guided.Guide(self.link, self.error, self.progress, self.sleep)
            self.guide.start()
            self._guide_ended()
            return
        self.send(commands_for(self.view, key))

    def _guide_ended(self):
        """Back to the jog screen once the guide is done or quit, its last word in the status line."""
        g = self.guide
        if not g.over():
            return
        self.guide = None
        if not g.connected:
            self.view.connected = False
            self.view.error = True
            self.view.message = g.message
            return
        self.send(refresh(self.view))
        self.view.error = not g.started  # the board refused the start: shown as the err it is
        self.view.message = g.message

    def screen(self, port=""):
        """The lines to draw: the guide's while it runs, else the jog screen."""
        return self.guide.render() if self.guide is not None else render(self.view, port)

    def line(self, text):
        try:
            lines = typed(text)
        except ValueError as err:
            _refuse(self.view, str(err))
            return
        self.send(lines)
