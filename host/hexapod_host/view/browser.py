"""A headless Chromium on the view, for the browser tests and `hexapod bench view`: the server
started in its own process on a free port, the page driven by Selenium through Debian's
chromium and chromium-driver (`make test` installs them when it can), WebGL by SwiftShader."""

import contextlib
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import time
import weakref

CHROMIUM = ("chromium", "chromium-browser", "google-chrome")
DRIVER = "chromedriver"
FLAGS = ("--headless=new", "--no-sandbox", "--use-gl=swiftshader", "--enable-unsafe-swiftshader")
WINDOW = (1500, 1100)
# The scene's redraws a second in the tests' pages (`hexapod view --fps`): SwiftShader's redraws
# hold the page's main thread, and at the product's 20 a second WebDriver's commands waited ~1 s
# each on a loaded 2-core machine (0.1 s at 5). A test of the page, not of its frame rate; the
# view bench keeps the product's default (fps=None).
TEST_FPS = 5
# A hang guard, not a time limit: a wait that is met returns at once, and this bound only ends a
# test that would otherwise hang. 30 s expired once in a fresh-clone CI run on a loaded 2-core
# machine (the suite took 16.6 min there instead of ~7), waiting for a reply that came.
HANG_S = 600


def chromium():
    """Paths of (browser, driver), either None when missing."""
    browser = next((p for p in map(shutil.which, CHROMIUM) if p), None)
    return browser, shutil.which(DRIVER)


def missing():
    """Why no browser test can run here, or None."""
    browser, driver = chromium()
    if browser is None or driver is None:
        return "no %s (apt-get install chromium chromium-driver; `make test` does it as root)" % (
            "chromium" if browser is None else "chromedriver"
        )
    try:
        import selenium  # noqa: F401
    except ImportError:
        return "no selenium (pip install -r requirements.txt)"
    return None


def require():
    """For a test: skip it, saying why, when no browser test can run here; under CI (CI set and
    not "false") fail it instead, since CI runs the browser tests."""
    import pytest

    why = missing()
    if why:
        if os.environ.get("CI") not in (None, "", "false"):
            pytest.fail("CI runs the browser tests: " + why)
        pytest.skip(why)


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


_LIVE = []  # the servers running now, for diagnose()
_BROWSERS = weakref.WeakSet()  # the browsers opened, for diagnose()


def diagnose(lines=30):
    """What a failed browser test should show (tests/conftest.py adds it to the report): the last
    lines of each live server's log and each open page's console, a test's only window on a
    socket lost under load. Reading a console empties it: page_errors() sees only later entries."""
    out = []
    for server in _LIVE:
        out.append("server %s:" % server.url)
        out += ["  " + line for line in server.log().splitlines()[-lines:]]
    for driver in list(_BROWSERS):
        try:
            entries = driver.get_log("browser")
        except Exception:  # a browser that quit has nothing more to say
            continue
        out += ["console: %s %s" % (e["level"], e["message"]) for e in entries[-lines:]]
    return "\n".join(out)


class Server:
    """`hexapod view ARGS --no-browser` in a subprocess on 127.0.0.1:port (pythonpath: the
    host package to import instead of this one; fps: its --fps, None for the view's own
    default; timeout: seconds to start listening, HANG_S unless given); stop() ends it."""

    def __init__(self, args=("--sim",), port=None, timeout=None, pythonpath=None, fps=TEST_FPS):
        timeout = HANG_S if timeout is None else timeout
        self.port = port or free_port()
        self.url = "http://127.0.0.1:%d/" % self.port
        self.output = None  # what the server printed, once stopped
        # A file, not a pipe: a pipe nobody reads until stop() fills (64 KiB) and then blocks the
        # server's event loop in its next print, the page's socket with it.
        fd, self._log_path = tempfile.mkstemp(prefix="hexapod-view-", suffix=".log")
        os.close(fd)
        cmd = [
            sys.executable,
            "-m",
            "hexapod_host",
            "view",
            *args,
            *(("--fps", str(fps)) if fps else ()),
            "--no-browser",
            "--listen",
            "127.0.0.1:%d" % self.port,
        ]
        # NiceGUI takes PYTEST_CURRENT_TEST as its own test mode (another port): the server is a plain run.
        env = {k: v for k, v in os.environ.items() if k != "PYTEST_CURRENT_TEST"}
        if pythonpath:  # another tree's host package (the bench's before/after), ahead of this one
            env["PYTHONPATH"] = pythonpath
        with open(self._log_path, "a") as log:  # O_APPEND: the server's writes and log()'s reads never race
            self.proc = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT, text=True, env=env)
        _LIVE.append(self)
        end = time.monotonic() + timeout
        while True:
            if self.proc.poll() is not None:
                raise RuntimeError("hexapod view stopped (exit %s): %s" % (self.proc.returncode, self.log()))
            try:
                socket.create_connection(("127.0.0.1", self.port), timeout=1).close()
                return
            except OSError:
                if time.monotonic() > end:
                    self.stop()
                    raise RuntimeError(
                        "hexapod view did not listen on port %d within %d s" % (self.port, timeout)
                    ) from None
                time.sleep(0.2)

    def stop(self):
        """Stop the server (again: nothing more); everything it printed."""
        if self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait(10)
        if self.output is None:
            self.output = self.log()
            os.unlink(self._log_path)
            _LIVE.remove(self)
        return self.output

    def log(self):
        """What the server printed so far."""
        if self.output is not None:
            return self.output
        with open(self._log_path) as f:
            return f.read()


def open_browser():
    """A headless Chromium under WebDriver that keeps the page's console log (goog:loggingPrefs)."""
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    browser, driver = chromium()
    options = webdriver.ChromeOptions()
    options.binary_location = browser
    for flag in FLAGS + ("--window-size=%d,%d" % WINDOW,):
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    browser = webdriver.Chrome(options=options, service=Service(driver, log_output=os.devnull))
    _BROWSERS.add(browser)
    return browser


def page_errors(driver):
    """The page's console entries at level SEVERE (errors); the GPU driver's performance
    warnings under SwiftShader are WARNING and are not the page's."""
    return [e for e in driver.get_log("browser") if e["level"] == "SEVERE"]


def text(driver, element_id):
    """The text of the page's element element_id, "" while it is missing or being redrawn."""
    from selenium.common.exceptions import NoSuchElementException, StaleElementReferenceException
    from selenium.webdriver.common.by import By

    try:
        return driver.find_element(By.ID, element_id).text
    except (NoSuchElementException, StaleElementReferenceException):
        return ""


@contextlib.contextmanager
def driving(args, timeout=None, fps=TEST_FPS):
    """(driver, server): `hexapod view ARGS` served (up within timeout s, HANG_S unless given) and
    open in headless Chromium, this tab the one that drives; the browser quits and the server
    stops after."""
    server = Server(args, timeout=timeout, fps=fps)
    driver = None
    try:
        driver = open_browser()
        driver.get(server.url)
        if not wait_for(lambda: "you drive" in text(driver, "drive-who")):
            raise AssertionError("the page never gave this tab the drive: %r" % text(driver, "drive-who"))
        yield driver, server
    finally:
        if driver is not None:
            driver.quit()
        server.stop()


@contextlib.contextmanager
def second_tab(driver, url):
    """driver in a new tab on url (the page a second visitor sees); after, that tab is closed and
    the first one current again, whatever happened in between."""
    first = driver.current_window_handle
    driver.switch_to.new_window("tab")
    try:
        driver.get(url)
        yield
    finally:
        driver.close()
        driver.switch_to.window(first)


def wait_for(predicate, timeout=None, every=0.1):
    """predicate()'s first true value within timeout seconds (HANG_S unless given), else None."""
    end = time.monotonic() + (HANG_S if timeout is None else timeout)
    while True:
        v = predicate()
        if v or time.monotonic() > end:
            return v
        time.sleep(every)


class VirtualBoard:
    """`hexapod virtual-board` (pico, default robot) with its trace file (virtual_board.py's Trace):
    what the board saw, counted in its own frames. stop() ends it."""

    def __init__(self, trace_path, cal_dir=""):
        from hexapod_host.commands.console import start_virtual_board

        self.trace_path = str(trace_path)
        self._events, self._read = [], 0  # parsed so far, and up to which byte of the file
        self.proc, self.path, self._master, self._slave = start_virtual_board(
            "pico", "default", cal_dir, trace=self.trace_path
        )

    def trace(self):
        """The trace so far: (kind, frame, t_ns, words) per event, oldest first. Only what the
        board wrote since the last call is parsed: tests poll this many times a second while
        the file grows by a frame's lines every 20 ms."""
        try:
            with open(self.trace_path, "rb") as f:
                f.seek(self._read)
                chunk = f.read()
        except FileNotFoundError:
            chunk = b""
        end = chunk.rfind(b"\n") + 1  # a line being written is read next time
        for line in chunk[:end].decode().splitlines():
            kind, frame, t_ns, *words = line.split()
            self._events.append((kind, int(frame), int(t_ns), words))
        self._read += end
        return list(self._events)

    def stop(self):
        from hexapod_host.commands.console import stop_virtual_board

        stop_virtual_board(self.proc, self._master, self._slave)


def commands(events, word):
    """The console lines whose command is word (the tag skipped): [(frame, t_ns, words)]."""
    out = []
    for kind, frame, t_ns, words in events:
        if kind == "L":
            w = words[1:] if words and words[0].startswith("#") else words
            if w[:1] == [word]:
                out.append((frame, t_ns, w))
    return out
