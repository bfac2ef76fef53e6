"""Output paths checked before anything runs (hexapod_host.commands.checks): a bad one is exit 2 with the
option named, and the simulation, render or staging never starts (each is replaced by a tripwire)."""

import os

import pytest

from hexapod_host.commands import checks, cli
from hexapod_host.commands import sim_physics as cmd_physics
from hexapod_host.commands import sim_wall as cmd_wall
from hexapod_host.pico import emulator as pico


def usage_error(capsys, argv):
    """(exit status, stderr) of argv, which must stop with a usage error."""
    with pytest.raises(SystemExit) as stop:
        cli.main(argv)
    out = capsys.readouterr()
    assert out.out == ""
    return stop.value.code, out.err


@pytest.fixture
def no_trials(monkeypatch):
    monkeypatch.setattr(cmd_wall, "run_trials", lambda *a, **k: pytest.fail("ran the trials before checking --plot"))


def test_sim_wall_plot_into_a_missing_directory(capsys, tmp_path, no_trials):
    # main: the whole run, then FileNotFoundError, exit 3 and no table
    png = tmp_path / "nosuchdir" / "x.png"
    status, err = usage_error(capsys, ["sim", "wall", "--trials", "1", "--plot", str(png)])
    assert status == 2
    assert err == "hexapod: error: --plot: no such directory '%s' (for '%s')\n" % (tmp_path / "nosuchdir", png)


def test_sim_wall_plot_onto_a_directory_or_a_read_only_one(capsys, tmp_path, no_trials):
    folder = tmp_path / "x.png"
    folder.mkdir()
    status, err = usage_error(capsys, ["sim", "wall", "--plot", str(folder)])
    assert status == 2 and "--plot: '%s' is a directory; give a file name" % folder in err
    if os.geteuid() != 0:  # root writes anywhere
        ro = tmp_path / "ro"
        ro.mkdir()
        ro.chmod(0o500)
        status, err = usage_error(capsys, ["sim", "wall", "--plot", str(ro / "a.png")])
        assert status == 2 and "--plot: cannot write '%s': Permission denied" % (ro / "a.png") in err
    status, err = usage_error(capsys, ["sim", "wall", "--plot", "/proc/x.png"])  # no file can be made in /proc
    assert status == 2 and err.startswith("hexapod: error: --plot: cannot write '/proc/x.png': ")


def test_sim_wall_default_plot_is_checked_too(capsys, tmp_path, monkeypatch, no_trials):
    monkeypatch.setattr(cmd_wall, "PLOT", str(tmp_path / "gone" / "wall_sim.png"))
    status, err = usage_error(capsys, ["sim", "wall", "--trials", "1"])
    assert status == 2 and "--plot: no such directory" in err


def test_sim_physics_render_onto_an_existing_file(capsys, tmp_path, monkeypatch):
    # main: FileExistsError after MuJoCo started, exit 3
    monkeypatch.setattr(cmd_physics, "simulate", lambda **k: pytest.fail("simulated before checking --render"))
    f = tmp_path / "frames"
    f.write_text("mine")
    status, err = usage_error(capsys, ["sim", "physics", "--render", str(f)])
    assert status == 2 and err == "hexapod: error: --render: '%s' exists and is not a directory\n" % f
    assert f.read_text() == "mine"
    status, err = usage_error(capsys, ["sim", "physics", "--render", str(f / "sub")])
    assert status == 2 and "--render: cannot write into '%s': Not a directory" % (f / "sub") in err


def test_flash_stage_dir_with_other_files_is_not_wiped(capsys, tmp_path):
    # main: staging began with shutil.rmtree(--stage-dir), whatever the directory held
    mine = tmp_path / "notes.txt"
    mine.write_text("mine")
    argv = ["flash", "--board", "pico", "--port", "/dev/ttyACM0", "--dry-run", "--stage-dir", str(tmp_path)]
    status, err = usage_error(capsys, argv)
    assert status == 2 and "--stage-dir: '%s' holds other files and staging replaces it" % tmp_path in err
    assert mine.read_text() == "mine"


def test_flash_restages_over_its_own_stage(capsys, tmp_path):
    stage = tmp_path / "stage"
    argv = ["flash", "--board", "pico", "--port", "/dev/ttyACM0", "--dry-run", "--stage-dir", str(stage)]
    assert cli.main(argv) == 0
    assert cli.main(argv) == 0  # the directory now holds a stage: replaced, not refused
    capsys.readouterr()


@pytest.mark.skipif(pico.missing() is not None, reason=pico.missing() or "")
def test_pico_paths(capsys, tmp_path):
    f = tmp_path / "file"
    f.write_text("mine")
    status, err = usage_error(capsys, ["pico", "run", __file__, "--image", str(f)])
    assert status == 2 and "--image: '%s' exists and is not a directory" % f in err
    status, err = usage_error(capsys, ["pico", "serial", "--save-fs", str(tmp_path / "no" / "fs.img")])
    assert status == 2 and "--save-fs: no such directory '%s'" % (tmp_path / "no") in err


def test_checking_a_new_directory_creates_nothing(capsys, tmp_path):
    out = tmp_path / "new" / "plots"
    assert checks.out_dir("--out", str(out)) == str(out)
    assert os.listdir(tmp_path) == []  # a check that failed later would leave nothing behind
    assert cli.main(["plot", "gait", "--out", str(out), "--gait", "wave"]) == 0  # a good run makes it
    assert sorted(os.listdir(out)) == ["phases_wave.png", "top_wave.png", "trajectory.png"]
    capsys.readouterr()
