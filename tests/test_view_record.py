"""hexapod view's recordings (--record FILE.mcap) and replays (--replay FILE.mcap), without a
browser: a short simulator run recorded and read back with the mcap package's own reader, the
replay's clock, bad files refused with what is wrong, the CLI's refusals and Ctrl-C. The replay
in a browser: tests/test_view_browser.py."""

import json
import os
import signal

import pytest
from mcap.reader import make_reader
from mcap.writer import Writer

from hexapod_host.commands import cli
from hexapod_host.view import browser as vb
from hexapod_host.view import record
from hexapod_host.view.player import Player
from hexapod_host.view.replay import ReplayError, ReplaySource
from hexapod_host.view.sim import SimSource
from hexapod_host.wall import world

STEP_NS = 40_000_000  # the test clock: 40 ms between two stamps


class Clock:
    """A host clock that moves 40 ms each time it is read, from 1 s."""

    def __init__(self):
        self.t = 1_000_000_000

    def __call__(self):
        self.t += STEP_NS
        return self.t


def plain(value):
    """A snapshot as JSON gives it back (tuples as lists)."""
    return json.loads(json.dumps(value))


def recorded_run(path, updates=30):
    """A simulator run of `updates` player updates of 40 ms recorded in path: the live snapshots
    and the source's describe()."""
    src = SimSource(world.load("wall"), 12, seed=0)
    described = src.describe()
    p = Player(src, recorder=record.Recorder(str(path), described, clock=Clock()))
    live = [plain(p.snap)]
    for _ in range(updates):
        p.advance(0.04)
        live.append(plain(p.snap))
    p.stop()
    return live, plain(described)


@pytest.fixture(scope="module")
def recording(tmp_path_factory):
    path = tmp_path_factory.mktemp("rec") / "run.mcap"
    live, described = recorded_run(path)
    return path, live, described


def test_a_recording_read_back_with_the_mcap_reader(recording):
    path, live, described = recording
    with open(path, "rb") as f:
        reader = make_reader(f)
        assert reader.get_header().profile == "hexapod-view"
        messages = list(reader.iter_messages())
    topics = [c.topic for _, c, _ in messages]
    assert topics == ["/hexapod/describe"] + ["/hexapod/snapshot"] * 31  # the first snapshot and 30 updates
    for schema, channel, _ in messages:
        assert channel.message_encoding == "json" and schema.encoding == "jsonschema"
        assert (
            schema.name
            == {"/hexapod/describe": "hexapod.view.Describe", "/hexapod/snapshot": "hexapod.view.Snapshot"}[
                channel.topic
            ]
        )
        assert json.loads(schema.data)["required"][:1] == (["source"] if "describe" in channel.topic else ["frame"])
    assert json.loads(messages[0][2].data) == described
    # Stamps: the clock read once for describe() (1.04 s), then once per snapshot, 40 ms apart.
    assert [m.log_time for _, _, m in messages] == [1_000_000_000 + STEP_NS * k for k in range(1, 33)]
    snaps = [json.loads(m.data) for _, _, m in messages[1:]]
    # 40 ms of real time at 1x is two 20 ms frames: frames 0, 2, 4, ... 60.
    assert [s["frame"] for s in snaps] == list(range(0, 62, 2))
    for got, want in zip(snaps, live, strict=True):
        assert got["angles"] == want["angles"] and len(got["angles"]) == 18
        assert got["legs"] == want["legs"] and got["pulses"] == want["pulses"]
        assert got == want  # and every other field, as the page drew it
    assert snaps[-1]["angles"] != snaps[0]["angles"]  # the robot moved: the comparison means something


def test_no_part_file_is_left_and_a_paused_source_is_written_once(tmp_path):
    path = tmp_path / "paused.mcap"
    src = SimSource(world.load("wall"), 12, seed=0)
    rec = record.Recorder(str(path), src.describe(), clock=Clock())
    assert os.listdir(tmp_path) == ["paused.mcap.part"]  # the name it has while written
    p = Player(src, recorder=rec)
    p.pause()
    for _ in range(10):
        p.advance(0.04)  # paused: the same snapshot ten times
    p.step()
    p.stop()
    p.stop()  # the server's shutdown and the command's finally both stop it
    assert os.listdir(tmp_path) == ["paused.mcap"]
    r = ReplaySource(str(path))
    assert len(r) == 2 and rec.written == 2
    r.seek(1.0)
    assert r.snapshot()["frame"] == 1


def test_the_schema_check_names_what_is_wrong(recording):
    _, live, _ = recording
    good = live[-1]
    assert record.problem(record.SNAPSHOT, good) is None
    cases = [
        ({k: v for k, v in good.items() if k != "angles"}, "snapshot: no 'angles'"),
        ({**good, "angles": good["angles"][:17]}, "snapshot.angles: 17 items, expected 18"),
        ({**good, "frame": "12"}, "snapshot.frame: str, expected integer"),
        ({**good, "frame": True}, "snapshot.frame: bool, expected integer"),
        ({**good, "stance": [1] * 6}, "snapshot.stance[0]: int, expected boolean"),
        ({**good, "body": {"x": 1.0, "y": 2.0, "z": 80.0}}, "snapshot.body: no 'yaw'"),
        ({**good, "legs": [[[0, 0]] * 4] * 6}, "snapshot.legs[0][0]: 2 items, expected 3"),
        ({**good, "counters": {"frames": 1.5}}, "snapshot.counters.frames: float, expected integer"),
        ({**good, "distances": [None, "a", 0, 0, 0]}, "snapshot.distances[1]: str, expected number or null"),
    ]
    for snap, message in cases:
        assert record.problem(record.SNAPSHOT, snap) == message


def test_the_replay_clock_seek_step_and_end(recording):
    path, live, described = recording
    r = ReplaySource(str(path))
    assert len(r) == 31 and r.duration_s == pytest.approx(1.2)  # 30 gaps of 40 ms
    assert r.describe() == {**described, "source": "replay of sim"}
    assert r.snapshot() == live[0]
    r.seek(0.1)  # between the snapshots at 0.08 and 0.12 s: the one at 0.08
    assert r.index == 2 and r.snapshot() == live[2]
    r.step()  # 0.12 s
    assert r.index == 3 and r.snapshot()["frame"] == 6
    r.seek(99)
    assert r.clock_s == pytest.approx(1.2) and r.done() and r.snapshot() == live[-1]
    r.restart()
    assert r.index == 0 and not r.done()
    r.seek(-5)
    assert r.clock_s == 0.0
    p = Player(r, speed=2.0)  # 0.2 s at 2x: 0.4 s of the recording, 10 snapshots on
    p.advance(0.2)
    assert p.snap == live[10]
    p.seek(1.0)
    assert p.snap == live[25] and p.history[-1][0] == live[25]["time_s"] and len(p.history) == 1


def _write(path, channels, profile="hexapod-view"):
    """An MCAP file of [(topic, schema name, encoding, [message bytes])]."""
    with open(path, "wb") as f:
        w = Writer(f)
        w.start(profile=profile)
        t = 1
        for topic, name, encoding, messages in channels:
            sid = w.register_schema(name=name, encoding="jsonschema", data=b"{}")
            cid = w.register_channel(topic=topic, message_encoding=encoding, schema_id=sid)
            for m in messages:
                w.add_message(cid, log_time=t, data=m, publish_time=t)
                t += 1
        w.finish()


def bad_files(tmp, good, live, described):
    """(file, what the refusal must say) for files that are not a recording."""
    data = good.read_bytes()
    d = json.dumps(described).encode()
    snap = json.dumps(live[3]).encode()
    no_angles = json.dumps({k: v for k, v in live[3].items() if k != "angles"}).encode()
    desc = ("/hexapod/describe", "hexapod.view.Describe", "json", [d])
    files = {
        "empty.mcap": (b"", "empty file"),
        "text.mcap": (b"frame,time_s\n1,0.02\n" * 10, "not a whole MCAP file (InvalidMagic"),
        "magic-only.mcap": (data[:8], "not a whole MCAP file"),
        "half.mcap": (data[: len(data) // 2], "MCAP file"),
        "no-last-byte.mcap": (data[:-1], "MCAP file"),
        "no-footer.mcap": (data[:-30], "MCAP file"),
        "crc.mcap": (data[:200] + bytes([data[200] ^ 0xFF]) + data[201:], "damaged MCAP file"),
    }
    for name, (content, _) in files.items():
        (tmp / name).write_bytes(content)
    channel_files = {
        "other-schema.mcap": (
            [desc, ("/hexapod/snapshot", "my.Pose", "json", [snap])],
            "topic /hexapod/snapshot has schema 'my.Pose', expected 'hexapod.view.Snapshot'",
        ),
        "other-topics.mcap": (
            [("/tf", "foxglove.FrameTransform", "json", [b"{}"])],
            "no hexapod.view.Describe message on /hexapod/describe",
        ),
        "no-snapshots.mcap": ([desc], "no snapshots on /hexapod/snapshot (an empty recording)"),
        "not-json.mcap": (
            [desc, ("/hexapod/snapshot", "hexapod.view.Snapshot", "json", [snap, b"\x00\x01cbor"])],
            "message 2 is not JSON",
        ),
        "no-angles.mcap": (
            [desc, ("/hexapod/snapshot", "hexapod.view.Snapshot", "json", [snap, snap, no_angles])],
            "message 3 does not fit hexapod.view.Snapshot: snapshot: no 'angles'",
        ),
        "bad-describe.mcap": (
            [("/hexapod/describe", "hexapod.view.Describe", "json", [b'{"source": "sim"}'])],
            "message 0 does not fit hexapod.view.Describe: snapshot: no 'sensors'",
        ),
    }
    for name, (channels, message) in channel_files.items():
        _write(tmp / name, channels)
        files[name] = (None, message)
    return {name: message for name, (_, message) in files.items()}


def test_bad_files_are_refused_saying_what_is_wrong(recording, tmp_path):
    good, live, described = recording
    for name, message in bad_files(tmp_path, good, live, described).items():
        with pytest.raises(ReplayError) as err:
            ReplaySource(str(tmp_path / name))
        assert message in str(err.value), name
        assert str(tmp_path / name) in str(err.value)
    with pytest.raises(ReplayError, match="cannot read: No such file or directory"):
        ReplaySource(str(tmp_path / "nowhere.mcap"))


def test_cli_refuses_a_bad_replay_with_exit_2(recording, tmp_path, capsys):
    good, live, described = recording
    bad_files(tmp_path, good, live, described)
    for name, message in [("half.mcap", "MCAP file"), ("no-angles.mcap", "no 'angles'")]:
        with pytest.raises(SystemExit) as exc:
            cli.main(["view", "--replay", str(tmp_path / name), "--no-browser"])
        assert exc.value.code == 2
        err = capsys.readouterr().err
        assert "--replay %s" % (tmp_path / name) in err and message in err


@pytest.mark.parametrize(
    "args, message",
    [
        (["--record", "{tmp}/run.csv"], "--record: '{tmp}/run.csv', allowed a file name ending in .mcap"),
        (["--record", "{tmp}/no/such/run.mcap"], "--record: no such directory '{tmp}/no/such'"),
        (["--record", "{tmp}/dir.mcap"], "--record: '{tmp}/dir.mcap' is a directory; give a file name"),
        (["--record", ""], "--record: empty; give a file name"),
    ],
)
def test_cli_refuses_a_bad_record_path_and_writes_nothing(args, message, tmp_path, capsys):
    (tmp_path / "dir.mcap").mkdir()
    with pytest.raises(SystemExit) as exc:
        cli.main(["view", "--sim", *[a.format(tmp=tmp_path) for a in args]])
    assert exc.value.code == 2
    assert message.format(tmp=tmp_path) in capsys.readouterr().err
    assert os.listdir(tmp_path) == ["dir.mcap"]


def test_cli_refuses_record_with_replay(recording, tmp_path, capsys):
    with pytest.raises(SystemExit) as exc:
        cli.main(["view", "--replay", str(recording[0]), "--record", str(tmp_path / "again.mcap")])
    assert exc.value.code == 2
    assert "--record: not with --replay" in capsys.readouterr().err
    assert os.listdir(tmp_path) == []


def test_ctrl_c_leaves_a_whole_recording(tmp_path):
    """The real command in its own process, stopped by SIGINT as Ctrl-C stops it."""
    path = tmp_path / "live.mcap"
    server = vb.Server(("--sim", "--record", str(path)))
    vb.wait_for(lambda: False, timeout=2)  # two seconds of updates
    server.proc.send_signal(signal.SIGINT)
    server.proc.wait(60)
    out = server.stop()
    assert server.proc.returncode == 130, out  # the CLI's exit after Ctrl-C
    assert os.listdir(tmp_path) == ["live.mcap"]
    r = ReplaySource(str(path))
    assert len(r) > 5, out
    assert "hexapod view: %d snapshots recorded in %s" % (len(r), path) in out
    frames = [json.loads(d)["frame"] for d in r.data]
    assert frames == sorted(frames) and frames[0] == 0


def test_a_ctrl_c_the_server_took_still_ends_in_keyboard_interrupt(monkeypatch):
    # A CI run: SIGINT stopped `hexapod view --record` (the recording finished) but the command
    # exited 0, not 130: uvicorn's own raise of the signal it took did not come out of its runner.
    import signal as sig

    from nicegui.server import Server

    from hexapod_host.view import server

    class Stopped:
        _captured_signals = [sig.SIGINT]

    class Served:
        _captured_signals = []

    monkeypatch.setattr(Server, "instance", Stopped(), raising=False)
    with pytest.raises(KeyboardInterrupt):
        server.interrupted()
    monkeypatch.setattr(Server, "instance", Served(), raising=False)
    server.interrupted()  # a server stopped otherwise (its page's shutdown) is no Ctrl-C
