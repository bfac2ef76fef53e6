"""`hexapod pico`: bad input is a usage error naming what was wrong (exit 2) and nothing runs;
a script's exception is the board's exit status. No emulation needed except in the last test."""

import os
import subprocess
import sys

import pytest

from hexapod_host.pico import emulator as pico

HEXAPOD = os.path.join(os.path.dirname(sys.executable), "hexapod")


def hexapod(*args, env=None):
    return subprocess.run([HEXAPOD, "pico", *args], capture_output=True, text=True, timeout=300, env=env)


@pytest.mark.parametrize(
    "args, message",
    [
        (("run", "no/such/file.py"), "no such file: no/such/file.py"),
        (("run", "x.py", "--firmware", "/nonexistent/fw.uf2"), "no Pico firmware at /nonexistent/fw.uf2"),
        (("bench", "nope"), "no Pico benchmark 'nope'; there are: boot, frame, ik, tick"),
        (("bench", "ik", "--firmware", "/nonexistent.uf2"), "no Pico firmware at /nonexistent.uf2"),
        # each count one past its ends, zero and negative (a negative --frames reached the board's
        # summary as an IndexError; 0 silently became the default)
        (("bench", "ik", "--rounds", "0"), "--rounds 0: allowed 1..200"),
        (("bench", "ik", "--rounds", "201"), "--rounds 201: allowed 1..200"),
        (("bench", "tick", "--ticks", "0"), "--ticks 0: allowed 1..2000"),
        (("bench", "tick", "--ticks", "-5"), "--ticks -5: allowed 1..2000"),
        (("bench", "tick", "--ticks", "2001"), "--ticks 2001: allowed 1..2000"),
        (("bench", "frame", "--frames", "1"), "--frames 1: allowed 2..1000"),
        (("bench", "frame", "--frames", "-1"), "--frames -1: allowed 2..1000"),
        (("bench", "frame", "--frames", "1001"), "--frames 1001: allowed 2..1000"),
        (("bench", "ik", "--frames", "0"), "--frames 0: allowed 2..1000"),
    ],
)
def test_bad_input_is_a_usage_error(args, message):
    proc = hexapod(*args)
    assert proc.returncode == 2 and message in proc.stderr, proc.stderr
    assert proc.stdout == ""


def test_a_file_that_is_no_rp2040_image_is_refused_before_booting(tmp_path):
    # main: an ELF loaded as a .bin ran garbage until the runner's 900 s timeout
    elf = tmp_path / "firmware.elf"
    elf.write_bytes(b"\x7fELF\x01\x01\x01" + bytes(2000))
    text = tmp_path / "notes.uf2"
    text.write_text("not an image\n")
    for fw, why in ((elf, "an ELF file"), (text, "13 bytes, not a whole number of 512-byte UF2 blocks")):
        for args in (("run", __file__), ("bench", "ik"), ("serial",)):
            proc = hexapod(*args, "--firmware", str(fw))
            assert proc.returncode == 2 and proc.stdout == "", (args, proc.stderr)
            assert proc.stderr.startswith("hexapod: error: not an RP2040 UF2/bin: %s: %s" % (fw, why)), proc.stderr


def test_bad_subcommand_and_missing_files_are_argparse_errors():
    for args in (("walk",), ("run",), ()):
        proc = hexapod(*args)
        assert proc.returncode == 2 and "usage:" in proc.stderr, (args, proc.stderr)


def test_missing_or_old_node_is_named(tmp_path):
    old = tmp_path / "node"
    old.write_text("#!/bin/sh\necho v16.20.0\n")
    old.chmod(0o755)
    for node, words in ((str(old), "needs Node.js >= 18; %s is v16.20.0" % old), ("/nonexistent/node", "")):
        env = dict(os.environ, NODE=node)
        proc = hexapod("run", __file__, env=env)
        assert proc.returncode == 2 and "Node.js >= 18" in proc.stderr and words in proc.stderr, proc.stderr


def test_no_image_names_how_to_build_it(monkeypatch, tmp_path):
    """With no image built and none named, the reason (a test's skip line too) says what to run."""
    monkeypatch.delenv("PICO_FIRMWARE", raising=False)
    monkeypatch.setattr(pico, "DEFAULT_FIRMWARE", str(tmp_path / "firmware.bin"))
    reason = pico.missing()
    assert reason is not None and "no Pico firmware image" in reason and "make pico-firmware" in reason, reason
    assert "Debian" in reason and "\n" not in reason


def test_image_dir_must_be_new_or_empty(tmp_path):
    (tmp_path / "keep.txt").write_text("mine")
    proc = hexapod("run", __file__, "--image", str(tmp_path))
    assert proc.returncode == 2 and "not empty" in proc.stderr
    assert os.listdir(tmp_path) == ["keep.txt"]  # nothing written


@pytest.mark.skipif(pico.missing() is not None, reason=pico.missing() or "")
def test_run_streams_output_and_returns_the_boards_status(tmp_path):
    good = tmp_path / "good.py"
    good.write_text("import sys\nprint(sys.platform, 6 * 7)\n")
    bad = tmp_path / "bad.py"
    bad.write_text("print('before')\nraise ValueError('from the board')\n")
    image = tmp_path / "img"
    proc = hexapod("run", str(good), str(bad), "--image", str(image))
    assert proc.returncode == 1
    assert proc.stdout.splitlines() == ["rp2 42", "before"]
    assert "ValueError: from the board" in proc.stderr
    staged = sorted(os.listdir(image))
    # what `hexapod flash --board pico` lands: main.py the entry, the rest compiled, the manifest
    assert staged == [
        "boards",
        "calstore.mpy",
        "console.mpy",
        "drivers",
        "hexapod",
        "hexapod.manifest",
        "main.py",
        "robots",
        "runner.mpy",
        "selftest.mpy",
    ]
    assert os.path.getsize(str(image) + ".img") == pico.FS_BLOCKS * pico.FS_BLOCK_SIZE
