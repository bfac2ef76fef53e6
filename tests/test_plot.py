"""`hexapod plot gait` writes its PNGs; bad options exit 2 and write nothing. And the tick
bench's VM script runs (a short run: its figures are for `hexapod bench tick`, not a test)."""

import json
import os

import pytest

from hexapod_host import mpvm
from hexapod_host.commands import cli


def test_plot_gait_writes_pngs(tmp_path, capsys):
    out = tmp_path / "plots"
    assert cli.main(["plot", "gait", "--out", str(out), "--gait", "ripple"]) == 0
    names = sorted(os.listdir(out))
    assert names == ["phases_ripple.png", "top_ripple.png", "trajectory.png"]
    for name in names:
        data = (out / name).read_bytes()
        assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 5000
    assert capsys.readouterr().out.split() == [
        str(out / n) for n in ("trajectory.png", "phases_ripple.png", "top_ripple.png")
    ]


@pytest.mark.parametrize(
    "argv,message",
    [
        (["--gait", "trot"], "--gait: 'trot' is not one of"),
        (["--speed", "fast"], "--speed: 'fast' is not a number"),
        (["--speed", "301"], "--speed: '301' is outside the accepted -300..300 mm/s"),
        (["--speed", "300"], None),  # exactly at the limit: accepted, then --out is checked
        (["--speed", "9" * 40], "--speed: '99999999999999999999...' is outside the accepted -300..300 mm/s"),
        (["--turn", "-91"], "--turn: '-91' is outside the accepted -90..90 deg/s"),
        (["--turn", "1e1"], "--turn: '1e1' is not a number: exponents are not accepted"),
    ],
)
def test_plot_bad_options(tmp_path, capsys, argv, message):
    out = tmp_path / "plots"
    (tmp_path / "file").write_text("x")
    if message is None:  # a good value: the run goes on to --out, here a file, and stops there
        out, message = tmp_path / "file", "--out: '%s' exists and is not a directory" % (tmp_path / "file")
    with pytest.raises(SystemExit) as err:
        cli.main(["plot", "gait", "--out", str(out)] + argv)
    assert err.value.code == 2
    assert message in capsys.readouterr().err
    assert not (tmp_path / "plots").exists()


def test_plot_out_must_be_a_directory(tmp_path, capsys):
    f = tmp_path / "file"
    f.write_text("x")
    with pytest.raises(SystemExit):
        cli.main(["plot", "gait", "--out", str(f)])
    assert "not a directory" in capsys.readouterr().err


@pytest.mark.parametrize(
    "out,message",
    [
        ("", "--out: empty; give a directory"),
        ("/proc/hexapod-plots", "--out: cannot write into '/proc/hexapod-plots': No such file or directory"),
        ("FILE/sub", "cannot write into '{tmp}/FILE/sub': Not a directory"),
    ],
)
def test_plot_unwritable_out_exits_2_before_drawing(tmp_path, capsys, monkeypatch, out, message):
    from hexapod_host.commands import plot as cmd_plot

    (tmp_path / "FILE").write_text("x")
    monkeypatch.setattr(cmd_plot, "record", lambda *a, **k: pytest.fail("drew before checking --out"))
    out = out.replace("FILE", str(tmp_path / "FILE"))
    with pytest.raises(SystemExit) as exc:
        cli.main(["plot", "gait", "--out", out])
    assert exc.value.code == 2 and message.format(tmp=tmp_path) in capsys.readouterr().err


def test_plot_write_failure_leaves_no_partial_file(tmp_path, monkeypatch):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from hexapod_host.commands import plot as cmd_plot
    from hexapod_host.commands.cli import UsageError

    fig, _ = plt.subplots()

    def full_disk(path, **kw):
        with open(path, "wb") as f:
            f.write(b"\x89PNG half")
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(fig, "savefig", full_disk)
    with pytest.raises(UsageError, match="No space left on device"):
        cmd_plot._save(fig, plt, str(tmp_path), "x.png")
    assert os.listdir(tmp_path) == []


@pytest.mark.skipif(mpvm.executable() is None, reason="no MicroPython VM")
def test_tick_bench_script_runs_allocation_free():
    from hexapod_host.bench.tick import bench_tick

    result = bench_tick(None, ticks=300, repeats=1)
    assert result["bench"] == "tick" and result["heap"] == "256k"  # 192k stopped fitting the wall row on 2026-11-27
    assert [g["gait"] for g in result["gaits"]] == ["tripod", "tetrapod", "ripple", "wave"]
    for g in result["gaits"]:
        assert g["heap_bytes_per_tick"] == 0 and g["faults"] == 0
        assert 0 < g["median_us"] <= g["p99_us"] <= g["max_us"] <= g["raw_max_us"]
    wall = result["wall_follow"]  # the follower's frame: sonar result, PID, walk command, tick
    assert wall["row"] == "wall-follow" and wall["heap_bytes_per_frame"] == 0 and wall["faults"] == 0
    assert wall["pid_updates"] >= 50 and 0 < wall["median_us"] <= wall["max_us"] <= wall["raw_max_us"]
    json.dumps(result)
