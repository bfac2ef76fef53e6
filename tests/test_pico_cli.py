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
        (("bench", "frame", "--frames", "1"), "--frames 1: allowed 2..2000"),
        (("bench", "frame", "--frames", "-1"), "--frames -1: allowed 2..2000"),
        (("bench", "frame", "--frames", "2001"), "--frames 2001: allowed 2..2000"),
        (("bench", "ik", "--frames", "0"), "--frames 0: allowed 2..2000"),
        (("serial", "--sonar-cm", "1.9"), "--sonar-cm: 1.9 is outside 2..400 cm (the HC-SR04's range)"),
        (("serial", "--sonar-cm", "nan"), "--sonar-cm: nan is outside 2..400 cm"),
        (("serial", "--sonar-cm", "10", "20"), "--sonar-cm: 2 values; allowed 1 (for every sonar) or 5 (one each)"),
        (("run", __file__, "--sonar-cm", "far"), "--sonar-cm: 'far' is not a number (cm)"),
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
    # what `hexapod flash --board pico` lands: main.py the entry, the rest compiled (its body
    # startup.py too), the list of the files flash checked (hexapod.wiring), the manifest
    assert staged == [
        "boards",
        "calstore.mpy",
        "console.mpy",
        "consolecal.mpy",
        "consoleparts",
        "drivers",
        "hexapod",
        "hexapod.checked",
        "hexapod.manifest",
        "main.py",
        "robots",
        "runner.mpy",
        "selftest.mpy",
        "startup.mpy",
    ]
    assert os.path.getsize(str(image) + ".img") == pico.FS_BLOCKS * pico.FS_BLOCK_SIZE


@pytest.mark.skipif(pico.missing() is not None, reason=pico.missing() or "")
def test_serial_attaches_the_boards_chips_and_sonars_at_the_distances_given(tmp_path):
    # main: no emulated chips on `pico serial`: after a flash, status said bus_failed 550 sonar_faults 549
    import shutil
    import signal
    import time

    from hexapod_host.serial.link import Link

    with pico.flashed() as fs:  # what `hexapod flash --board pico` lands, as a filesystem image
        img = tmp_path / "fs.img"
        shutil.copy(fs, img)
    cm = ("25", "35", "45", "55", "65")
    proc = subprocess.Popen(
        [HEXAPOD, "pico", "serial", "--fs", str(img), "--sonar-cm", *cm],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        port = proc.stdout.readline().strip()
        assert port.startswith("/dev/"), proc.stderr.read() if proc.poll() is not None else port
        with Link.open(port, timeout=120) as link:  # a generous bound on main.py's boot (~4 emulated s)
            first = link.request("status")
            end = time.monotonic() + 120  # bounded: the round robin gives each sonar its turn in turn
            sonar = link.request("sonar").split()
            while "wait" in sonar and time.monotonic() < end:
                time.sleep(0.2)
                sonar = link.request("sonar").split()
            status = link.request("status").split()
    finally:
        proc.send_signal(signal.SIGTERM)
        proc.wait(60)
    assert first.startswith("ok frames "), first
    words = dict(zip(status[1::2], status[2::2], strict=False))
    assert int(words["frames"]) > 0 and words["bus_failed"] == "0" and words["sonar_faults"] == "0", status
    # 'ok NAME MM ok' per sensor: each within 0.2 mm of what was set (docs/pico.md: the echo's timing)
    assert sonar[0] == "ok" and sonar[3::3] == ["ok"] * 5, sonar
    # compared in tenths of a mm, the reply's resolution: 649.8 against 650.0 is 0.2 mm, within the
    # bound, though 650.0 - 649.8 is 0.20000000000004547 in floats (a fresh-clone CI failed on it)
    tenths = [round(float(v) * 10) for v in sonar[2::3]]
    assert all(abs(t - 100 * int(c)) <= 2 for t, c in zip(tenths, cm, strict=True)), (tenths, cm)
