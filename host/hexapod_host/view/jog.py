"""Jog and calibrate from the page (docs/view.md, "Jog and calibrate"): the browser counterpart of
`hexapod jog`, built on the jog tool's own pieces, not a copy of them:

- the view and its replies: serial/jog.py's View, commands_for (the pulse, reference, trim,
  direction and save lines) and apply (the `get` and `cal` replies into the view);
- the guided calibration: serial/guided.py's Guide, run by serial/jog.py's Jog ('G' starts it,
  its keys go to it), the buttons from guided.ACTIONS.

What is the page's own: a joint nudge in degrees (`joint L J DEG` from the angle the board last
reported), the leg and joint picked as values rather than keys, and `get L` then `cal L J` after
every step, so the panel always shows the calibration line the board holds.

Every line goes out through the Driver (drive.py): only the driving tab may jog, the same rule
as for walking, and the line is tagged and kept in the drive log like any other. The page never
waits in its event loop: Jogger's methods block until the board has answered (or REPLY_S passed)
and the panel calls them in a worker thread. A refused command (`err`) stops the step there: the
board changed nothing, the panel shows its reply and sends nothing after it.
"""

import threading
import time
import weakref

from hexapod_host.serial import guided
from hexapod_host.serial import jog as tool
from hexapod_host.serial.guided import centidegrees, degrees

REPLY_S = 10.0  # a reply later than this: the line is taken as lost
POLL_S = 0.01
BUSY_S = 30.0  # a step waits this long for the one before (the guide's relax polls, a sweep)
STEPS_DEG = ("0.5", "1", "2", "5")  # joint nudges, degrees: sent as typed (no float rounds them)
LEGS = (1, 2, 3, 4, 5, 6)


class NoReply(Exception):
    """The board did not answer a line within REPLY_S (or the tab lost the drive mid-step)."""


class TabLink:
    """serial/jog.Jog's link (request(line) -> reply) over the Driver for one tab at a time."""

    def __init__(self, driver):
        self.driver = driver
        self.client = None  # the tab the step in hand is for

    def request(self, line):
        from hexapod_host.view.drive import NotOwner

        try:
            tag = self.driver.command(self.client, line)
        except NotOwner as e:
            raise NoReply(str(e)) from None
        end = time.monotonic() + REPLY_S
        while True:
            reply = self.driver.source.reply(tag)
            if reply is not None and reply != "working":
                return reply
            if time.monotonic() > end:
                raise NoReply("no reply to %r within %g s" % (line, REPLY_S))
            time.sleep(POLL_S)


class Jogger:
    """One board's jog state, shared by every tab (one of them drives)."""

    def __init__(self, driver, pause=time.sleep, progress=None):
        """pause: the guide's wait between sweep steps (tests: none); progress None: the page keeps
        no progress file (the terminal's --progress does)."""
        self.driver = driver
        self.link = TabLink(driver)
        self.tool = tool.Jog(self.link, NoReply, progress, pause)
        self.step_deg = 1  # index into STEPS_DEG
        self.busy = threading.Lock()  # one step on the line at a time, in the order clicked

    @property
    def view(self):
        return self.tool.view

    @property
    def guide(self):
        return self.tool.guide

    def _run(self, client, step, in_guide=False):
        """Run step() for client: the owner check first (nothing changes for another tab), one step
        at a time; a jog step waits while the guided calibration runs (it holds the servos)."""
        self.driver.check(client)
        if not in_guide and self.guide is not None:
            raise ValueError("the guided calibration runs: quit it first")
        # Steps queue behind the one on the line (two quick picks: leg, then joint), not refused.
        if not self.busy.acquire(timeout=BUSY_S):
            raise ValueError("the last step is still on the line after %g s: try again" % BUSY_S)
        try:
            self.link.client = client
            self.tool.view.connected = True  # a lost reply is not a lost board: the next step tries again
            step()
        finally:
            self.busy.release()

    def _send(self, lines):
        """lines, then `get L` and `cal L J` (unless already there): stops at the first err."""
        v = self.view
        lines = list(lines) + [x for x in tool.refresh(v) if x not in lines]
        self.tool.send(lines)

    def _key(self, key, step_us=None):
        """A jog tool key's lines (serial/jog.commands_for), then the refresh; refused keys send nothing."""
        if step_us is not None:
            self.view.step_us = tool.STEPS_US.index(step_us)
        lines = tool.commands_for(self.view, key)
        if lines:
            self._send(lines)

    # -- the panel's steps (client: the tab's id) --------------------------------------------------

    def pick(self, client, leg, joint):
        """Pick leg (1-6) and joint (coxa, femur, tibia): read its leg line and calibration."""
        if leg not in LEGS:
            raise ValueError("leg %r: allowed 1-6" % (leg,))
        if joint not in tool.JOINTS:
            raise ValueError("joint %r: allowed %s" % (joint, ", ".join(tool.JOINTS)))

        def step():
            v = self.view
            if (v.leg, v.joint) != (leg, tool.JOINTS.index(joint)):
                v.leg, v.joint = leg, tool.JOINTS.index(joint)
                v.angles = v.pulses = v.foot = v.cal = None
            self._send([])

        self._run(client, step)

    def nudge(self, client, sign, step_deg):
        """The joint by +-step_deg degrees from the angle the board last reported (`joint L J DEG`)."""
        if step_deg not in STEPS_DEG:
            raise ValueError("step %r deg: allowed %s" % (step_deg, ", ".join(STEPS_DEG)))

        def step():
            v = self.view
            leg, joint = v.leg, tool.JOINTS[v.joint]
            if not v.pulses or not v.pulses[v.joint]:
                tool._refuse(v, "leg %d %s is limp: put it at its reference first" % (leg, joint))
                return
            angle = centidegrees(v.angles[v.joint]) + sign * centidegrees(step_deg)
            self._send(["joint %d %s %s" % (leg, joint, degrees(angle))])

        self._run(client, step)

    def reference(self, client):
        """The joint to its reference angle (the cal line's ref_deg), where a trim is judged."""
        self._run(client, lambda: self._key("0"))

    def pulse(self, client, sign, step_us):
        self._run(client, lambda: self._key("]" if sign > 0 else "[", step_us))

    def trim(self, client, sign, step_us):
        self._run(client, lambda: self._key("}" if sign > 0 else "{", step_us))

    def flip(self, client):
        self._run(client, lambda: self._key("d"))

    def save(self, client):
        self._run(client, lambda: self._key("s"))

    def refresh(self, client):
        self._run(client, lambda: self._send([]))

    # -- the guided calibration ----------------------------------------------------------------------

    def guided(self, client, key):
        """A key of the guided procedure ('G' starts it; then guided.ACTIONS' keys, ESC quits)."""
        if key != "G" and self.guide is None:
            raise ValueError("the guided calibration is not running (start it first)")
        if key == "G" and self.guide is not None:
            raise ValueError("the guided calibration runs already")
        self._run(client, lambda: self.tool.key(key), in_guide=True)

    def redo(self, client, leg, joint):
        """At the standing check: redo one servo (the guide's n, then the leg, then c f t)."""
        if leg not in LEGS or joint not in tool.JOINTS:
            raise ValueError("leg %r joint %r: allowed 1-6 and %s" % (leg, joint, ", ".join(tool.JOINTS)))

        def step():
            for key in ("n", str(leg), joint[0]):
                self.tool.key(key)

        self._run(client, step, in_guide=True)

    # -- what the panel shows --------------------------------------------------------------------------

    def lines(self):
        """The panel's text: the guide's screen while it runs (its keys are buttons), else the leg and cal lines."""
        g = self.guide
        if g is not None:
            keys = set(guided.KEYS.get(g.phase, ()))
            return [x for x in g.render() if x not in keys and not x.startswith("Esc q")]
        return tool.render(self.view)[1:6]


_JOGGERS = weakref.WeakKeyDictionary()


def jogger_for(driver):
    """The one Jogger of a driver's board (every tab's panel shows and steps the same one)."""
    j = _JOGGERS.get(driver)
    if j is None:
        j = _JOGGERS[driver] = Jogger(driver)
    return j
