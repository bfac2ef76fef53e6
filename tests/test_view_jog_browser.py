"""Jog and calibrate the virtual board from hexapod view in a real headless Chromium (Selenium):
pick leg 2 tibia, put it at its reference, trim +10 us; the board's `cal 2 tibia` says trim 10,
its PCA9685 model moves that servo's pulse by the hand-worked amount in the frame after the trim
arrived, `save` answers ok and writes the row; a second tab cannot jog. Counted in the board's
own frames (the virtual board's trace), never in wall-clock time. The tests share one board
and run in any order (pytest-randomly): each reads the state it starts from. Skips without Chromium (and
without the MicroPython VM); under CI a missing browser fails.

Hand-worked pulses (boards/pico.py: leg 2 tibia on chip 0x40 channel 5, oscillator 25 MHz,
50 Hz): PRE_SCALE = round(25e6 / (4096 x 50)) - 1 = 121, so a count is 122 / 25 MHz = 4.88 us.
At the reference (-90 deg) the servo's pulse is centre_us 1500 (robots/default_cal.py): counts
round(1500 / 4.88) = round(307.38) = 307, which the model reads back as 307 x 4.88 = 1498.16 ->
1498 us. Trim +10: 1510 us, round(309.43) = 309 counts, 1507.92 -> 1508 us: 10 us more."""

import os
import re

import pytest

from hexapod_host.view import browser as vb
from tests.test_view_drive_browser import STANDING, WALKING, click, frames_pass, keys, modes, stand, text

ON_CI = os.environ.get("CI") not in (None, "", "false")
TIBIA_2 = 5  # the trace's channel: 0x40's 0-15 first (boards/pico.py: leg 2 tibia is 0x40 channel 5)
AT_REFERENCE_US, TRIMMED_US = 1498, 1508  # the model's widths, worked in the docstring
RELAXED = 0  # hexapod.tick.MODE_NAMES
NEXT_FRAMES = 2  # trim acts at once (docs/console.md): the pulse changes by the next frame's check


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    """(driver, board, url, cal_dir): the page on a virtual board (with a calibration directory)."""
    why = vb.missing()
    if why:
        if ON_CI:
            pytest.fail("CI runs the browser tests: " + why)
        pytest.skip(why)
    from hexapod_host.testing.runtimes import micropython_missing

    if micropython_missing():
        pytest.skip(micropython_missing())
    tmp = tmp_path_factory.mktemp("jog")
    cal_dir = tmp / "cal"
    cal_dir.mkdir()
    board = vb.VirtualBoard(tmp / "trace.txt", str(cal_dir))
    try:
        with vb.driving(("--virtual", "--virtual-port", board.path)) as (driver, server):
            yield driver, board, server.url, cal_dir
    finally:
        board.stop()


def pick(driver, toggle, label):
    from selenium.webdriver.common.by import By

    buttons = driver.find_elements(By.CSS_SELECTOR, "#%s button" % toggle)
    [b for b in buttons if b.text.strip().lower() == label][0].click()


def trim_shown(driver):
    """The trim of the cal line the panel shows for leg 2 tibia (the board's reply), or None."""
    m = re.search(r"cal    tibia: centre 1500 at -90\.00 deg trim ([+-]\d+) dir \+1 ", text(driver, "jog-text"))
    return int(m.group(1)) if m else None


def files(folder):
    return {p.name: p.read_bytes() for p in folder.iterdir()}


def arrived(board, words):
    """Frames at which the console line `words` (the tag skipped) arrived."""
    return [f for f, _, w in vb.commands(board.trace(), words.split()[0]) if w == words.split()]


def wait_line(board, words, before, timeout=vb.HANG_S):
    """The frame at which `words` arrived for the (before + 1)th time: before is the count taken
    before the click (an earlier test's same line is not this one's)."""
    assert vb.wait_for(lambda: len(arrived(board, words)) > before, timeout=timeout), (
        "%r never reached the board; its %r lines: %r"
        % (
            words,
            words.split()[0],
            vb.commands(board.trace(), words.split()[0])[-5:],
        )
    )
    return arrived(board, words)[before]


def widths(events, channel, after=-1):
    """[(frame, us)] of the trace's P lines that changed channel, at frames >= after."""
    out = []
    for kind, frame, _, words in events:
        if kind == "P" and frame >= after:
            for w in words:
                k, _, us = w.partition("=")
                if int(k) == channel:
                    out.append((frame, int(us)))
    return out


def relaxed(driver, board):
    """Relax the robot (a maker calibrates it relaxed and supported) unless it is already: an
    earlier test may have left it standing."""
    if [m[1] for m in modes(board.trace())][-1:] in ([], [RELAXED]):
        return
    assert vb.wait_for(lambda: "you drive" in text(driver, "drive-who")), text(driver, "drive-who")
    click(driver, "drive-relax")
    assert vb.wait_for(lambda: [m[1] for m in modes(board.trace())][-1:] == [RELAXED])


def test_trim_leg_2_tibia_moves_its_pulse_and_save_keeps_it(page):
    driver, board, _, cal_dir = page
    relaxed(driver, board)
    n_cal, n_ref = len(arrived(board, "cal 2 tibia")), len(arrived(board, "joint 2 tibia -90.00"))
    pick(driver, "jog-leg", "2")
    pick(driver, "jog-joint", "tibia")
    click(driver, "jog-read")  # a pick of the leg and joint in hand already sends nothing
    wait_line(board, "cal 2 tibia", n_cal)
    click(driver, "jog-ref")
    f_ref = wait_line(board, "joint 2 tibia -90.00", n_ref)
    assert vb.wait_for(lambda: trim_shown(driver) == 0), text(driver, "jog-text")
    frames_pass(board, 5)
    assert widths(board.trace(), TIBIA_2, f_ref)[-1][1] == AT_REFERENCE_US
    n_cal, n_trim = len(arrived(board, "cal 2 tibia")), len(arrived(board, "trim 2 tibia 10"))
    click(driver, "jog-trim-plus")  # the us step is 10 to start
    f_trim = wait_line(board, "trim 2 tibia 10", n_trim)
    # the panel shows the board's own cal line, asked after the trim
    assert vb.wait_for(lambda: len(arrived(board, "cal 2 tibia")) > n_cal), "no cal after the trim"
    assert vb.wait_for(lambda: trim_shown(driver) == 10), text(driver, "jog-text")
    frames_pass(board, 5)
    moved = widths(board.trace(), TIBIA_2, f_trim)
    assert moved and moved[0][1] == TRIMMED_US, moved
    assert moved[0][0] - f_trim <= NEXT_FRAMES
    assert TRIMMED_US - AT_REFERENCE_US == 10
    # only that servo moved: no other channel changed since the reference
    others = [w for k, f, _, ws in board.trace() if k == "P" and f > f_ref for w in ws if not w.startswith("5=")]
    assert others == []
    assert not arrived(board, "trim 1 tibia 10") and not arrived(board, "trim 3 tibia 10")
    n_save = len(arrived(board, "save"))
    click(driver, "jog-save")
    wait_line(board, "save", n_save)
    assert vb.wait_for(lambda: "save: ok saved" in text(driver, "jog-text")), text(driver, "jog-text")
    saved = (cal_dir / "hexapod_cal.txt").read_text()
    assert "2 tibia 10 1 600 2400" in saved
    assert vb.page_errors(driver) == []


def test_a_trim_the_board_refuses_shows_its_err_and_changes_nothing(page):
    """While walking the console refuses a trim (docs/console.md): the panel shows the board's
    err, asks nothing after it, and the board's cal line is as it was."""
    driver, board, _, _ = page
    pick(driver, "jog-leg", "2")
    pick(driver, "jog-joint", "tibia")
    click(driver, "jog-read")
    # +10 when the trim test ran first (the order is random)
    assert vb.wait_for(lambda: trim_shown(driver) is not None), text(driver, "jog-text")
    trim = trim_shown(driver)
    stand(driver, board)
    n_walk = len(vb.commands(board.trace(), "walk"))
    keys(driver, down="w")
    try:
        assert vb.wait_for(lambda: len(vb.commands(board.trace(), "walk")) > n_walk), "W sent no walk"
        f_walk = vb.commands(board.trace(), "walk")[n_walk][0]
        assert vb.wait_for(lambda: any(m[1] == WALKING for m in modes(board.trace(), f_walk)))
        n_cal, n_trim = len(arrived(board, "cal 2 tibia")), len(arrived(board, "trim 2 tibia %d" % (trim + 10)))
        click(driver, "jog-trim-plus")
        f_trim = wait_line(board, "trim 2 tibia %d" % (trim + 10), n_trim)
        assert vb.wait_for(lambda: "ERROR trim 2 tibia %d: " % (trim + 10) in text(driver, "jog-text")), text(
            driver, "jog-text"
        )
        frames_pass(board, 10)
        assert len(arrived(board, "cal 2 tibia")) == n_cal  # nothing asked after the err
        n_stop = len(arrived(board, "stop"))
    finally:
        keys(driver, up="w")
    f_stop = wait_line(board, "stop", n_stop)
    assert f_stop > f_trim
    # The feet finish their cycle after a stop: the next test starts from a robot standing still.
    assert vb.wait_for(lambda: any(m[1] == STANDING for m in modes(board.trace(), f_stop)))
    click(driver, "jog-read")
    assert vb.wait_for(lambda: len(arrived(board, "cal 2 tibia")) > n_cal)
    assert vb.wait_for(lambda: trim_shown(driver) == trim), text(driver, "jog-text")
    assert vb.page_errors(driver) == []


def test_the_guided_calibration_starts_and_quits_from_the_page(page):
    driver, board, _, cal_dir = page
    saved = files(cal_dir)
    # Not walking (the board refuses `relax` then, and the guide would end at once: test_guided)
    assert vb.wait_for(lambda: [m[1] for m in modes(board.trace())][-1:] != [WALKING])
    n_relax = len(vb.commands(board.trace(), "relax"))
    n_fit = len(arrived(board, "pulse 1 coxa 1500"))
    click(driver, "jog-guided")
    assert vb.wait_for(lambda: "leg 1 coxa  step: fit" in text(driver, "jog-text")), text(driver, "jog-text")
    assert len(vb.commands(board.trace(), "relax")) > n_relax  # it starts by relaxing every servo
    f_fit = wait_line(board, "pulse 1 coxa 1500", n_fit)  # the fit step: the reference pulse
    frames_pass(board, 5)
    assert widths(board.trace(), 0, f_fit)[-1][1] == AT_REFERENCE_US  # leg 1 coxa: 0x40 channel 0
    click(driver, "guide-quit")
    assert vb.wait_for(lambda: "quit, nothing saved" in text(driver, "jog-text")), text(driver, "jog-text")
    assert files(cal_dir) == saved
    assert vb.page_errors(driver) == []


def test_a_second_tab_cannot_jog(page):
    from selenium.webdriver.common.by import By

    driver, board, url, _ = page
    with vb.second_tab(driver, url):
        assert vb.wait_for(lambda: "view-only: another tab jogs" in text(driver, "jog-text")), text(driver, "jog-text")
        for element_id in ("jog-trim-plus", "jog-deg-plus", "jog-save", "jog-guided"):
            assert not driver.find_element(By.ID, element_id).is_enabled(), element_id
        n = len(vb.commands(board.trace(), "trim"))
        driver.execute_script("document.getElementById('jog-trim-plus').click()")  # a click anyway
        frames_pass(board, 50)
        assert len(vb.commands(board.trace(), "trim")) == n, "a view-only tab trimmed a servo"
        assert vb.page_errors(driver) == []
    shot = os.environ.get("HEXAPOD_JOG_SCREENSHOT")
    if shot:  # for looking at the panel by eye (docs/view.md)
        driver.find_element(By.ID, "jog-text").location_once_scrolled_into_view  # noqa: B018
        driver.save_screenshot(shot)
