"""hexapod view in a real headless Chromium (Selenium, SwiftShader WebGL): the page loads
without console errors, the 3-D canvas shows the robot where it stands, the pose moves while
the simulator runs, and pause/step hold and advance it. Skips, saying why, without Chromium and
its driver (`make test` installs them as root); under CI a missing browser fails."""

import io
import re
import time

import pytest

from hexapod_host.view import browser as vb


@pytest.fixture(scope="module")
def page():
    """(driver, server) with the page loaded and its first frames drawn."""
    vb.require()
    from selenium.webdriver.common.by import By

    server = vb.Server(("--sim", "--speed", "0.5"))  # a trial lasts 90 s: fewer races with its end
    driver = vb.open_browser()
    try:
        driver.get(server.url)
        assert vb.wait_for(lambda: frame(driver) > 0), "the page never showed a frame"
        assert driver.find_element(By.CSS_SELECTOR, ".nicegui-scene canvas")
        yield driver, server
    finally:
        driver.quit()
        server.stop()


def status(driver):
    from selenium.common.exceptions import NoSuchElementException, StaleElementReferenceException
    from selenium.webdriver.common.by import By

    try:
        return driver.find_element(By.ID, "status").text
    except (NoSuchElementException, StaleElementReferenceException):
        return ""


def frame(driver):
    m = re.search(r"frame (\d+)", status(driver))
    return int(m.group(1)) if m else -1


def canvas(driver):
    """The 3-D canvas as a PIL image."""
    from PIL import Image
    from selenium.webdriver.common.by import By

    png = driver.find_element(By.CSS_SELECTOR, ".nicegui-scene canvas").screenshot_as_png
    return Image.open(io.BytesIO(png)).convert("RGB")


def robot_orange(p):
    """The body and links' colour (#e07b00, #c05000) under the scene's light: red well above green
    well above blue. Walls and floor are grey, beams green, the trail blue, the feet black or pale blue."""
    r, g, b = p
    return r >= 120 and 0.25 * r <= g <= 0.75 * r and b <= 0.35 * r


def orange_pixels(img, box):
    x0, y0, x1, y1 = box
    px = img.load()
    return [(x, y) for x in range(x0, x1) for y in range(y0, y1) if robot_orange(px[x, y])]


def click(driver, element_id):
    from selenium.webdriver.common.by import By

    driver.find_element(By.ID, element_id).click()


def test_the_page_loads_without_console_errors(page):
    driver, _ = page
    time.sleep(1)  # a second of live updates: an error in a redraw would show by now
    assert vb.page_errors(driver) == []
    assert driver.execute_script("return document.querySelector('#popup').getAttribute('aria-hidden')") == "true", (
        "the page shows 'Connection lost'"
    )


def test_the_robot_is_drawn_where_it_stands(page, tmp_path):
    driver, _ = page
    # The scene's objects reach the canvas after the first frame's text does (a busy machine shows
    # the gap): wait until anything robot-coloured is drawn, then look where it is.
    drawn = vb.wait_for(lambda: orange_pixels(canvas(driver), (0, 0, 820, 540)))
    assert drawn, "no robot-coloured pixel in the canvas after 60 s"
    img = canvas(driver)
    w, h = img.size
    assert (w, h) == (820, 540)
    # The follow camera looks at the body centre: the robot is in the middle of the canvas.
    middle = orange_pixels(img, (w // 3, h // 3, 2 * w // 3, 2 * h // 3))
    everywhere = orange_pixels(img, (0, 0, w, h))
    img.save(tmp_path / "canvas.png")  # to look at when this fails
    assert len(middle) > 2000, "only %d robot-coloured pixels in the canvas' middle third" % len(middle)
    assert len(middle) >= 0.95 * len(everywhere)  # nothing robot-coloured off where the robot stands
    corner = img.getpixel((2, 2))
    assert max(corner) - min(corner) < 8 and min(corner) > 200  # the light grey background, not a blank canvas


def test_the_pose_changes_while_the_sim_runs(page):
    driver, _ = page
    for _ in range(3):  # a trial that ends between the two pictures freezes the robot: the next one
        click(driver, "start")
        assert vb.wait_for(lambda: "running" in status(driver)), status(driver)
        f0, a = frame(driver), canvas(driver)
        assert vb.wait_for(lambda f0=f0: frame(driver) >= f0 + 25), "the simulator did not step"
        b = canvas(driver)
        if "running" in status(driver):
            break
    w, h = a.size
    box = (w // 3, h // 3, 2 * w // 3, 2 * h // 3)
    changed = set(orange_pixels(a, box)) ^ set(orange_pixels(b, box))
    assert len(changed) > 100, "the robot looks the same %d frames later" % (frame(driver) - f0)


def test_pause_holds_the_frame_and_step_advances_it_by_one(page):
    driver, _ = page
    for _ in range(3):  # a finished trial cannot be paused or stepped: the next one
        click(driver, "start")
        assert vb.wait_for(lambda: "running" in status(driver)), status(driver)
        click(driver, "pause")
        assert vb.wait_for(lambda: re.search("paused|done", status(driver))), status(driver)
        if "paused" in status(driver):
            break
    held = frame(driver)
    time.sleep(0.5)
    assert frame(driver) == held
    click(driver, "step")
    assert vb.wait_for(lambda: frame(driver) == held + 1), status(driver)
    click(driver, "start")
    assert vb.wait_for(lambda: frame(driver) > held + 5), status(driver)
    assert vb.page_errors(driver) == []


# --- replay: a recording played back shows the recorded angles at the recorded frame ---

LEG_ROW = re.compile(r"^\d \w\w\s+(-?\d+\.\d)\s+(-?\d+\.\d)\s+(-?\d+\.\d)$", re.M)


def shown_angles(driver):
    """The 18 joint angles in the page's readings table, degrees as printed (0.1)."""
    from selenium.webdriver.common.by import By

    rows = LEG_ROW.findall(driver.find_element(By.ID, "readings").text)
    return [float(v) for row in rows for v in row]


def recorded(path):
    """{frame: 18 angles in degrees to 0.1} read from the file with the mcap package's reader."""
    import json

    from mcap.reader import make_reader

    with open(path, "rb") as f:
        snaps = [json.loads(m.data) for _, _, m in make_reader(f).iter_messages(topics=["/hexapod/snapshot"])]
    return {s["frame"]: [float("%.1f" % (a / 100)) for a in s["angles"]] for s in snaps}


def settled(driver):
    """(frame, angles) once two readings half a second apart agree (the table redraws 4 times a second)."""
    last = None
    for _ in range(40):
        now = (frame(driver), shown_angles(driver))
        if now == last and len(now[1]) == 18:
            return now
        last = now
        time.sleep(0.5)
    raise AssertionError("the page did not settle: %r" % (last,))


@pytest.fixture(scope="module")
def replay_page(tmp_path_factory):
    vb.require()
    from hexapod_host.view.player import Player
    from hexapod_host.view.record import Recorder
    from hexapod_host.view.sim import SimSource
    from hexapod_host.wall import world

    path = str(tmp_path_factory.mktemp("replay") / "walk.mcap")
    ticks = iter(range(10**9))
    src = SimSource(world.load("wall"), 12, seed=0)
    p = Player(src, recorder=Recorder(path, src.describe(), clock=lambda: 40_000_000 * next(ticks)))
    for _ in range(200):  # 8 s of recording, frames 0..400, 40 ms apart
        p.advance(0.04)
    p.stop()
    server = vb.Server(("--replay", path, "--speed", "0.5"))
    driver = vb.open_browser()
    try:
        driver.get(server.url)
        assert vb.wait_for(lambda: frame(driver) >= 0 and shown_angles(driver)), "no frame shown"
        yield driver, recorded(path)
    finally:
        driver.quit()
        server.stop()


def test_a_paused_replay_shows_the_recorded_angles_at_its_frame(replay_page):
    driver, angles = replay_page
    click(driver, "pause")
    f, shown = settled(driver)
    assert f in angles, "frame %d is not in the recording" % f
    assert shown == angles[f]
    assert any(abs(a) > 1 for a in shown)  # not a blank table


def test_scrubbing_the_timeline_shows_the_recorded_angles(replay_page):
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By

    driver, angles = replay_page
    click(driver, "pause")
    slider = driver.find_element(By.ID, "timeline")
    for fraction in (0.75, 0.25):
        # A click at that fraction of the slider's width seeks there: 8 s of recording, 400 frames.
        x = int(slider.size["width"] * (fraction - 0.5))
        ActionChains(driver).move_to_element_with_offset(slider, x, 0).click().perform()
        expect = int(400 * fraction)
        assert vb.wait_for(lambda e=expect: abs(frame(driver) - e) <= 40), (frame(driver), expect)
        f, shown = settled(driver)
        assert f in angles and shown == angles[f], (f, shown)
    assert "paused" in status(driver)


def test_a_replay_played_to_its_end_shows_its_last_frame(replay_page):
    driver, angles = replay_page
    click(driver, "start")
    assert vb.wait_for(lambda: "done" in status(driver)), status(driver)
    f, shown = settled(driver)
    assert f == 400 and shown == angles[400]
    assert vb.page_errors(driver) == []
