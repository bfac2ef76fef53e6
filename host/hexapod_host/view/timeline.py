"""The replay's timeline on the page: where the recording is, and a slider to scrub it (the
page's start, pause, step and speed buttons work on a replay as on the simulator)."""

from nicegui import ui

TIMELINE_DRAW_S = 0.25  # the slider follows the replay 4 times a second


class Timeline:
    """A slider over the player's replay source (replay.ReplaySource), seconds from its start."""

    def __init__(self, player):
        self.player = player
        src = player.source
        self._following = False  # True while the slider is moved to follow the replay, not by a hand
        with ui.column().classes("w-full"):
            self.label = ui.label().props("id=timeline-label")
            self.slider = (
                ui.slider(min=0.0, max=max(src.duration_s, 0.02), step=0.02, value=src.clock_s, on_change=self._moved)
                .props("id=timeline label")
                .classes("w-[800px]")
            )
        ui.timer(TIMELINE_DRAW_S, self.draw)
        self.draw()

    def _moved(self, e):
        if not self._following:
            self.player.seek(e.value)

    def draw(self):
        src = self.player.source
        self.label.set_text(
            "replay %s  t %.2f of %.2f s  snapshot %d of %d%s"
            % (
                src.path,
                src.clock_s,
                src.duration_s,
                src.index + 1,
                len(src),
                "  (end of the recording)" if src.done() else "",
            )
        )
        if abs(self.slider.value - src.clock_s) > 1e-6:
            self._following = True
            try:
                self.slider.set_value(round(src.clock_s, 2))
            finally:
                self._following = False
