"""Driving the virtual board from hexapod view in a real headless Chromium (Selenium): the page
loads without console errors, the stand button stands the board, W walks it (its PCA9685 models'
pulses change) and letting go stops it, a second tab is view-only. Everything is counted in the
board's own frames (the virtual board's trace: when a line arrived, when the models' pulses
changed, the robot's mode and walk), never in wall-clock time. Skips without Chromium (and
without the MicroPython VM); under CI a missing browser fails."""

import re

import pytest

from hexapod_host.view import browser as vb

STANDING, WALKING = 3, 4  # hexapod.tick.MODE_NAMES
PULSE_FRAMES = 2  # a walk that arrives in frame F moves the servos in frame F + 1 (the next tick)
STOP_FRAMES = 2  # the deadman: released = stopped within 2 frames
# then the feet come down: the tripod at 80 mm/s stopped at each of 200 phases (tests/scenarios
# Rig, robot.stop()) stood within 63 frames, the same before and after 2026-11-28's changes;
# +1: the frame the stop line arrives in (60 was one cycle and a margin, and failed at 61)
SETTLE_FRAMES = 64
STAND_FRAMES = 150  # stand from relaxed: about 56 frames here (a posture move at its servo speed)


@pytest.fixture(scope="module")
def drive(tmp_path_factory):
    """(driver, board, url): the page on a virtual board this test started with its trace."""
    vb.require()
    from hexapod_host.testing.runtimes import micropython_missing

    if micropython_missing():
        pytest.skip(micropython_missing())
    board = vb.VirtualBoard(tmp_path_factory.mktemp("drive") / "trace.txt")
    try:
        from hexapod_host.serial.link import Link

        # The front sonar hears nothing from the start (the virtual board's own fault command,
        # sent before the page takes the line): its beam must be drawn red.
        with Link.open(board.path) as link:
            assert link.request("fault no_echo 0") == "ok fault no_echo 0"
        with vb.driving(("--virtual", "--virtual-port", board.path)) as (driver, server):
            yield driver, board, server.url
    finally:
        board.stop()


text = vb.text  # the other browser test modules import it from here


def click(driver, element_id):
    from selenium.webdriver.common.by import By

    driver.find_element(By.ID, element_id).click()


def keys(driver, down=(), up=()):
    from selenium.webdriver.common.action_chains import ActionChains

    chain = ActionChains(driver)
    for k in down:
        chain.key_down(k)
    for k in up:
        chain.key_up(k)
    chain.perform()


def last_frame(board):
    ev = board.trace()
    return ev[-1][1] if ev else -1


def frames_pass(board, n, timeout=vb.HANG_S):
    """Wait until the board has run n more frames (its trace's heartbeat), not a wall-clock time."""
    start = last_frame(board)
    assert vb.wait_for(lambda: last_frame(board) >= start + n, timeout=timeout), "the board stopped running"


def modes(events, after=-1):
    """[(frame, mode, vx, vy, wz)] from the trace's M lines at frames >= after."""
    return [(f, *map(int, w)) for k, f, _, w in events if k == "M" and f >= after]


def pulse_frames(events, after=-1):
    return [f for k, f, _, _ in events if k == "P" and f >= after]


def stand(driver, board):
    n = len(vb.commands(board.trace(), "stand"))  # an earlier test's stand is not this one's
    # A socket that reconnected under load gives the drive back within a refresh: wait for it.
    assert vb.wait_for(lambda: "you drive" in text(driver, "drive-who")), text(driver, "drive-who")
    click(driver, "drive-stand")
    assert vb.wait_for(lambda: len(vb.commands(board.trace(), "stand")) > n), "no stand reached the board: %r" % text(
        driver, "drive-who"
    )
    f0 = vb.commands(board.trace(), "stand")[n][0]
    assert vb.wait_for(lambda: any(m[1] == STANDING for m in modes(board.trace(), f0))), (
        "the board did not reach standing"
    )
    return f0


def test_the_page_loads_without_console_errors(drive):
    driver, board, _ = drive
    frames_pass(board, 50)
    assert vb.page_errors(driver) == []
    assert driver.execute_script("return document.querySelector('#popup').getAttribute('aria-hidden')") == "true"
    # a live board runs on its own clock: no start, pause, step or speed (the simulator's, test_view_browser)
    assert driver.execute_script("return ['start', 'pause', 'step'].filter(i => document.getElementById(i))") == []
    # The board streams: the page shows `stream on 25`'s reply and counts telemetry lines.
    assert vb.wait_for(lambda: "(ok stream 25)" in text(driver, "drive-board")), text(driver, "drive-board")
    assert vb.wait_for(lambda: "telemetry lines 0 " not in text(driver, "drive-board"))


def red_pixels(driver):
    """Pixels of the faulted beam's red (#d62728 at 0.8 opacity on the light floor: about
    (205, 77, 78)) in the 3-D canvas: green and blue alike and well under red. The robot's
    oranges have far less blue than green, the floor and the grey beams all three alike."""
    import io

    from PIL import Image
    from selenium.webdriver.common.by import By

    png = driver.find_element(By.CSS_SELECTOR, ".nicegui-scene canvas").screenshot_as_png
    img = Image.open(io.BytesIO(png)).convert("RGB")
    w, h = img.size
    px = img.load()
    return sum(
        1
        for x in range(w)
        for y in range(h)
        for r, g, b in (px[x, y],)
        if r >= 150 and g <= 0.45 * r and abs(g - b) <= 0.1 * r
    )


def test_a_sonar_fault_turns_its_beam_red(drive):
    driver, _, _ = drive
    assert vb.wait_for(lambda: re.search(r"front\s+-\s+no_echo", text(driver, "readings"))), text(driver, "readings")
    assert red_pixels(driver) > 20  # the 150 mm beam, 8 mm thick: about 40-60 pixels here
    assert re.search(r"left front\s+400\.\d\s+ok", text(driver, "readings"))  # the others read their walls


def test_the_stand_button_stands_it(drive):
    driver, board, _ = drive
    f0 = stand(driver, board)
    ev = board.trace()
    standing = next(m[0] for m in modes(ev, f0) if m[1] == STANDING)
    assert standing - f0 <= STAND_FRAMES
    assert pulse_frames(ev, f0)[0] <= f0 + PULSE_FRAMES  # the servos moved from the next frame on
    # and the page, drawn from the board's telemetry, says so
    assert vb.wait_for(lambda: "robot standing" in text(driver, "status")), text(driver, "status")
    assert vb.page_errors(driver) == []


def test_w_walks_while_held_and_letting_go_stops_it(drive):
    driver, board, _ = drive
    stand(driver, board)
    n0 = len(vb.commands(board.trace(), "walk"))
    keys(driver, down="w")
    assert vb.wait_for(lambda: len(vb.commands(board.trace(), "walk")) > n0), "W sent no walk"
    first = vb.commands(board.trace(), "walk")[n0]
    assert first[2] == ["walk", "80", "0", "0"]
    fw = first[0]
    # The page, from the telemetry: walking, the walk in force.
    assert vb.wait_for(lambda: "robot walking" in text(driver, "status")), text(driver, "status")
    assert vb.wait_for(lambda: "walk 80 0 0," in text(driver, "drive-board")), text(driver, "drive-board")
    frames_pass(board, 120)  # held for 2.4 s of the board's time: more than twice the walk's 1000 ms timeout
    keys(driver, up="w")
    assert vb.wait_for(lambda: [c for c in vb.commands(board.trace(), "stop") if c[0] > fw]), (
        "letting go of W sent no stop"
    )
    fs = [c for c in vb.commands(board.trace(), "stop") if c[0] > fw][0][0]
    frames_pass(board, SETTLE_FRAMES + 10)
    ev = board.trace()
    # W -> the PCA9685 models' pulses change within PULSE_FRAMES of the walk's arrival
    assert pulse_frames(ev, fw + 1)[0] - fw <= PULSE_FRAMES
    # held: renewed, and never expired (the walk asked stays 80 0 0 from the walk to the stop)
    renewals = [c for c in vb.commands(ev, "walk")[n0:] if c[0] < fs]
    assert len(renewals) >= 4, renewals  # 2.4 s held, a renewal every 0.25 s: about 10
    assert all(c[2] == ["walk", "80", "0", "0"] for c in renewals)
    # A loaded machine can stall the page's server for over a second: then the board's own
    # timeout stops the walk (the deadman doing its job) until the next renewal. What must
    # never happen while W is held: the walk ending sooner than the timeout after a renewal.
    timeout_frames = 50  # the console's walk_timeout_ms, 1000 ms (boards/pico.py sets none)
    for f, _mode, *walk in modes(ev, fw):
        if f < fs and walk == [0, 0, 0]:
            last = max(c[0] for c in renewals if c[0] <= f)
            assert f - last >= timeout_frames, "the walk ended %d frames after a renewal, W held" % (f - last)
    # let go: stop; the walk asked is 0 0 0 within STOP_FRAMES, the feet down within a cycle
    zero = next(m[0] for m in modes(ev, fs) if m[2:] == (0, 0, 0))
    assert zero - fs <= STOP_FRAMES
    standing = next(m[0] for m in modes(ev, fs) if m[1] == STANDING)
    assert standing - fs <= SETTLE_FRAMES
    assert not pulse_frames(ev, standing + 1), "the servos still move after the robot stood"
    assert vb.page_errors(driver) == []


def test_the_window_losing_focus_stops_a_held_walk(drive):
    driver, board, _ = drive
    stand(driver, board)
    n0, s0 = len(vb.commands(board.trace(), "walk")), len(vb.commands(board.trace(), "stop"))
    keys(driver, down="w")
    assert vb.wait_for(lambda: len(vb.commands(board.trace(), "walk")) > n0), "W sent no walk"
    driver.execute_script("window.dispatchEvent(new Event('blur'))")  # as when another window takes the focus
    assert vb.wait_for(lambda: len(vb.commands(board.trace(), "stop")) > s0), "losing focus sent no stop"
    fs = vb.commands(board.trace(), "stop")[s0][0]
    frames_pass(board, 60)
    keys(driver, up="w")  # its keyup, late: nothing more to stop
    assert not [c for c in vb.commands(board.trace(), "walk") if c[0] > fs], "the walk was renewed after the blur"
    assert vb.page_errors(driver) == []


def test_the_stick_pushed_up_walks_and_let_go_stops(drive):
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By

    driver, board, _ = drive
    stand(driver, board)
    n0, s0 = len(vb.commands(board.trace(), "walk")), len(vb.commands(board.trace(), "stop"))
    stick = driver.find_element(By.ID, "drive-stick")
    ActionChains(driver).move_to_element(stick).click_and_hold().move_by_offset(0, -60).perform()  # up, to the rim
    # The stick's first move can be its centre (`walk 0 0 0`, then the push): wait for the push.
    assert vb.wait_for(
        lambda: [c for c in vb.commands(board.trace(), "walk")[n0:] if float(c[2][1]) > 60], timeout=30
    ), "the stick sent no forward walk: %s" % vb.commands(board.trace(), "walk")[n0:]
    words = [c for c in vb.commands(board.trace(), "walk")[n0:] if float(c[2][1]) > 60][0][2]
    assert abs(float(words[3])) < 5, words  # forward, hardly turning
    ActionChains(driver).release().perform()
    assert vb.wait_for(lambda: len(vb.commands(board.trace(), "stop")) > s0), "letting go sent no stop"
    assert vb.page_errors(driver) == []


def test_a_second_tab_is_view_only(drive):
    from selenium.webdriver.common.by import By

    driver, board, url = drive
    with vb.second_tab(driver, url):
        assert vb.wait_for(lambda: "view-only" in text(driver, "drive-who")), text(driver, "drive-who")
        assert not driver.find_element(By.ID, "drive-stand").is_enabled()
        n0 = len(vb.commands(board.trace(), "walk"))
        keys(driver, down="w")
        # The key reached the server and was refused there (the page's own widgets are disabled,
        # but the keyboard is the whole page's).
        assert vb.wait_for(lambda: "another tab drives" in text(driver, "drive-log"))
        frames_pass(board, 50)
        keys(driver, up="w")
        frames_pass(board, 50)
        assert len(vb.commands(board.trace(), "walk")) == n0, "a view-only tab made the board walk"
        assert vb.page_errors(driver) == []
    assert "you drive" in text(driver, "drive-who")


# A pretend gamepad in the page: navigator.getGamepads replaced by one that returns the test's pad
# (standard mapping: axes 0-3 the sticks, 17 buttons), whose axes the test then moves.
FAKE_PAD = """
window.hexapodPad = {connected: true, id: "test pad", mapping: "standard", axes: [0, 0, 0, 0],
                     buttons: Array.from({length: 17}, () => ({pressed: false, value: 0}))};
Object.defineProperty(navigator, "getGamepads", {configurable: true, value: () => [window.hexapodPad]});
"""
NO_PAD = 'Object.defineProperty(navigator, "getGamepads", {configurable: true, value: () => [null, null]});'


def test_a_gamepad_walks_while_off_centre_and_stops_centred_or_gone(drive):
    driver, board, _ = drive
    stand(driver, board)
    try:
        driver.execute_script(FAKE_PAD)
        n0 = len(vb.commands(board.trace(), "walk"))
        driver.execute_script("window.hexapodPad.axes = [0, -1, 0, 0]")  # left stick up, to the rim
        assert vb.wait_for(lambda: len(vb.commands(board.trace(), "walk")) > n0), "the pad sent no walk"
        fw, _, words = vb.commands(board.trace(), "walk")[n0]
        assert words == ["walk", "80", "0", "0"]
        # Held 10 s of the board's time, well past the server's PAD_STALE (12 renewals: 3 s, 5-6 s
        # at load 15): the page's reports while off-centre keep the pad held (no stop until it is
        # centred), and the walk is renewed.
        frames_pass(board, 500)
        s0 = len(vb.commands(board.trace(), "stop"))
        early = [c for c in vb.commands(board.trace(), "stop") if c[0] > fw]
        assert not early, "stopped at frame %d while the pad was held (walk at %d)" % (early[0][0], fw)
        driver.execute_script("window.hexapodPad.axes = [0, 0.05, 0, 0]")  # let go: back within the dead zone
        assert vb.wait_for(lambda: len(vb.commands(board.trace(), "stop")) > s0), "centred sent no stop"
        fs = vb.commands(board.trace(), "stop")[s0][0]
        frames_pass(board, SETTLE_FRAMES + 10)
        ev = board.trace()
        renewals = [c for c in vb.commands(ev, "walk")[n0:] if c[0] < fs]
        assert len(renewals) >= 4 and all(c[2] == ["walk", "80", "0", "0"] for c in renewals), renewals
        assert any(m[1] == WALKING and m[2:] == (800, 0, 0) for m in modes(ev, fw) if m[0] < fs)  # 0.1 mm/s
        zero = next(m[0] for m in modes(ev, fs) if m[2:] == (0, 0, 0))
        assert zero - fs <= STOP_FRAMES
        assert not [c for c in vb.commands(ev, "walk") if c[0] > fs], "a walk after the pad was centred"

        # The right stick turns; then the pad disconnects while held: stop.
        n1, s1 = len(vb.commands(ev, "walk")), len(vb.commands(ev, "stop"))
        driver.execute_script("window.hexapodPad.axes = [0, 0, 1, 0]")
        assert vb.wait_for(lambda: len(vb.commands(board.trace(), "walk")) > n1), "the turn sent no walk"
        assert vb.commands(board.trace(), "walk")[n1][2] == ["walk", "0", "0", "-20"]  # right turns right
        driver.execute_script(NO_PAD)
        assert vb.wait_for(lambda: len(vb.commands(board.trace(), "stop")) > s1), "gone sent no stop"
        fg = vb.commands(board.trace(), "stop")[s1][0]
        frames_pass(board, 50)
        assert not [c for c in vb.commands(board.trace(), "walk") if c[0] > fg], "a walk after the pad was gone"
        assert vb.page_errors(driver) == []
    finally:
        driver.execute_script(NO_PAD)


def test_the_height_control_refuses_outside_the_range_and_sends_a_height_inside(drive):
    from selenium.webdriver.common.by import By
    from selenium.webdriver.common.keys import Keys

    driver, board, _ = drive
    stand(driver, board)
    field = driver.find_element(By.CSS_SELECTOR, "input#drive-height")
    n0 = len(vb.commands(board.trace(), "height"))
    # One value below the range (both bounds: test_view_virtual's Driver test, no browser needed).
    field.send_keys(Keys.CONTROL, "a")
    field.send_keys("59")
    click(driver, "drive-height-set")
    assert vb.wait_for(
        lambda: "height 59.0 mm: allowed 60..100 (the robot file's range)" in text(driver, "drive-log"), timeout=30
    ), text(driver, "drive-log")
    # The standing height the board has (the robot file's 80.0 mm): the guard table answers it,
    # so the board's reply comes within a few frames (another height is checked for ~40 s of frames:
    # tests/test_console_height.py moves the feet).
    field.send_keys(Keys.CONTROL, "a")
    field.send_keys("80")
    click(driver, "drive-height-set")
    assert vb.wait_for(lambda: len(vb.commands(board.trace(), "height")) > n0), "no height reached the board"
    assert [w for _, _, w in vb.commands(board.trace(), "height")[n0:]] == [["height", "80.0"]]
    assert vb.wait_for(lambda: "ok height 80.0" in text(driver, "drive-log")), text(driver, "drive-log")
    assert vb.page_errors(driver) == []
