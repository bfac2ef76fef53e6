"""Power-up (issue 20, point 1): no pulse before `stand` unless the board file asks for a stand at
boot and the calibration file is valid. Both runtimes, main.main with its console on the stub
machine; the PCA9685 models say what reached the servos."""

import pytest

RELAXED, STANDING = 0, 3  # hexapod.tick modes


@pytest.mark.parametrize(
    "cal, setting, word",
    [
        ("none", None, "relaxed_uncalibrated"),
        ("none", "stand", "relaxed_uncalibrated"),
        ("corrupt", "stand", "relaxed_uncalibrated"),
        ("corrupt", "relaxed", "relaxed_uncalibrated"),
        ("valid", None, "relaxed"),
        ("valid", "relaxed", "relaxed"),
    ],
)
def test_boot_sends_no_pulse_until_stand(rt, tmp_path, cal, setting, word):
    # 300 frames (6 s): every PCA9685 channel stays off, the robot relaxed, status says why.
    assert rt.call("scenarios.power_up:boot", str(tmp_path), cal, setting, 300) == (
        word,
        RELAXED,
        -1,
        0,
    )


def test_calibrated_board_with_boot_stand_stands(rt, tmp_path):
    word, mode, first, most = rt.call("scenarios.power_up:boot", str(tmp_path), "valid", "stand", 300)
    assert (word, mode, first) == ("stood", STANDING, 0)  # the very first frame (index 0) drives the servos
    # Soft start, seen on the PCA9685 models: at most one leg group (2 legs, 6 servos) switches on
    # in a frame, where all 18 did before.
    assert most == 6


def test_an_uncalibrated_board_stands_when_told(rt, tmp_path):
    # `stand` typed at frame 49 (0-based; one line every 50 frames): nothing before it, standing
    # well within the 250 frames after; typed in frame 49's poll, sent in frame 50.
    word, mode, first, most = rt.call("scenarios.power_up:boot", str(tmp_path), "none", None, 300, ["stand"], 50)
    assert most == 6  # the soft start
    assert word == "relaxed_uncalibrated" and mode == STANDING and first == 50


def test_flash_says_what_the_board_does_after_its_reset(monkeypatch):
    from hexapod import board as boards
    from hexapod_host.serial import flash

    board = boards.load("pico")
    assert "boot" not in board  # the shipped board files boot relaxed
    assert flash.after_reset("pico").startswith("after its reset the board stays relaxed: no servo moves until")
    monkeypatch.setitem(board, "boot", "stand")
    assert flash.after_reset("pico").startswith("after its reset the board stands the robot up")


@pytest.mark.parametrize("bad", ["Stand", "stood", "", 1, True, None, ("stand",), "relax"])
def test_bad_boot_settings_are_refused(monkeypatch, bad):
    from hexapod import board as boards

    board = boards.load("pico")
    monkeypatch.setitem(board, "boot", bad)
    with pytest.raises(ValueError) as err:
        boards.validate(board)
    assert str(err.value) == "board 'pico': boot: %r, allowed 'relaxed' or 'stand'" % (bad,)


def test_main_releases_the_boot_only_modules(rt, tmp_path):
    # MicroPython: forgotten once the runner is built (their heap back to the loop); CPython, where
    # the tests share one process, keeps them (hexapod.release is a no-op there).
    kept = rt.name == "cpython"
    assert rt.call("scenarios.power_up:released", str(tmp_path)) == [kept] * 6


def test_no_command_runs_before_the_calibration_file_is_in_force(rt, tmp_path):
    # main.main leaves the calibration file's load to the first frames (issue 22: the first frame
    # sooner). A client's lines already waiting at power-up wait for it: `status` tells the file's
    # calibration and the boot's outcome, a `pulse` inside the robot file's range but outside the
    # file's is refused, and every frame that drives a servo (the `stand`) does so on the file's
    # calibration, never on the robot file's.
    typed = ["status", "pulse 1 coxa LO", "stand"]
    said, seen, want, mode = rt.call("scenarios.power_up:early", str(tmp_path), typed)
    assert len(said) == 3 and said[0].startswith("ok frames ") and " cal file boot relaxed " in said[0], said
    assert said[1].startswith("err "), said
    assert said[2].startswith("ok "), said
    assert mode == STANDING and seen == [want], (said, seen[:1], want)


def test_a_call_while_the_boot_loads_the_file_finishes_the_load_first(rt, tmp_path):
    # console.do (the REPL's way in, after a Ctrl-C in the first frames) runs on the file's
    # calibration too: the load under way is finished first.
    reply, maps, want, pending = rt.call("scenarios.power_up:early_do", str(tmp_path), "status")
    assert pending and maps == want
    assert reply.startswith("ok frames ") and " cal file boot relaxed " in reply, reply


def test_a_load_interrupted_in_a_step_starts_over(rt, tmp_path):
    # A Ctrl-C (here: the file's open raising KeyboardInterrupt) inside one of the load's steps
    # leaves a new load in its place, not a dead one: the next call finishes it, on the file's
    # calibration.
    raised, pending, reply, maps, want = rt.call("scenarios.power_up:interrupted", str(tmp_path))
    assert raised == "KeyboardInterrupt" and pending
    assert maps == want and reply.startswith("ok frames ") and " cal file boot relaxed " in reply, reply
