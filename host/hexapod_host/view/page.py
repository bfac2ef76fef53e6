"""The page (NiceGUI): the 3-D scene, the plots, the buttons. Every browser tab gets its own
elements and redraws them from the player's latest snapshot; the player steps the source in
the background (player.py). Scene units are metres (the snapshot's mm / 1000)."""

import json
import math
import time

from nicegui import ui

from hexapod_host.view import player as player_mod
from hexapod_host.view.drive import Driver
from hexapod_host.view.drive_ui import DrivePanel
from hexapod_host.view.pace import Pace
from hexapod_host.view.scene import geometry, segment_pose
from hexapod_host.view.support import support

PLOT_DRAW_S = 0.25
COLOURS = {
    "body": "#e07b00",
    "link": "#c05000",
    "stance": "#202020",
    "swing": "#6fa8dc",
    "ok": "#2ca02c",
    "none": "#9e9e9e",
    "fault": "#d62728",
    "wall": "#555555",
    "trail": "#1f77b4",
    "bracket": "#404040",
}
# The support polygon and the centre of mass by support.support's state: well inside, within
# support.NEAR_MM of an edge, outside, fewer than three feet down.
SUPPORT_COLOURS = {"ok": "#2ca02c", "near": "#ff9800", "out": "#d62728", "none": "#d62728"}
SUPPORT_RADIUS = 0.003
# The plots: title, then each series' name and its player.COLUMNS column. Every source gets the
# same plots; a value it does not have is a gap in the line and "-" in the title.
PLOTS = (
    ("side distance (mm)", (("front", "front_mm"), ("rear", "rear_mm"), ("set point", "setpoint_mm"))),
    ("PID", (("error (mm)", "error_mm"), ("output (deg/s)", "output_dps"))),
    ("walking speed (mm/s)", (("asked", "asked_mm_s"), ("body", "body_mm_s"))),
    ("battery (V)", (("battery", "battery_v"),)),
    ("frames per second (host clock)", (("frames/s", "frames_per_s"),)),
    ("firmware frame time (us)", (("last", "frame_us"), ("worst", "frame_us_max"))),
    ("loop counters", tuple((k, k) for k in player_mod.COUNTERS)),
)
COLUMN = {name: k for k, name in enumerate(player_mod.COLUMNS)}
# The plots' points live in the page: each look sends only the history rows added since the last
# (Player.new_rows), which the page appends to each series (x = the row's time, y = its column),
# dropping the oldest beyond `keep` (the history's length). Sending the whole window each time
# was ~2,500 points a look, and assigning into ui.echart's options wraps every point in NiceGUI's
# observable lists (5-90 ms a redraw on the shared machine). A chart not mounted yet is drawn
# once it is.
PLOTS_JS = """<script>
window.hexapodPlots = (charts, rows, fresh, keep) => {
  const store = (window.hexapodPlotData ||= {});
  const draw = (id) => {
    const el = getElement(id);
    if (!el) return; // gone with its page
    const s = store[id];
    if (!el.chart) { // ECharts not set up yet (a chart in a closed panel may never be): one retry
      // pending per chart, not one more chain of them at every look (those piled up to thousands
      // of timers a second and starved the page: WebDriver timeouts in the CI)
      if (!s.waiting) s.waiting = setTimeout(() => { s.waiting = 0; draw(id); }, 50);
      return;
    }
    el.chart.setOption({ title: { text: s.title }, series: s.data.map((d) => ({ data: d.slice() })) });
  };
  for (const [id, title, cols] of charts) {
    if (fresh || !store[id]) store[id] = { data: cols.map(() => []) };
    const s = store[id];
    s.title = title;
    for (const row of rows) cols.forEach((c, k) => s.data[k].push([row[0], row[c]]));
    for (const d of s.data) if (d.length > keep) d.splice(0, d.length - keep);
    draw(id);
  }
};
</script>"""
LINK_RADIUS = 0.006
TRAIL_CHUNK = 50  # trail points a point cloud holds (page.View._draw_trail)
BEAM_RADIUS = 0.004
CAMERA_BACK = (-0.55, -0.45, 0.45)  # the follow camera's place from the body centre, m (world axes)
SENSOR_NAMES = ("front", "left front", "left rear", "right front", "right rear")
LEGS = ("1 RF", "2 RM", "3 RR", "4 LR", "5 LM", "6 LF")


# Scene numbers are sent rounded to 0.1 mm (and rotations to 1e-4): a third of the bytes of a
# float's 17 digits, and what did not move by 0.1 mm is not sent again (NiceGUI sends a move,
# rotation or scale only when it changed; unrounded, the links' constant lengths "changed" in
# their last digits every redraw).
DIGITS = 4


def _m(p):
    """mm -> scene metres, rounded."""
    return [round(v / 1000, DIGITS) for v in p]


def _place(obj, start, end):
    """Pose a unit cylinder (or line) along y as the segment start -> end (mm). A segment where it
    was at the last redraw is skipped: not worked out again nor compared by NiceGUI's move,
    rotate and scale (a standing robot's links and brackets cost nothing a redraw)."""
    key = (*start, *end)
    if getattr(obj, "hexapod_segment", None) == key:
        return
    obj.hexapod_segment = key
    centre, rot, length = segment_pose([v / 1000 for v in start], [v / 1000 for v in end])
    obj.move(*(round(v, DIGITS) for v in centre))
    obj.rotate_R([[round(v, DIGITS) for v in row] for row in rot])
    obj.scale(1.0, max(round(length, DIGITS), 1e-6), 1.0)


class View:
    """One tab's elements and how they follow the player."""

    def __init__(self, player, driver, fps):
        self.player = player
        self.fps = fps  # the 3-D scene's redraws a second (hexapod view --fps)
        self.client = ui.context.client
        ui.add_body_html(PLOTS_JS)
        d = player.described
        # a board source's own name (board.py), the room's world, or both (a board's replay in a room)
        where = [d["board_said"]] if "board_said" in d else []
        if "world" in d or not where:
            where.append("world %s" % d.get("world", "-"))
        where = ", ".join(where)
        ui.label("hexapod view: %s, %s" % (d["source"], where)).classes("text-lg").props("id=title")
        self.status = ui.label().props("id=status")
        with ui.row().classes("w-full no-wrap"):
            self._scene(d)
            with ui.column():
                self.own_clock = driver.drivable  # a board runs on its own clock
                self._controls(live=self.own_clock)
                self.drive = DrivePanel(driver, lambda: self.player.snap)
                self.jog = _jog_panel(driver)
                self.table = ui.label().style("white-space: pre; font-family: monospace").props("id=readings")
        self._replay_timeline()
        self.live = ui.label().props("id=live").classes("font-mono text-sm")
        with ui.row().classes("w-full"):
            self.plots = [(self._plot(title, [n for n, _ in series]), title, series) for title, series in PLOTS]
        self.drawn = 0
        self.pace = Pace()
        ui.on("hexapod_drawn", lambda e: self.pace.shown(e.args))
        self._plotted = None  # Player.new_rows' mark: what this tab's plots have
        self._follow_player()
        self._plots_due = 0.0  # time.monotonic() of the next plots' redraw (in a scene's draw)
        self.draw()

    def _follow_player(self):
        """Redraw on the player's beat, right after each snapshot it publishes (25 a second), until
        the tab is gone. Not a ui.timer: its period is the interval plus the wait for the CPU, and
        on the loaded 2-core machine that wait cut the redraws to 12-15 a second while the
        player's fixed beat (player.run) held 25."""
        listeners = self.player.listeners
        listeners.append(self.draw)
        ui.context.client.on_delete(lambda: self.draw in listeners and listeners.remove(self.draw))

    def _replay_timeline(self):
        """A replay's slider (timeline.py), under the scene; nothing for a live source."""
        if hasattr(self.player.source, "seek"):
            from hexapod_host.view.timeline import Timeline

            self.timeline = Timeline(self.player)

    def _scene(self, d):
        xs = [v for w in d.get("walls", []) for v in (w[0], w[2])] or [0.0]
        ys = [v for w in d.get("walls", []) for v in (w[1], w[3])] or [0.0]
        size = math.ceil(max(map(abs, xs + ys)) / 1000 + 1) * 2
        with ui.scene(width=820, height=540, grid=(size, size * 10), background_color="#f4f4f4", fps=self.fps) as scene:
            self.scene = scene
            for x1, y1, x2, y2 in d.get("walls", []):
                length = math.hypot(x2 - x1, y2 - y1) / 1000
                wall = scene.box(length, 0.012, 0.15).material(COLOURS["wall"])
                wall.move((x1 + x2) / 2000, (y1 + y2) / 2000, 0.075).rotate(0, 0, math.atan2(y2 - y1, x2 - x1))
            if "finish" in d:
                f = d["finish"]
                scene.line([f[0] / 1000, f[1] / 1000, 0.001], [f[2] / 1000, f[3] / 1000, 0.001]).material("#888888")
            bx, by = d["body_half"]
            self.body = scene.box(2 * bx / 1000, 2 * by / 1000, 0.03).material(COLOURS["body"])
            self.links = [scene.cylinder(LINK_RADIUS, LINK_RADIUS, 1.0).material(COLOURS["link"]) for _ in range(18)]
            self.brackets = [scene.cylinder(0.004, 0.004, 1.0).material(COLOURS["bracket"]) for _ in d["brackets"]]
            self.feet = [scene.sphere(0.012).material(COLOURS["stance"]) for _ in range(6)]
            self.beams = [scene.cylinder(BEAM_RADIUS, BEAM_RADIUS, 1.0).material(COLOURS["ok"], 0.8) for _ in range(5)]
            self.support_edges = [scene.cylinder(SUPPORT_RADIUS, SUPPORT_RADIUS, 1.0) for _ in range(6)]
            self.com_ground = scene.cylinder(0.014, 0.014, 0.002).rotate(math.pi / 2, 0, 0)  # a flat disc
            self.com_plumb = scene.cylinder(0.0015, 0.0015, 1.0)  # from the centre of mass down
            self.com = scene.sphere(0.008)
            self.trails = []  # the trail's point clouds, TRAIL_CHUNK points each (_draw_trail)
            self.trail_n = 0
            self._camera = None  # where the follow camera was last put
            self._body_at = None  # the body's centre (mm) and yaw when last moved

    def _controls(self, live):
        """Start, pause, step and speed for a source the player steps (the simulator, a replay);
        a live board runs on its own clock: it has none of them."""
        p = self.player
        if not live:
            with ui.row():
                ui.button("start", on_click=p.start).props("id=start")
                ui.button("pause", on_click=p.pause).props("id=pause")
                ui.button("step", on_click=p.step).props("id=step")
            speeds = {s: "%gx" % s for s in player_mod.SPEEDS}
            ui.toggle(speeds, value=p.speed, on_change=lambda e: p.set_speed(e.value))
        self.follow_cam = ui.checkbox("follow camera", value=True)

    def _plot(self, title, names):
        series = [{"name": n, "type": "line", "showSymbol": False, "data": []} for n in names]
        return ui.echart(
            {
                "title": {"text": title, "left": 0, "textStyle": {"fontSize": 12}},
                "legend": {"top": 0, "right": 0},
                "animation": False,
                "xAxis": {"type": "value", "name": "s", "scale": True},
                "yAxis": {"type": "value", "scale": True},
                "series": series,
            }
        ).classes("w-[600px] h-56")

    def draw(self):
        if not self.pace.ready():
            return
        # One message for the whole scene instead of one per moved object (about 60): NiceGUI
        # 3.18.0's own batching (pinned), as its scene uses it to resend everything on a reconnect.
        with self.scene._batch_calls():
            self._draw_scene()
        self.drawn += 1
        self._status(self.player.snap)
        self._readings(self.player.snap)  # with the status line: one snapshot's frame and angles
        # The plots ride on a scene's draw, not on a timer of their own: paced with it (a timer's
        # redraws would queue behind a page that is behind).
        now = time.monotonic()
        if now >= self._plots_due:
            self._plots_due = now + PLOT_DRAW_S
            self.draw_plots()
        self.client.run_javascript('emitEvent("hexapod_drawn", %d)' % self.pace.sending())

    def _draw_scene(self):
        snap, p = self.player.snap, self.player
        g = geometry(p.described, snap)
        b = g["body"]
        yaw = round(b["yaw"], DIGITS)
        if (b["centre"], yaw) != self._body_at:  # rotate() works out a matrix before comparing
            self._body_at = (b["centre"], yaw)
            self.body.move(*_m(b["centre"])).rotate(0, 0, yaw)
        for obj, foot, down in zip(self.feet, g["feet"], g["stance"], strict=True):
            obj.move(*_m(foot)).material(COLOURS["stance" if down else "swing"])
        for obj, beam in zip(self.beams, g["beams"], strict=True):
            obj.material(COLOURS[beam["state"]], 0.8)
        objs = self.links + self.brackets + self.beams
        segments = g["links"] + g["brackets"] + [(beam["start"], beam["end"]) for beam in g["beams"]]
        support_objs, support_segments = self._draw_support(g["support"])
        for obj, (start, end) in zip(objs + support_objs, segments + support_segments, strict=True):
            _place(obj, start, end)
        self._draw_trail(p.trail)
        if self.follow_cam.value:
            cx, cy, _ = _m(b["centre"])
            dx, dy, dz = CAMERA_BACK
            camera = (round(cx + dx, DIGITS), round(cy + dy, DIGITS), dz, cx, cy, 0.0)
            if camera != self._camera:  # NiceGUI sends every move_camera, moved or not
                self._camera = camera
                self.scene.move_camera(*camera, duration=0)
        else:
            self._camera = None  # turned on again: the camera goes behind the body at once

    def _draw_trail(self, trail):
        """The body's trail (mm) in point clouds of TRAIL_CHUNK points: a new point resends only
        its own cloud. One cloud for the whole trail resent every point (every 5 mm, several
        times a second) grew with the trial: 400 points, ~25 kB a time, a minute in."""
        n, old = len(trail), self.trail_n
        if n == old:
            return
        if n < old:  # a new trial or a jump: it starts over
            old = 0
            for cloud in self.trails:
                cloud.set_points([])
        self.trail_n = n
        for k in range(old // TRAIL_CHUNK, (n - 1) // TRAIL_CHUNK + 1):
            if k == len(self.trails):
                with self.scene:
                    self.trails.append(self.scene.point_cloud([], point_size=0.01).material(COLOURS["trail"]))
            chunk = trail[k * TRAIL_CHUNK : (k + 1) * TRAIL_CHUNK]
            self.trails[k].set_points([[round(x / 1000, DIGITS), round(y / 1000, DIGITS), 0.002] for x, y in chunk])

    def _draw_support(self, sup):
        """The stance feet's polygon on the ground (edges 1 mm up, over the grid) and the centre of
        mass with its plumb line down to the ground, coloured by how far inside it is. The
        cylinders to place and their segments (the caller places them with the rest)."""
        colour = SUPPORT_COLOURS[sup["state"]]
        poly = [[x, y, 1.0] for x, y, _ in sup["polygon"]]
        n = len(poly) if len(poly) >= 3 else 0
        for k, edge in enumerate(self.support_edges):
            if k < n:
                edge.material(colour)
            edge.visible(k < n)
        down = sup["com_ground"][:2] + [1.0]
        self.com_ground.move(*_m(down)).material(colour)
        self.com.move(*_m(sup["com"])).material(colour)
        self.com_plumb.material(colour)
        segments = [(poly[k], poly[(k + 1) % n]) for k in range(n)] + [(sup["com"], down)]
        return self.support_edges[:n] + [self.com_plumb], segments

    def _status(self, s):
        f, x = s["follow"], s.get("extra", {})
        if self.own_clock:  # a board: no trial, and it runs whether or not the page looks
            played = ""
        elif self.player.running:
            played = "running  "
        else:
            played = ("done: %s  " % (x.get("why") or "success")) if self.player.done() else "paused  "
        trial = "trial %s  " % x["trial"] if "trial" in x else ""
        self.status.set_text(
            "%sframe %d  t %.2f s  %srobot %s  follower %s  updates %d  skipped %d"
            % (trial, s["frame"], s["time_s"], played, s["mode"], f["mode"], self.drawn, self.pace.skipped)
        )

    def _readings(self, s):
        f, x = s["follow"], s.get("extra", {})
        lines = ["sonar         reading   status"]
        for name, d, st in zip(SENSOR_NAMES, s["distances"], s["sonar_status"], strict=True):
            lines.append("%-12s %7s   %s" % (name, "-" if d is None else "%.1f" % d, st))
        lines.append("")
        lines.append("leg    coxa  femur  tibia (deg)")
        for i, name in enumerate(LEGS):
            a = s["angles"][3 * i : 3 * i + 3]
            lines.append("%-5s %6.1f %6.1f %6.1f" % (name, a[0] / 100, a[1] / 100, a[2] / 100))
        lines.append("")
        lines.append("PID error %.1f mm  output %.1f deg/s" % (f["error_mm"], f["output_dps"]))
        sup = support(s["legs"], s["stance"])
        lines.append(
            "feet down %d  support margin %s (%s)"
            % (len(sup["polygon"]), "-" if sup["margin_mm"] is None else "%.1f mm" % sup["margin_mm"], sup["state"])
        )
        if x.get("wall_mm") is not None:
            lines.append("true wall distance %.1f mm" % x["wall_mm"])
        lines.append(" ".join("%s %d" % kv for kv in s["counters"].items()))
        self.table.set_text("\n".join(lines))

    def draw_plots(self):
        """The plots: 4 times a second is enough to read them. Only the rows added since this tab's
        last look go out (Player.new_rows); the page keeps the points (PLOTS_JS); nothing when no
        row was added since."""
        h = self.player.history
        fresh, rows, self._plotted = self.player.new_rows(self._plotted)
        if not (fresh or rows):
            return
        last = h[-1] if h else None
        charts = []
        for chart, title, series in self.plots:
            cols = [COLUMN[c] for _, c in series]
            # The newest values in the title: "-" where the source has none (never a made-up 0).
            now = "  ".join(_value(last[c] if last else None) for c in cols)
            charts.append([chart.id, "%s: %s" % (title, now), cols])
        self.client.run_javascript("hexapodPlots(...%s)" % json.dumps([charts, rows, fresh, h.maxlen]))
        self.live.set_text(live_text(last))


def _value(v):
    return "-" if v is None else "%g" % v


def live_text(row):
    """The newest history row (player.COLUMNS) as one line, "-" for what the source lacks."""
    row = row or (None,) * len(player_mod.COLUMNS)
    v = dict(zip(player_mod.COLUMNS, map(_value, row), strict=True))
    return (
        "speed asked %(asked_mm_s)s mm/s, body %(body_mm_s)s mm/s  battery %(battery_v)s V  "
        "frames/s %(frames_per_s)s  frame %(frame_us)s us (worst %(frame_us_max)s)  "
        "overruns %(overruns)s  held %(held)s  bus_failed %(bus_failed)s  "
        "sonar_faults %(sonar_faults)s" % v
    )


def _jog_panel(driver):
    """The jog and calibrate panel (jog_ui.py) for a source with servos to jog; none for the simulator."""
    if not driver.drivable:
        return None
    from hexapod_host.view.jog_ui import JogPanel

    return JogPanel(driver)


def build(player, fps):
    """Register the page for this player's source; one Driver for every tab (one of them drives);
    the 3-D scene redraws fps times a second."""
    driver = Driver(player.source)

    @ui.page("/")
    def index():
        _log_tab(ui.context.client)
        View(player, driver, fps)


def _log_tab(client):
    """One line per tab event on the server's console: a tab that lost its socket and came back
    (or was forgotten, server.RECONNECT_S later) explains a page that stopped answering."""

    def say(what):
        print("view: tab %s %s" % (client.id[:8], what), flush=True)

    say("opened")
    # The page's side: why its socket went (socket.io's reason: ping timeout, transport close, ...).
    ui.add_body_html(
        "<script>(function hook() { if (!window.socket) return setTimeout(hook, 100);"
        ' window.socket.on("disconnect", (r) => console.log("socket lost: " + r)); })();</script>'
    )
    client.on_disconnect(lambda: say("lost its socket"))
    client.on_connect(lambda: say("connected"))
    client.on_delete(lambda: say("forgotten"))
