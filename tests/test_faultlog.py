"""The fault log (issue 20, point 6): hexapod.faultlog's words and drivers.faultkeep's keepers, on
both runtimes. Every expected word is packed by hand from the layout in faultlog's docstring:
MARK 0x10000000 | kind << 25 | what << 22 | frame (22 bits)."""

import pytest

I2C, BROWNOUT, SONAR, WATCHDOG, BATTERY = 1, 2, 3, 4, 5
SCRATCH = [0x4005800C, 0x40058010, 0x40058014, 0x40058018]  # RP2040 datasheet: WATCHDOG_BASE + 0x0C..0x18


def word(kind, what, frame):
    return 0x10000000 + kind * 0x02000000 + what * 0x00400000 + frame % 0x400000


def test_words_by_hand(rt):
    out = rt.call(
        "scenarios.faultlog:pushes",
        [(I2C, 1, 1234), (SONAR, 4, 0x400000 + 5), (BATTERY, 0, 99), (WATCHDOG, 0, 0), (BROWNOUT, 1, 77)],
    )
    assert word(I2C, 1, 1234) == 0x124004D2
    assert out[0] == [[0x124004D2, 0, 0, 0], [[I2C, 1, 1234, False]]]
    assert out[1][1][1] == [SONAR, 4, 5, False]  # the frame count is kept modulo 2**22
    assert out[3][0] == [word(I2C, 1, 1234), word(SONAR, 4, 5), word(BATTERY, 0, 99), word(WATCHDOG, 0, 0)]
    # a fifth fault pushes the oldest out
    assert out[4][0] == [word(SONAR, 4, 5), word(BATTERY, 0, 99), word(WATCHDOG, 0, 0), word(BROWNOUT, 1, 77)]
    assert [e[0] for e in out[4][1]] == [SONAR, BATTERY, WATCHDOG, BROWNOUT]


def test_rp2_scratch_registers_hold_the_log_across_a_reset(rt):
    first, cells, kept, got = rt.call("scenarios.faultlog:scratch", [(I2C, 0, 10), (SONAR, 2, 20)])
    assert first == [0, []]  # power-on: the scratch registers read 0
    assert cells == [[SCRATCH[0], word(I2C, 0, 10)], [SCRATCH[1], word(SONAR, 2, 20)], [SCRATCH[2], 0], [SCRATCH[3], 0]]
    assert kept == 2
    assert got == [[I2C, 0, 10, True], [SONAR, 2, 20, True]]


@pytest.mark.parametrize(
    "fill, preset",
    [
        (0xFFFFFFFF, []),  # all ones: no mark-only pattern survives (bits above 28 set)
        (0x0000BEEF, []),  # no MARK
        (0, [(SCRATCH[1], 0x10000000 | 6 << 25)]),  # marked, kind 6 does not exist
        (0, [(SCRATCH[2], 0x10000000)]),  # marked, kind 0
    ],
)
def test_foreign_words_are_ignored_at_load(rt, fill, preset):
    first, _, kept, got = rt.call("scenarios.faultlog:scratch", [(BATTERY, 0, 5)], fill, preset)
    assert first == [0, []]
    assert (kept, got) == (1, [[BATTERY, 0, 5, True]])


def test_a_kept_word_between_foreign_ones_moves_to_the_front(rt):
    preset = [(SCRATCH[0], 0xDEAD), (SCRATCH[2], word(WATCHDOG, 0, 3))]
    first, _, kept, got = rt.call("scenarios.faultlog:scratch", [], 0, preset)
    assert first == [1, [[WATCHDOG, 0, 3, True]]]


def test_rtc_memory_bytes_little_endian(rt):
    data, kept, got = rt.call("scenarios.faultlog:rtc", [(I2C, 1, 1234)])
    assert data == [0xD2, 0x04, 0x40, 0x12] + [0] * 12
    assert (kept, got) == (1, [[I2C, 1, 1234, True]])


def test_rtc_memory_shorter_than_the_log_reads_as_empty(rt):
    data, kept, got = rt.call("scenarios.faultlog:rtc", [], b"\xd2\x04")
    assert (kept, got) == (0, [])


@pytest.mark.parametrize("n_new, kept", [(0, 4), (1, 3), (3, 1), (4, 0), (6, 0)])
def test_new_faults_push_out_the_kept_ones_first(rt, n_new, kept):
    got_kept, got = rt.call("scenarios.faultlog:kept_then_new", n_new)
    assert got_kept == kept
    assert [e[3] for e in got] == [True] * kept + [False] * (4 - kept)
    new = [[I2C, 1, 7 + k, False] for k in range(n_new)][-4:]
    assert got[kept:] == new


@pytest.mark.parametrize("keeper", ["rp2", "rtc", None])
def test_recording_allocates_nothing_in_the_vm(mp, keeper):
    assert mp.call("scenarios.faultlog:record_heap", keeper) == 0


# -- the loop notices faults (the stub board: PCA9685 and HC-SR04 models) ----------------------
# Frame k is the runner's k-th step (counted from 0). A chip unplugged before frame k fails its
# write in frame k. The round robin pings sonar 2 (left_rear) every 5th frame and collects the
# echo in the next; a ping whose echo never rose is a fault in the frame it is collected.


def faults_reply(rt, plan):
    lines, words = rt.call("scenarios.faultlog:on_the_board", plan)
    assert len(lines) == 1
    return lines[0], words


def test_a_chip_unplugged_for_many_frames_is_one_fault(rt):
    line, _ = faults_reply(rt, [(10, "unplug_0x41")])
    assert line == "ok faults 1 logged (oldest first) i2c 0x41 frame 10"


def test_a_chip_unplugged_again_after_good_frames_is_a_second_fault(rt):
    line, _ = faults_reply(rt, [(10, "unplug_0x41"), (20, "replug_0x41"), (40, "unplug_0x41")])
    first, second = line.split("; ")
    assert first == "ok faults 2 logged (oldest first) i2c 0x41 frame 10"
    # the replugged chip is set up again by the driver (offline -> init) within its retry period, then
    # frames go through; its next failure is frame 40
    assert second == "i2c 0x41 frame 40"


def test_a_chip_found_reset_is_a_brownout(rt):
    line, words = faults_reply(rt, [(10, "reset_0x41")])
    assert line.startswith("ok faults 1 logged (oldest first) brownout 0x41 frame ")
    frame = int(line.split()[-1])
    assert 10 <= frame < 20  # the driver reads MODE1 back every 10 frames (docs/pca9685.md)
    assert words[0] == word(BROWNOUT, 1, frame)


def test_a_sonar_without_echo_is_one_fault_until_it_answers_again(rt):
    line, _ = faults_reply(rt, [(10, "mute_2"), (30, "unmute_2"), (45, "mute_2")])
    parts = line.split("; ")
    assert parts[0].startswith("ok faults 2 logged (oldest first) sonar left_rear frame ")
    f1 = int(parts[0].split()[-1])
    f2 = int(parts[1].split()[-1])
    assert parts[1] == "sonar left_rear frame %d" % f2
    assert 10 <= f1 < 16 and 45 <= f2 < 51  # the first of its pings (every 5 frames) after the mute


def test_a_watchdog_reset_is_logged_once_and_clear_empties_the_log(rt):
    line, _ = faults_reply(rt, [(0, "wdt"), (1, "wdt")])
    assert line == "ok faults 1 logged (oldest first) watchdog frame 0"
    line, words = faults_reply(rt, [(5, "unplug_0x41"), (10, "replug_0x41"), (30, "clear")])
    assert (line, words) == ("ok faults none", [0, 0, 0, 0])


def test_bad_faults_lines_are_refused_and_change_nothing(rt):
    bad = ["faults x", "faults clear now", "faults CLEAR", "faults 1", "faults clear clear", "faults -"]
    out, same, nonempty = rt.call("scenarios.faultlog:refused", bad)
    assert nonempty and same
    for line, got in zip(bad, out, strict=True):
        arg = line[len("faults ") :]
        assert got == ["err faults: need clear or nothing (list), got %r" % arg], line
