"""Faults on the PCA9685 side: the loop keeps running, the fault is reported, and no channel ever
outputs a pulse outside its servo's calibrated range (read from the chip model's outputs).

The firmware side is tests/scenarios/pca9685.py (the rig of test_pca9685_driver.py); its `unsafe()`
lists every output neither off nor inside its servo's min..max, give or take half a count."""


def test_nack_mid_frame_never_outputs_half_a_channel(rt):
    st, bad, first_new, rest_old, chip1_new, st2, healed, errors, errno = rt.call("scenarios.pca9685:nack_mid_frame")
    assert st == 2  # FAILED: no retries allowed
    assert bad == []
    assert first_new and rest_old and chip1_new  # channels 0-2 complete, 3-15 kept the old frame
    assert st2 == 0 and healed
    assert (errors, errno) == (1, 19)


def test_nack_is_retried_within_the_frame(rt):
    assert rt.call("scenarios.pca9685:nack_retried") == [1, True, [], 2]  # RETRIED, the third attempt went through


def test_timeout_reported_as_etimedout(rt):
    sts, errno, bad, final = rt.call("scenarios.pca9685:timeouts")
    assert sts == [2, 2, 1, 0]  # 2 + 2 attempts fail, the 5th hangs too, the 6th gets through
    assert errno == 110
    assert bad == []
    assert final


def test_brownout_between_frames_is_found_and_healed(rt):
    sts, bad, seen, final, mode1, prescale = rt.call("scenarios.pca9685:brownout")
    assert bad == []
    assert seen == 1
    assert 4 in sts[7:12]  # REINIT within check_every frames of the reset
    assert all(s in (0, 4) for s in sts)
    assert final and mode1 == 0x20 and prescale == 125


def test_reset_fault_on_the_wire_mid_run(rt):
    # The chip resets just before its MODE1 read-back: found at once, re-initialised, frame sent.
    assert rt.call("scenarios.pca9685:reset_on_the_wire") == [4, [], True, 1]


def test_unplugged_chip_at_boot_loop_runs_and_it_comes_back(rt):
    sts, mid, bad, final, offline, codes = rt.call("scenarios.pca9685:unplugged_at_boot")
    assert mid == [True, [0, 0], True]  # chip 0 drives its servos; chip 1's are simply not driven
    assert all(s & 8 for s in sts[:6])  # OFFLINE reported every frame while unplugged
    assert 4 in sts[6:]  # REINIT once plugged in
    assert sts[-1] == 0
    assert bad == [] and final and offline is False and codes == []


def test_random_fault_soak_is_safe_and_identical_in_both_runtimes(both_runtimes):
    cp, mp = both_runtimes.call("scenarios.pca9685:soak", 150, 12345)
    assert cp == mp  # same statuses, errors and outputs, frame by frame
    bad, sts, last, final, errors, clamped = cp
    assert len(sts) == 150
    assert bad == []
    assert last == 0 and final
    assert errors > 10 and clamped > 100
    assert any(s & 1 for s in sts) and any(s & 2 for s in sts) and any(s & 4 for s in sts)


def test_chip_put_to_sleep_and_woken_without_restart_is_recovered(rt):
    """Someone else's sleep/wake leaves RESTART pending and the outputs stopped: the read-back sees it."""
    stopped, sts, running, final, bad = rt.call("scenarios.pca9685:sleep_wake_without_restart")
    assert stopped == [False, 0]
    assert 4 in sts and running and final and bad == []
