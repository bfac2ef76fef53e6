"""The core's jog mode (hexapod.tick.Robot.jog_foot/jog_joint/jog_pulse/calibrate/go_limp) on a
FrameBuffer, both runtimes: what moves, what is refused and why, leaving the jog."""


def test_jog_api_moves_one_leg_refuses_with_reasons_and_leaves_smoothly(rt):
    # 512k: the VM compiles the whole core from source here; at 256k the board file's check ran
    # out of heap on some runs (this test measures behaviour, not memory).
    out = rt.with_heapsize("512k").call("scenarios.tick_jog:jog_session")
    assert out[0] == 0
    mode, pulses = out[1]
    # leg 2 only; seed 004 IK of (130, 0, -80) mm: 0, 8.11, -90.83 deg; pico.py leg 2 rows
    assert mode == 5 and pulses == [0, 0, 0, 1500, 1581, 1492] + [0] * 12
    assert out[2] == (26, 1, out[2][2]) and out[2][2] > 0  # JOG_IK, leg.TOO_FAR
    assert out[3] == (26, 8, 500)  # TIBIA_HIGH by 5 deg
    assert out[4] == (27, 4, 2, 50)  # JOG_SERVO, servo 4 (leg 2 femur), ABOVE_MAX by 50 us
    assert out[5] == (27, 4, 1, 19)  # femur at 8.11 deg is 1581 us: 19 below a 1600 minimum
    assert out[6] is True  # refusals changed nothing
    assert out[7] == [
        "leg: 6, allowed 0..5 (legs 1..6)",
        "joint: 3, allowed 0 coxa, 1 femur, 2 tibia",
        "pulse: need a whole number (us), got 1500.0",
        "direction: 0, allowed 1 or -1",
        "range: min_us 2400 must be below max_us 600",
    ]
    assert out[8] == (0, [1600, 0, 0, 1500, 1581, 1492])  # one servo of a limp leg: only it
    assert out[9] == 0
    # leaving the jog: the posture starts where the jog put leg 2; its first frame moves the foot
    # one posture step (at most 2 mm: 1.3 deg here) up from there
    assert all(abs(a - b) <= 150 for a, b in zip(out[10], (0, 811, -9083), strict=True)), out[10]
    assert out[11] == 3  # standing
    assert out[12] == (0, True)
    assert out[13] == 0  # no frame held on the way (leg 1's stretched limp joints included)
