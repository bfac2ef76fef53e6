"""The page's jog and calibrate panel (NiceGUI): leg and joint picks, nudges, trim, direction,
save, the guided calibration's buttons, and what the board answered. The logic is jog.Jogger's;
this file only wires widgets to it. Each step runs in a worker thread (it waits for the board's
replies): the page's event loop never waits for the board."""

from nicegui import run, ui

from hexapod_host.serial.guided import ACTIONS
from hexapod_host.serial.jog import JOINTS, STEPS_US
from hexapod_host.view.drive import NotOwner
from hexapod_host.view.jog import LEGS, STEPS_DEG, jogger_for

REFRESH_S = 0.25
# The guided step buttons' id attributes: guide-<key>, but for the keys NiceGUI's props parser
# drops an id with (`id=guide-<` leaves the button with no id at all).
GUIDE_IDS = {"<": "step-down", ">": "step-up", "+": "plus", "-": "minus"}


def guide_id(key):
    """The id attribute of the guided step's button for key (guided.ACTIONS' keys)."""
    return "guide-" + GUIDE_IDS.get(key, key.lower())


class JogPanel:
    def __init__(self, driver):
        self.driver = driver
        self.jog = j = jogger_for(driver)
        self.client = ui.context.client
        self.error = ""
        self.picking = 0  # picks clicked and not yet taken by the jogger (refresh leaves the toggles be)
        self.widgets = []
        with ui.card().classes("w-[420px]"):
            ui.label("jog and calibrate").classes("font-bold")
            with ui.row().classes("items-center"):
                self.leg = ui.toggle(list(LEGS), value=j.view.leg).props("id=jog-leg dense no-caps")
                self.joint = ui.toggle(list(JOINTS), value=JOINTS[j.view.joint]).props("id=jog-joint dense no-caps")
                self.leg.on_value_change(self._pick)
                self.joint.on_value_change(self._pick)
                self.widgets += [self.leg, self.joint]
            with ui.row().classes("items-center"):
                self.deg = ui.select(list(STEPS_DEG), value=STEPS_DEG[j.step_deg], label="deg").classes("w-16")
                self._button("joint -", "jog-deg-minus", lambda c: j.nudge(c, -1, self.deg.value))
                self._button("joint +", "jog-deg-plus", lambda c: j.nudge(c, 1, self.deg.value))
                self._button("reference", "jog-ref", j.reference)
                self.widgets.append(self.deg)
            with ui.row().classes("items-center"):
                self.us = ui.select(list(STEPS_US), value=10, label="us").classes("w-16").props("id=jog-us")
                self._button("pulse -", "jog-pulse-minus", lambda c: j.pulse(c, -1, self.us.value))
                self._button("pulse +", "jog-pulse-plus", lambda c: j.pulse(c, 1, self.us.value))
                self._button("trim -", "jog-trim-minus", lambda c: j.trim(c, -1, self.us.value))
                self._button("trim +", "jog-trim-plus", lambda c: j.trim(c, 1, self.us.value))
                self.widgets.append(self.us)
            with ui.row():
                self._button("flip direction", "jog-dir", j.flip)
                self._button("save", "jog-save", j.save)
                self._button("read", "jog-read", j.refresh)
                self._button("guided calibration", "jog-guided", lambda c: j.guided(c, "G"))
            self.guide_row = ui.row()
            self.text = ui.label().props("id=jog-text")
            self.text.style("white-space: pre; font-family: monospace; font-size: 11px")
            self.text.style("overflow-x: auto; max-width: 100%")  # the cal line is wider than the card
        self.phase = None
        ui.timer(REFRESH_S, self.refresh)
        self.refresh()

    def _button(self, label, element_id, fn):
        b = ui.button(label, on_click=lambda: self._do(fn)).props("id=%s dense no-caps" % element_id)
        self.widgets.append(b)
        return b

    async def _do(self, fn):
        try:
            await run.io_bound(fn, self.client.id)
            self.error = ""
        except (NotOwner, ValueError) as e:
            self.error = str(e)
        self.refresh()

    async def _pick(self, _e=None):
        v = self.jog.view
        if self.jog.guide is not None or (self.leg.value, self.joint.value) == (v.leg, JOINTS[v.joint]):
            return  # the guide's redo pick, or the refresh setting the toggles to the shared state
        leg, joint = self.leg.value, self.joint.value  # as clicked
        # Until the jogger has it, the view still holds the old pick: a refresh in between (its
        # timer) reset the toggles to it, and a second click (the joint after the leg) then took
        # the old leg with it: the page sent `cal 1 tibia` for leg 2 on a loaded machine.
        self.picking += 1
        try:
            await self._do(lambda c: self.jog.pick(c, leg, joint))
        finally:
            self.picking -= 1

    def _guide_buttons(self, phase):
        """The guided step's buttons (guided.ACTIONS), rebuilt when the phase changes."""
        self.phase = phase
        self.guide_row.clear()
        self.guide_widgets = []
        if phase is None:
            return
        j = self.jog
        with self.guide_row:
            for _keys, what, buttons in ACTIONS.get(phase, ()):
                for key, label in buttons:
                    b = ui.button(label, on_click=lambda key=key: self._do(lambda c: j.guided(c, key)))
                    # the title attribute, not ui.tooltip: a tooltip in a row cleared on the next
                    # phase logs "Anchor: target not found" errors in the page's console
                    b.props('id=%s dense no-caps title="%s"' % (guide_id(key), what))
                    self.guide_widgets.append(b)
            if phase == "stand":
                b = ui.button("redo leg/joint picked", on_click=lambda: self._do(self._redo))
                self.guide_widgets.append(b.props("id=guide-redo dense no-caps"))
            b = ui.button("quit guide", on_click=lambda: self._do(lambda c: j.guided(c, "ESC")))
            self.guide_widgets.append(b.props("id=guide-quit dense no-caps"))

    def _redo(self, client):
        self.jog.redo(client, self.leg.value, self.joint.value)

    def refresh(self):
        j, d = self.jog, self.driver
        owns = d.owner == self.client.id
        guide = j.guide
        phase = guide.phase if guide is not None else None
        if phase != self.phase:
            self._guide_buttons(phase)
        v = j.view
        moved = (self.leg.value, self.joint.value) != (v.leg, JOINTS[v.joint])
        if guide is None and not self.picking and not j.busy.locked() and moved:
            self.leg.value, self.joint.value = v.leg, JOINTS[v.joint]  # another step (or the guide) moved them
        for w in self.widgets:
            w.set_enabled(owns and (guide is None or w in (self.leg, self.joint)))
        for w in getattr(self, "guide_widgets", ()):
            w.set_enabled(owns)
        lines = j.lines()
        if not owns:
            lines = ["view-only: another tab jogs" if d.drivable else "this source cannot be jogged", *lines]
        if self.error:
            lines.append("refused: " + self.error)
        self.text.set_text("\n".join(lines))
