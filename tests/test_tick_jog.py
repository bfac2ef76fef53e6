"""The core's jog mode (hexapod.tick.Robot.jog_foot/jog_joint/jog_pulse/calibrate/go_limp) on a
FrameBuffer, both runtimes: what moves, what is refused and why, leaving the jog."""


def test_jog_api_moves_one_leg_refuses_with_reasons_and_leaves_smoothly(rt):
    out = rt.call("scenarios.tick_jog:jog_session")
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


def test_a_calibration_reaches_the_servo_at_once_even_while_frames_are_held(rt):
    # Issue 24: the console fuzz once found a PCA9685 driving 2118 us on leg 3 femur after
    # `range 3 femur 590 1858`: the robot's pulse had moved, the chip's would only at the next
    # frame sent. Hand-worked: the jog's angle is (2118 - 1500) / 10 us per degree = 61.8 deg;
    # centre 1200 maps it to 1200 + 618 = 1818 us, inside 590..1858 (2118 is not).
    out = rt.call("scenarios.tick_jog:calibrate_reaches_the_chip_at_once")
    assert out[0] == 0 and out[1] == 2118
    assert out[2] == (0, 1818)  # the sink has the new pulse before any tick
    assert out[3] == (0, 1818)  # so the narrowed range never sees 2118 us
    assert out[4] == (25, True)  # FRAME_SERVO: held, the sink keeps the last frame
    # leg 4 femur (dir -1) at centre 1460: its pulse moves 40 us down at once, held frames or not
    reason, moved, top = out[5]
    assert reason == 0 and moved == -40 and top < 2400
