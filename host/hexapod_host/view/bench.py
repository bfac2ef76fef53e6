"""`hexapod bench view`: how fast the view goes with the simulator, measured three ways.

- cost: CPU ms of one simulator frame, and of one snapshot turned into scene geometry;
- player: the background task alone for PLAYER_S seconds at 1x: snapshots published per
  second and simulated seconds per real second;
- page: the server in its own process and a headless Chromium on the page for PAGE_S seconds:
  redraws that reached the browser per second (the page's own counter, read from its text),
  simulated seconds per real second, and the server's CPU time over the window (Linux's
  /proc) per redraw and as a share of one core: the figure that least follows the machine's
  load. Skipped, saying why, without Chromium.
- drive: `hexapod view --virtual` on a virtual board with its trace, W pressed DRIVE_TRIES times
  in headless Chromium: the time from the key (just before WebDriver sends it) to the first
  frame in which the board's PCA9685 models' pulses changed (the trace's host clock), median
  and worst; the same in the board's frames from the walk's arrival; key -> walk line arrival;
  and the page's own keydown (the event's time in the browser) -> walk line arrival, which
  leaves out WebDriver's way into a busy browser. Skipped, saying why, without Chromium or the
  MicroPython VM.

The machine's load average is reported beside them: on a shared 2-core machine the figures
follow it.
"""

import asyncio
import json
import os
import re
import subprocess
import sys
import time

from hexapod_host.view import browser as vb
from hexapod_host.view.player import Player
from hexapod_host.view.scene import geometry
from hexapod_host.view.sim import SimSource
from hexapod_host.wall.world import load

FRAMES = 500
PLAYER_S = 5.0
PAGE_S = 10.0
DRIVE_TRIES = 10
PARTS_UPDATES = 1000
COMPARE_ROUNDS = 3
# Where the server's CPU goes per update, without a browser or a websocket: one tab built by
# NiceGUI's simulated user on the simulator's corridor trial at 1x, each part's own CPU time
# (time.process_time, which the machine's load does not stretch) over N updates after 600 frames:
# the simulator's two frames, the snapshot (the player's publish), the tab's 3-D redraw and its
# plots and readings (4 times a second: every 6.25th update, so their cost / 6.25 an update). A
# script, not an import: `compare` runs it on another tree's host package as well.
PARTS_SCRIPT = r"""
import asyncio, json, os, sys, time
os.environ["PYTEST_CURRENT_TEST"] = "bench"  # NiceGUI's user simulation outside pytest takes its root for a script
from nicegui.testing.user_simulation import user_simulation
from hexapod_host.view import page
from hexapod_host.view.player import Player
from hexapod_host.view.sim import SimSource
from hexapod_host.wall.world import load

N = int(sys.argv[1])
views = []

def root():
    player = Player(SimSource(load("corridor"), 12, seed=0))
    views.append(page.View(player, page.Driver(player.source)))

async def main():
    async with user_simulation(root=root) as user:
        await user.open("/")
        view = views[0]
        player = view.player
        player.listeners.clear()  # each part timed on its own below
        for _ in range(600):
            player.source.step()
        cpu = time.process_time
        step = snap = draw = plots = 0.0
        for k in range(N):
            t0 = cpu()
            player.source.step()
            player.source.step()
            t1 = cpu()
            player.publish()
            t2 = cpu()
            view.draw()
            t3 = cpu()
            if k % 25 in (0, 6, 12, 19):  # 4 of 25 updates: 4 times a second at 25 updates a second
                view.draw_plots()
            t4 = cpu()
            step, snap, draw, plots = step + t1 - t0, snap + t2 - t1, draw + t3 - t2, plots + t4 - t3
            await asyncio.sleep(0)  # NiceGUI's outbox and tasks run between updates, as in the server
        ms = lambda v: round(1000 * v / N, 3)
        print(json.dumps({"updates": N, "step_ms": ms(step), "snapshot_ms": ms(snap), "draw_ms": ms(draw),
                          "plots_ms": ms(plots), "update_ms": ms(step + snap + draw + plots)}))
        player.stop()

asyncio.run(main())
"""


def _cost():
    src = SimSource(load("wall"), 12, seed=0)
    try:
        t = time.perf_counter()
        for _ in range(FRAMES):
            src.step()
        frame_ms = (time.perf_counter() - t) * 1000 / FRAMES
        described = src.describe()
        t = time.perf_counter()
        for _ in range(FRAMES):
            geometry(described, src.snapshot())
        snap_ms = (time.perf_counter() - t) * 1000 / FRAMES
    finally:
        src.close()
    return {"sim_frame_ms": round(frame_ms, 3), "snapshot_and_geometry_ms": round(snap_ms, 3)}


def _player():
    p = Player(SimSource(load("wall"), 12, seed=0))

    async def run_for(seconds):
        task = asyncio.ensure_future(p.run())
        await asyncio.sleep(seconds)
        p._stopped = True
        await task

    u0, f0, t = p.updates, p.frames, time.monotonic()
    asyncio.run(run_for(PLAYER_S))
    dt = time.monotonic() - t
    p.stop()
    return {
        "seconds": round(dt, 2),
        "updates_per_s": round((p.updates - u0) / dt, 1),
        "sim_speed": round((p.frames - f0) * p.source.frame_s / dt, 3),
    }


def _status(driver):
    from selenium.webdriver.common.by import By

    try:
        text = driver.find_element(By.ID, "status").text
    except Exception:  # a page between reloads has no status yet
        return None
    m = re.search(r"frame (\d+).*updates (\d+)", text)
    return (int(m.group(1)), int(m.group(2))) if m else None


def _cpu_s(pid):
    """User + system CPU seconds of a process so far, None where /proc is not there."""
    try:
        with open("/proc/%d/stat" % pid) as f:
            fields = f.read().rsplit(")", 1)[1].split()
    except OSError:
        return None
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def _page(pythonpath=None):
    why = vb.missing()
    if why:
        return {"skipped": why}
    # a long trial: it runs on for the whole window
    server = vb.Server(("--sim", "--world", "corridor"), pythonpath=pythonpath, fps=None)
    driver = vb.open_browser()
    try:
        driver.get(server.url)
        vb.wait_for(lambda: _status(driver), timeout=60)
        time.sleep(2)  # past the first load
        a, t0, c0 = _status(driver), time.monotonic(), _cpu_s(server.proc.pid)
        time.sleep(PAGE_S)
        b, t1, c1 = _status(driver), time.monotonic(), _cpu_s(server.proc.pid)
        errors = len(vb.page_errors(driver))
    finally:
        driver.quit()
        server.stop()
    if a is None or b is None or b[1] < a[1]:
        return {"failed": "the page reloaded or lost its status during the window"}
    dt, redraws = t1 - t0, b[1] - a[1]
    out = {
        "load_average_1min": round(os.getloadavg()[0], 2),
        "seconds": round(dt, 2),
        "redraws_per_s": round(redraws / dt, 1),
        "sim_speed": round((b[0] - a[0]) * 0.02 / dt, 3),
        "console_errors": errors,
    }
    if c0 is not None and c1 is not None:
        out["server_cpu_share"] = round((c1 - c0) / dt, 3)
        out["server_cpu_ms_per_redraw"] = round(1000 * (c1 - c0) / max(redraws, 1), 2)
    return out


def _events_after(board, kind, t_ns):
    return [e for e in board.trace() if e[0] == kind and e[2] > t_ns]


def _drive():
    from hexapod_host.testing.runtimes import micropython_missing

    why = vb.missing() or micropython_missing()
    if why:
        return {"skipped": why}
    import statistics
    import tempfile

    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By

    tmp = tempfile.TemporaryDirectory(prefix="hexapod-bench-drive-")
    board = vb.VirtualBoard(os.path.join(tmp.name, "trace.txt"))
    key_ms, walk_ms, walk_frames, page_ms = [], [], [], []
    try:
        with vb.driving(("--virtual", "--virtual-port", board.path), fps=None) as (driver, _):
            # The keydown's own time in the page, on the host's clock (epoch ms).
            driver.execute_script(
                "document.addEventListener('keydown',"
                " e => { window.hexapodKeyMs = performance.timeOrigin + e.timeStamp; })"
            )
            t = time.time_ns()
            driver.find_element(By.ID, "drive-stand").click()
            vb.wait_for(lambda: [m for m in _events_after(board, "M", t) if m[3][0] == "3"], timeout=60)
            for _ in range(DRIVE_TRIES):
                time.sleep(0.5)  # standing still: no pulse changes before the key
                t0 = time.time_ns()
                ActionChains(driver).key_down("w").perform()
                first = vb.wait_for(lambda t0=t0: _events_after(board, "P", t0), timeout=30)
                walk = [c for c in vb.commands(board.trace(), "walk") if c[1] > t0]
                ActionChains(driver).key_up("w").perform()
                t1 = time.time_ns()
                vb.wait_for(lambda t1=t1: [m for m in _events_after(board, "M", t1) if m[3][0] == "3"], timeout=30)
                if first and walk:
                    key_ms.append((first[0][2] - t0) / 1e6)
                    walk_ms.append((walk[0][1] - t0) / 1e6)
                    walk_frames.append(first[0][1] - walk[0][0])
                    page_key = driver.execute_script("return window.hexapodKeyMs")
                    if page_key and page_key * 1e6 > t0:
                        page_ms.append(walk[0][1] / 1e6 - page_key)
            errors = len(vb.page_errors(driver))
    finally:
        board.stop()
        tmp.cleanup()
    if not key_ms:
        return {"failed": "no key press moved the board"}
    return {
        "tries": DRIVE_TRIES,
        "moved": len(key_ms),
        "key_to_pulse_ms_median": round(statistics.median(key_ms), 1),
        "key_to_pulse_ms_worst": round(max(key_ms), 1),
        "key_to_walk_line_ms_median": round(statistics.median(walk_ms), 1),
        "key_to_walk_line_ms_worst": round(max(walk_ms), 1),
        "page_keydown_to_walk_line_ms_median": round(statistics.median(page_ms), 1) if page_ms else None,
        "page_keydown_to_walk_line_ms_worst": round(max(page_ms), 1) if page_ms else None,
        "walk_line_to_pulse_frames": sorted(set(walk_frames)),
        "console_errors": errors,
    }


def _parts(pythonpath=None):
    """PARTS_SCRIPT in its own process on the host package at pythonpath (None: this one)."""
    env = dict(os.environ)
    if pythonpath:
        env["PYTHONPATH"] = pythonpath
    out = subprocess.run(
        [sys.executable, "-c", PARTS_SCRIPT, str(PARTS_UPDATES)], env=env, capture_output=True, text=True, timeout=600
    )
    if out.returncode:
        return {"failed": out.stderr.strip().splitlines()[-1:]}
    return json.loads(out.stdout.strip().splitlines()[-1])


def _tree(ref, into):
    """The repository's tree at git ref `ref`, written out under into; its host package's path."""
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
    archive = subprocess.run(["git", "-C", root, "archive", ref], capture_output=True, check=True).stdout
    subprocess.run(["tar", "-x", "-C", into], input=archive, check=True)
    return os.path.join(into, "host")


def _ratio(after, before):
    return round(after / before, 2) if before else None


def compare(ref, rounds=COMPARE_ROUNDS):
    """This tree against git ref `ref` in one run: the page and the per-update parts, `rounds`
    times each, before and after alternated so both see the same load. The ratios are after /
    before of the means."""
    import tempfile

    with tempfile.TemporaryDirectory(prefix="hexapod-bench-before-") as tmp:
        before_path = _tree(ref, tmp)
        runs = {"before": [], "after": []}
        parts = {"before": [], "after": []}
        for _ in range(rounds):
            for name, path in (("before", before_path), ("after", None)):
                runs[name].append(_page(path))
                parts[name].append(_parts(path))
    out = {"before_ref": ref, "rounds": rounds, "page": runs, "parts": parts}

    def mean(rows, key):
        vals = [r[key] for r in rows if key in r]
        return sum(vals) / len(vals) if vals else None

    for key in ("redraws_per_s", "server_cpu_ms_per_redraw", "sim_speed"):
        b, a = mean(runs["before"], key), mean(runs["after"], key)
        out["page_" + key] = {"before": b and round(b, 2), "after": a and round(a, 2), "ratio": _ratio(a, b)}
        out["page_" + key]["after_min"] = min((r[key] for r in runs["after"] if key in r), default=None)
    for key in ("step_ms", "draw_ms", "plots_ms", "snapshot_ms", "update_ms"):
        b, a = mean(parts["before"], key), mean(parts["after"], key)
        out["parts_" + key] = {"before": b and round(b, 3), "after": a and round(a, 3), "ratio": _ratio(a, b)}
    return out


def bench_view(args=None):
    before = getattr(args, "before", None)
    out = {"load_average_1min": round(os.getloadavg()[0], 2)}
    if before:
        out["compare"] = compare(before)
    else:
        out.update(cost=_cost(), player=_player(), parts=_parts(), page=_page(), drive=_drive())
    out["load_average_1min_after"] = round(os.getloadavg()[0], 2)
    return out
