"""`hexapod flash --board pico` onto the emulated Pico over a pseudo-terminal, through the real
mpremote exactly as a user runs it, then power-up from the filesystem the board wrote: the
strongest test of the flashing path without hardware (docs/flashing.md, docs/pico.md)."""

import json
import os
import re
import time

import pytest

from hexapod_host.commands import cli
from hexapod_host.pico import emulator as pico
from hexapod_host.pico import loop as pico_loop
from hexapod_host.serial import flash as flash_tool

REASON = pico.missing()
pytestmark = pytest.mark.skipif(REASON is not None, reason=REASON or "")


def flash(port, stage, capsys, monkeypatch):
    # The emulated Pico runs at a tenth of real time or less on a loaded machine: the tool's
    # hung-board guards (120 s a command, 15 s for the first answer, for a real board) must not
    # decide this test (a CI run under load took more than 15 s to answer the probe).
    monkeypatch.setattr(flash_tool, "MPREMOTE_S", 3600)
    monkeypatch.setattr(flash_tool, "PROBE_S", 3600)
    t0 = time.monotonic()
    status = cli.main(["flash", "--board", "pico", "--port", port, "--stage-dir", stage])
    out = capsys.readouterr().out
    assert status == 0, out
    m = re.search(r"flashed pico on \S+: (\d+) of (\d+) files copied", out)
    assert m, out
    return int(m.group(1)), int(m.group(2)), time.monotonic() - t0, out


def test_flash_the_emulated_pico_over_a_pty_then_boot_it(tmp_path, capsys, monkeypatch):
    saved = str(tmp_path / "fs.img")
    stage = str(tmp_path / "stage")
    stats = str(tmp_path / "stats.json")
    with pico.serial(save_fs=saved, stats=stats) as port:  # erased flash: MicroPython formats it
        assert port.startswith("/dev/")
        copied, total, t1, out = flash(port, stage, capsys, monkeypatch)
        assert "board manifest: 0 files" in out
        assert copied == total > 10, out  # a fresh board gets everything
        # mpremote's reset at the end rebooted the emulated chip (watchdog): the board answers again,
        # and its manifest says nothing changed.
        again, total2, t2, out2 = flash(port, stage, capsys, monkeypatch)
        assert "board manifest: %d files" % total in out2, out2
        assert (again, total2) == (0, total), out2
    assert os.path.getsize(saved) == pico.FS_BLOCKS * pico.FS_BLOCK_SIZE
    with open(stats) as f:
        resets = json.load(f)["resets"]
    # mpremote sends machine.reset() and leaves without waiting: the first flash's reset rebooted
    # the chip before the second flash; the second one may land after the runner was stopped.
    assert resets >= 1
    print("emulated Pico over a pty: %d files in %.1f s, second flash 0 files in %.1f s" % (total, t1, t2))

    # Power-up from what the board wrote: the image's own main.py, with no calibration file,
    # boots relaxed (every channel full-off), burst for burst as on the host's stub machine (as
    # tests/test_pico_loop.py does from a packed image). 6 emulated seconds: ~4.2 s of imports
    # and build (the servo guard's ~2,400 IK solves among them, docs/physics.md; `hexapod pico
    # bench boot`), then 20 ms frames.
    status, out, bursts = pico_loop.boot_main(6, saved)
    assert status == 0 and "Traceback" not in out, out
    frames = len(bursts) // 2
    assert frames > 50, (frames, out)
    _, host_bursts = pico_loop.host_main(frames)
    assert bursts[: 2 * frames] == host_bursts[: 2 * frames]
    assert {c for _, counts in bursts for c in counts} == {-1}


def test_hexapod_pico_serial_prints_the_port_and_saves_the_filesystem(tmp_path):
    import signal
    import subprocess
    import sys

    from hexapod_host import ROOT
    from hexapod_host.serial import flash

    saved = tmp_path / "fs.img"
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "host"))
    cmd = [sys.executable, "-m", "hexapod_host", "pico", "serial", "--save-fs", str(saved)]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    try:
        port = proc.stdout.readline().strip()
        assert port.startswith("/dev/"), (port, proc.stderr.read() if proc.poll() is not None else "")
        status, out = flash.run(
            [flash.tool("mpremote"), "connect", port, "exec", "with open('x.txt','w') as f: f.write('hi')"], 60
        )
        assert status == 0, out
    finally:
        proc.send_signal(signal.SIGTERM)
        proc.wait(30)
    assert proc.returncode == 0, proc.stderr.read()
    from littlefs import LittleFS

    lfs = LittleFS(block_size=pico.FS_BLOCK_SIZE, block_count=pico.FS_BLOCKS, mount=False)
    lfs.context.buffer = bytearray(saved.read_bytes())
    lfs.mount()
    with lfs.open("/x.txt", "r") as f:
        assert f.read() == "hi"
