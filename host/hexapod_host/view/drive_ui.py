"""The page's drive panel (NiceGUI): keys, stick, buttons, gait, wall following, and the last
commands with their replies. The logic is drive.Driver's; this file only wires widgets to it.
The same panel for every source: one that cannot be driven (the simulator) gets it disabled."""

from nicegui import ui

from hexapod import gait
from hexapod_host.view.drive import RENEW_S, WALL_CM, NotOwner

REFRESH_S = 0.25  # the panel's text and who-drives, this often
PAD_POLL_MS = 50  # the page reads the gamepad this often (the Gamepad API has no move events)
# The page's side of the gamepad: the first connected pad of navigator.getGamepads() (standard
# mapping: axes 0-3 the sticks, button 1 the east face button, 6 and 7 the triggers), rounded to
# 0.02, reported to the server (Driver.gamepad) when it changes and every RENEW_S while a stick
# or trigger is off its rest (the server's deadman lets go of a pad whose reports stop); null when
# there is none. The mapping to a walk is the server's (drive._pad_velocity).
PAD_JS = """<script>
(() => {
  let last = "", sent = 0;
  const r = (v) => Math.round((v || 0) * 50) / 50;
  setInterval(() => {
    // Not before NiceGUI's app is mounted (emitEvent needs it: an error in the console otherwise).
    if (typeof emitEvent !== "function" || typeof mounted_app === "undefined" || !mounted_app) return;
    const pads = navigator.getGamepads ? Array.from(navigator.getGamepads() || []) : [];
    const p = pads.find((g) => g && g.connected);
    let state = null;
    if (p) {
      const b = (k) => (p.buttons[k] ? r(p.buttons[k].value || (p.buttons[k].pressed ? 1 : 0)) : 0);
      state = {axes: [0, 1, 2, 3].map((k) => r(p.axes[k])), lt: b(6), rt: b(7), stop: b(1)};
    }
    const text = JSON.stringify(state), now = performance.now();
    const off = state && (state.axes.some((v) => Math.abs(v) > 0.1) || state.lt > 0.1 || state.rt > 0.1);
    if (text !== last || (off && now - sent >= %d)) {
      last = text;
      sent = now;
      emitEvent("hexapod_pad", state);
    }
  }, %d);
})();
</script>""" % (RENEW_S * 1000, PAD_POLL_MS)


def _key_name(code):
    """The browser's key code as Driver's key name: KeyW -> 'w', Space -> ' ' (the key's place
    on the keyboard, not its letter: a shifted W is still W)."""
    if code == "Space":
        return " "
    return code[3:].lower() if code.startswith("Key") else ""


class DrivePanel:
    def __init__(self, driver, snap=None):
        self.driver = driver
        self.snap = snap  # () -> the player's latest snapshot, for the board's line
        self.client = client = ui.context.client
        self.error = ""
        with ui.card().classes("w-[420px]"):
            self.who = ui.label().props("id=drive-who").classes("font-bold")
            self.board = ui.label().props("id=drive-board").classes("text-xs")
            self.widgets = []
            with ui.row():
                for line in ("stand", "sit", "relax", "stop"):
                    self.widgets.append(
                        ui.button(line, on_click=lambda _e, line=line: self._do(driver.command, line)).props(
                            "id=drive-%s" % line
                        )
                    )
            with ui.row().classes("items-center"):
                self.gait = ui.select(list(gait.NAMES), value=None, label="gait").classes("w-32").props("id=drive-gait")
                self.gait.on_value_change(lambda e: e.value and self._do(driver.command, "gait " + e.value))
                self.widgets.append(self.gait)
                lo, hi = driver.heights_mm
                self.height = ui.number("height (mm)", value=None, min=lo, max=hi, step=5, format="%.1f")
                self.height.classes("w-28").props("for=drive-height")  # QInput gives its input this id
                set_height = ui.button("set", on_click=lambda: self._do(driver.height, self.height.value))
                self.widgets += [self.height, set_height.props("id=drive-height-set")]
            with ui.row().classes("items-center"):
                self.side = ui.select(["left", "right"], value="left", label="wall side").classes("w-28")
                self.cm = ui.number("set point (cm)", value=12, min=WALL_CM[0], max=WALL_CM[1], step=0.5)
                self.cm.classes("w-32")
                on = ui.button("follow wall", on_click=lambda: self._do(driver.wall, self.side.value, self.cm.value))
                off = ui.button("wall off", on_click=lambda: self._do(driver.wall, None, None))
                self.widgets += [self.side, self.cm, on.props("id=drive-wall"), off.props("id=drive-wall-off")]
            ui.label(
                "keys: W/S forward/back, A/D strafe, Q/E turn, space stops; or the stick; or a gamepad "
                "(left stick walks, right stick or triggers turn, B stops)"
            ).classes("text-xs")
            self.stick = (
                ui.joystick(
                    color="#e07b00",
                    size=100,
                    mode="static",  # nipple.js's default draws the stick only once touched: an empty box
                    position={"left": "50%", "top": "50%"},
                    on_move=lambda e: self._do(driver.stick_move, e.x, e.y),
                    on_end=lambda e: self._do(driver.stick_move, None, None),
                )
                .classes("w-40 h-40")
                .props("id=drive-stick")
            )
            self.log = ui.label().style("white-space: pre; font-family: monospace; font-size: 11px")
            self.log.style("overflow-x: auto; max-width: 100%")  # a long reply scrolls in the card
            self.log.props("id=drive-log")
        # Keys drive whatever is focused but a text field (a clicked button is blurred, _do).
        ui.keyboard(on_key=self._key, repeating=False, ignore=["input", "select", "textarea"])
        # A key held while the window loses focus never sends its keyup: let go of it then.
        ui.add_body_html('<script>window.addEventListener("blur", () => emitEvent("hexapod_blur"));</script>')
        ui.on("hexapod_blur", lambda: self.driver.owner == client.id and self._do(driver.let_go))
        ui.add_body_html(PAD_JS)
        ui.on("hexapod_pad", lambda e: self.driver.owner == client.id and self._pad(e.args))
        ui.timer(RENEW_S, self._renew)
        ui.timer(REFRESH_S, self.refresh)
        # A tab without its socket (reloaded, network lost) neither drives nor claims until it is
        # back: its panel's timers run on until the server forgets it (server.RECONNECT_S).
        self.connected = True
        client.on_connect(lambda: setattr(self, "connected", True))
        client.on_disconnect(self._gone)
        client.on_delete(lambda: driver.release(client.id))
        self.refresh()

    def _gone(self):
        # A socket that reconnected before the old one was reaped keeps the tab connected: NiceGUI
        # clears the tab only when no socket is left (has_socket_connection).
        self.connected = self.client.has_socket_connection
        self.driver.release(self.client.id)

    def _do(self, fn, *args):
        try:
            fn(self.client.id, *args)
            self.error = ""
            # A focused button would take the next space as its own click (a `relax` instead of a stop).
            ui.run_javascript("document.activeElement && document.activeElement.blur()")
        except (NotOwner, ValueError) as e:
            self.error = str(e)
        self.refresh()

    def _pad(self, state):
        """A gamepad report: no blur (unlike a click), it comes 4 times a second while held."""
        try:
            self.driver.gamepad(self.client.id, state)
            self.error = ""
        except (NotOwner, ValueError) as e:
            self.error = str(e)

    def _key(self, e):
        name = _key_name(e.key.code)
        if name and (e.action.keydown or e.action.keyup) and not e.action.repeat:
            self._do(self.driver.key, name, e.action.keydown)

    def _renew(self):
        if self.driver.owner == self.client.id:
            self.driver.renew()

    def refresh(self):
        d = self.driver
        owns = d.claim(self.client.id, self.connected)  # a freed drive goes to the next tab that looks
        if not d.drivable:
            who = "this source cannot be driven"
        elif owns:
            who = "you drive: W/A/S/D, Q/E, space stops"
        else:
            who = "view-only: another tab drives"
        self.who.set_text(who)
        for w in self.widgets:
            w.set_enabled(owns)
        self.stick.set_visibility(owns)
        x = self.snap().get("extra", {}) if self.snap else {}
        if "stream" in x:
            v = x.get("walk") or [0, 0, 0]
            lost = "; " + x["lost"] if x.get("lost") else ""
            self.board.set_text(
                "%s: gait %s, walk %g %g %g, telemetry lines %d (%s)%s"
                % (x.get("board", "board"), x.get("gait"), *v, x.get("telemetry_lines", 0), x["stream"], lost)
            )
        lines = []
        if owns:
            for tag, line in d.sent[-4:]:
                lines.append("%-16s %s" % (line, d.source.reply(tag) or "..."))
        if self.error:
            lines.append("refused: " + self.error)
        self.log.set_text("\n".join(lines))
