"""The whole loop on the emulated Pico: main.build (board file, PCA9685 and HC-SR04 drivers,
Runner) on real MicroPython rp2 firmware, talking to emulated PCA9685s over the RP2040's I2C block
and to emulated HC-SR04s on its GPIOs, gives the very bursts the host's stub machine gives."""

import contextlib
import io
import json
import re

import pytest

from hexapod_host.pico import emulator as pico
from hexapod_host.pico import loop as pico_loop

REASON = pico.missing()
pytestmark = pytest.mark.skipif(REASON is not None, reason=REASON or "")

FRAMES = 100  # 2 s: stand up, then tripod walking from frame 60 (10 s: `hexapod pico bench frame`)


@pytest.fixture
def fs(pico_fs):
    """The staged firmware's littlefs image (what a flash puts on the board): conftest's, one a test process."""
    return pico_fs


@pytest.fixture(scope="module")
def boot():
    """`hexapod pico bench boot --json` (6 emulated s of the image's own main.py, without and then with
    a calibration file) and what its two boot_main runs returned, each (status, output, bursts): one
    pair of boots for the tests that read them."""
    from hexapod_host.commands import cli

    runs = []

    def recorded(*args, **kwargs):
        runs.append(real(*args, **kwargs))
        return runs[-1]

    real = pico_loop.boot_main
    out = io.StringIO()
    with pytest.MonkeyPatch.context() as mp, contextlib.redirect_stdout(out):
        mp.setattr(pico_loop, "boot_main", recorded)
        code = cli.main(["pico", "bench", "boot", "--json"])
    assert len(runs) == 2
    return code, out.getvalue(), runs[0], runs[1]


def test_stand_up_and_walk_bursts_equal_the_stub_machines(fs):
    status, lines, bursts, stats = pico_loop.board(FRAMES, fs)
    assert status == 0, "\n".join(lines)
    host_lines, host_bursts = pico_loop.host(FRAMES)
    assert len(bursts) == 2 * FRAMES  # one burst per chip per frame, nothing failed
    assert [b[0] for b in bursts[:2]] == [0x40, 0x41]
    assert bursts == host_bursts  # bit-identical, burst by burst
    # 50 Hz from the 25 MHz oscillator: PRE_SCALE 121, 4.88 us per count; the servos' 600..2400 us
    # are 123..492 counts (data sheet eq. 1), channels 9..15 unused (full off).
    # The soft start: 16 frames (32 bursts) in which the middle, then the rear pair is still off.
    for k, (_, counts) in enumerate(bursts):
        on = [c for c in counts[:9] if c != -1 or k >= 32]
        assert all(123 <= c <= 492 for c in on) and counts[9:] == [-1] * 7, counts
    assert sum(1 for _, counts in bursts[:2] for c in counts if c != -1) == 6
    assert len({tuple(c) for _, c in bursts[120:]}) > 30  # the legs walk
    status_line = [line for line in lines if line.startswith("frames ")][-1]
    assert status_line.startswith("frames %d held 0 " % FRAMES)
    assert "bus_failed 0 reinit 0 sonar_faults 0" in status_line
    dist = [int(v) for v in re.search(r"dist \[([^\]]*)\]", status_line).group(1).split(",")]
    # Each sonar read its emulated distance within the driver's 0.2 mm (echo timed on the emulated clock).
    assert all(abs(d - e) <= 2 for d, e in zip(dist, pico_loop.DISTANCES, strict=True)), dist
    s = pico_loop.summary(lines)
    assert s["heap_bytes_per_frame"] == 0
    # The bursts went through the background sender (drivers/_i2c_rp2.py): one write per burst
    # (start-up's transactions are machine.I2C's); no NACK; each frame's bus done before the next.
    refills, done, nacks = s["sender"]
    assert done == 2 * FRAMES and nacks == 0 and refills > done
    assert s["frames_begun_with_bus_busy"] == 0
    # The period is a benchmark figure (`hexapod pico bench frame`), reported here, not asserted.
    print("emulated Pico frame:", s, "status:", status_line)


def test_main_py_unmodified_boots_relaxed_and_sends_no_pulse(boot):
    # Power-up with the image's own main.py (no REPL, no script): 6 emulated seconds. No
    # calibration file on the board: it stays relaxed (issue 20), every channel full-off.
    status, out, bursts = boot[2]
    assert status == 0 and "Traceback" not in out, out
    assert "boot: relaxed, no pulse until `stand`: no valid calibration file" in out, out
    frames = len(bursts) // 2
    # ~4.2 s of imports and build (the servo guard's ~2,400 IK solves at the first configure,
    # docs/physics.md; `hexapod pico bench boot` measures it), then 20 ms frames, a burst per chip.
    assert frames > 50, frames
    assert {c for _, counts in bursts for c in counts} == {-1}  # full-off (LEDn_OFF_H bit 4) only
    print("main.py on the emulated Pico: %d frames in 6 emulated s" % frames)
    _, host_bursts = pico_loop.host_main(frames)
    assert bursts[: 2 * frames] == host_bursts[: 2 * frames]  # bit-identical on the stub machine


def test_echo_irq_faults_on_the_board(fs):
    # The rp2 port's real Pin.irq on the emulated HC-SR04s: 5 m (beyond the module's 4 m) and
    # 1.5 cm (inside its 2 cm) both make it hold echo 38 ms: OUT_OF_RANGE, no distance; the others
    # read their distance. 11 frames: every sensor fired and collected twice.
    src = """
import main
r = main.build()
for _ in range(11):
    r.step()
    r.wait()
print((r.sonar_status, r.distances, r.sonar_faults))
"""
    status, out, err, _ = pico.run_source(src, fs=fs, devices=pico.devices(distances=[3000, 50000, 150, 6000, 7000]))
    assert status == 0, out + err
    st, dist, faults = eval(out.strip().splitlines()[-1])  # noqa: S307 (our own repr)
    assert st == [0, 1, 1, 0, 0]
    assert dist[1:3] == [-1, -1] and abs(dist[0] - 3000) <= 2 and abs(dist[3] - 6000) <= 2 and abs(dist[4] - 7000) <= 2
    assert faults == 4  # two out-of-range pings each of the two sensors


def test_boot_bench_reports_the_first_burst(boot):
    code, out, _, _ = boot
    assert code == 0
    result = json.loads(out)
    # The first burst after imports (the guard's answers come from the robot's table); then 50 Hz
    # frames. (The trace's clock, the runner's cycle count at 125 MHz, reads the board's 20 ms frames
    # as 19.8 ms: within 2 %.) Issue 22's goal of 1 s has its own test below.
    assert 0.2 < result["first_burst_s"] <= 1.5 and abs(result["frame_period_ms"] - 20) < 0.4, result
    assert result["frames_in_6s"] > 50, result


def test_boot_reaches_the_first_burst_within_1_s(boot):
    # Issue 22's goal. 0.980 s on the frame branch alone, 1.153 s once merged with the fault log, the
    # tags and issue 19's split, 0.987 s with the flashed files built unchecked and main.py's body
    # compiled, 0.981 s after the frame fix; 1.117 s with the swing budget, gait switching and the
    # on-demand jog commands; 0.975 s with the built-in modules in sys.modules before the imports
    # (main.py: each import of array, time, machine, ... had searched the filesystem first, ~4 ms,
    # 24 times) and the boot's calibration load without consolecal when there is no file
    # (2026-11-27; the emulated clock is deterministic).
    code, out, _, _ = boot
    assert code == 0
    assert json.loads(out)["first_burst_s"] <= 1.0


def test_boot_with_a_calibration_file_reaches_the_first_burst_within_1_s(boot):
    # Issue 22's goal for a calibrated robot. 1.0886 s on main (766187f; 0.975 s without the file):
    # consolecal's import, the decode and the rows before the first frame; 1.1092 s (0.9914 s
    # without) on 2026-11-28, the load setting off a collection of the full heap; 1.0122 s (0.9897
    # s without) with the file read in place (calstore.parse) and its rows put in force without
    # consolecal; 1.0428 s (0.9866 s without) on main once the rows went through `calibrate`
    # again, which imports hexapod.jog (~19 ms) and costs ~1 ms a row. 0.9757 s (0.9668 s without)
    # since a boot that does not stand leaves the file's load to the first frames (console.start:
    # calstore's import, the read and check, hexapod.jog's import, the rows six a frame; no line
    # is read before the file's calibration is in force, tests/test_power_up.py); 0.9782 s (0.9693
    # s without) with Robot.calibrate back in the resident tick (no import in the load). The rest of the
    # gap is the image's one more file in the root folder: every import's littlefs lookups there
    # (docs/pico.md).
    code, out, _, _ = boot
    assert code == 0
    with_file = json.loads(out)["with_cal_file"]
    assert abs(with_file["frame_period_ms"] - 20) < 0.4 and with_file["frames_in_6s"] > 50, with_file
    assert with_file["first_burst_s"] <= 1.0, with_file


def test_main_py_with_a_calibration_file_boots_relaxed_too(boot):
    # A valid hexapod_cal.txt on the board (the bench's: robots/default_cal.py's rows, trim 0), the
    # shipped board file (no "boot": "stand"): still no pulse before `stand` (issue 20), only the
    # notice says why differently; the file loaded (no "cal:" line says it could not be used).
    status, out, bursts = boot[3]
    assert status == 0 and "Traceback" not in out and "cal:" not in out, out
    assert "boot: relaxed, no pulse until `stand` (the board file's boot setting)" in out, out
    assert len(bursts) > 100 and {c for _, counts in bursts for c in counts} == {-1}


def test_stream_on_25_writes_parseable_lines_and_allocates_nothing(fs):
    # The default scenario with the console's telemetry at 25 Hz (`stream on 25`, through
    # select.poll on the board's USB CDC): a line every second frame, none dropped, each one a
    # valid line; the same bursts as the stub machine's; still 0 bytes a frame.
    from hexapod_host.serial import telemetry

    status, lines, bursts, _ = pico_loop.board(FRAMES, fs, "stream")
    assert status == 0, "\n".join(lines)
    assert "ok stream 25" in lines
    _, host_bursts = pico_loop.host(FRAMES, "stream")
    assert bursts == host_bursts
    got = [telemetry.parse(line) for line in lines if telemetry.is_telemetry(line)]
    assert [t["frame"] for t in got] == list(range(2, FRAMES + 1, 2))
    assert got[-1]["mode"] == 4 and got[-1]["vx"] == 1200  # tripod walking forward from frame 60
    assert all(p for p in got[-1]["pulses"])
    s = pico_loop.summary(lines)
    assert s["stream_sent_dropped"] == [FRAMES // 2, 0]
    assert s["heap_bytes_per_frame"] == 0
    # The firmware's frame times (runner.wait: step to wait) against the script's own clock
    # around each frame (step and console poll). A line says the frame before it, one that wrote
    # no line (0.5-1.5 ms cheaper here): their median is under the script's median of all frames.
    # Its worst since the line before covers the frame that wrote that line: over the run, the
    # worst of every frame but the last, the script's own worst (its readings start a little
    # earlier and end a little sooner; in five frames its walk commands come after its reading).
    times = sorted(t["frame_us"] for t in got)
    assert 0 < times[len(times) // 2] <= s["frame_median_us"], (times, s)
    assert all(0 < t["frame_us"] <= t["frame_us_max"] < 20000 for t in got)
    worst = max(t["frame_us_max"] for t in got)
    assert worst <= s["frame_max_us"] + max(s["commands_us"]) + 500, (worst, s)
    if s["frame_max_at"] < FRAMES - 1:  # the last frame's time is in no line
        assert worst >= s["frame_max_us"] - 500, (worst, s)


def test_the_drive_scenario_stays_within_6_ms_a_frame(fs):
    # Issue 22's "every command within a frame": the drive scenario's 500 frames (walk commands every
    # 10 frames from frame 60, ripple from the guard table at 110, the tripod back at 200, the
    # tripod at 1.2 s, off the table, at 300) on the emulated Pico, whose cycle clock is
    # deterministic. A change is taken on the move at frames 135-137 (hexapod.gaitswitch: the
    # settings, then the swing budget and the rooms, then the slot, one part a frame): 5,741, 5,511
    # and 5,833 us (2026-11-28); in one frame, with the stroke gain made there, 12,973 us. Then two
    # frames over 6 ms were left: 300 (6,200 us: a walk command and the `gait` command) and 310
    # (6,725 us: a walk command and a configure step). Now a walking frame's step waits for the
    # frame's commands and is skipped in a frame that ran one (Robot.defer, as Runner.run), and a
    # command with no turn makes its aims without sines: 6,142 (300), then 5,986 (201, the tabled
    # gait's take), 2026-11-28.
    status, lines, _, _ = pico_loop.board(500, fs, "drive")
    assert status == 0, "\n".join(lines)
    result = pico_loop.summary(lines)
    assert result["drive"][0][:3] == [110, "gait", 0]  # ripple taken
    assert result["drive"][2][:3] == [300, "gait", 0]  # the tripod at 1.2 s asked, checked over frames
    assert result["frames_over_6ms"] == [] and result["frame_max_us"] <= 6000, result["frames_over_6ms"]
