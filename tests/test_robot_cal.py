"""The robot's calibration file (robots/default_cal.py, hexapod.robotcal): the shipped one passes,
many mutations of it fail with one ValueError naming the robot, the place and what is allowed,
identically on CPython and MicroPython; its servo maps give seed 001's pulses (the rows the board
files carried before, centre at angle 0) for every angle."""

import pytest

DELETE = "<delete>"  # scenarios.robot_cal.DELETE
SCENARIO = "scenarios.robot_cal:"

# (path, new value, the message's text after "robot 'default': ")
MUTATIONS = [
    (("SONARS",), DELETE, "calibration: missing key 'SONARS'"),
    (("TRIM",), 0, "calibration: unknown key 'TRIM' (allowed: REFERENCE, SERVOS, SONARS)"),
    (("REFERENCE",), (0, 0), "REFERENCE: expected 3 items (coxa, femur, tibia) in cdeg, got 2"),
    (("REFERENCE",), -9000, "REFERENCE: expected a tuple (coxa, femur, tibia) in cdeg, got int"),
    (("REFERENCE", 2), -9050, "REFERENCE tibia: -9050, allowed whole degrees (a multiple of 100 cdeg)"),
    (("REFERENCE", 2), -90.0, "REFERENCE tibia: -90.0, allowed -18000..18000 (0.01 deg)"),
    (("REFERENCE", 2), 900, "REFERENCE tibia: 900 is outside the robot's tibia limits -18000..0 cdeg"),
    (("REFERENCE", 0), 9100, "REFERENCE coxa: 9100 is outside the robot's coxa limits -9000..9000 cdeg"),
    (("REFERENCE", 1), True, "REFERENCE femur: True, allowed -18000..18000 (0.01 deg)"),
    (("SERVOS",), None, "SERVOS: expected a tuple of rows (leg, joint, centre_us, direction, min_us, max_us), got"),
    (("SERVOS", 17), DELETE, "SERVOS: missing servo leg 6 tibia"),
    (("SERVOS", 4, 0), 1, "SERVOS[4] (leg 1 femur): listed twice (first at SERVOS[1])"),
    (("SERVOS", 0, 0), 7, "SERVOS[0] leg: 7, allowed 1..6"),
    (("SERVOS", 0, 1), "knee", "SERVOS[0] joint: 'knee', allowed coxa, femur, tibia"),
    (("SERVOS", 0), (1, "coxa", 1500, 1, 600), "SERVOS[0]: expected 6 items (leg, joint, centre_us, direction,"),
    (("SERVOS", 0), (1, "coxa", 0x40, 0, 1500, 1, 600, 2400), "SERVOS[0]: expected 6 items (leg, joint,"),
    (("SERVOS", 3, 2), 2450, "SERVOS[3] (leg 2 coxa): need min_us <= centre_us <= max_us, got 600, 2450, 2400"),
    (("SERVOS", 3, 2), 100, "SERVOS[3] (leg 2 coxa): centre_us: 100 is outside 500..2500 us"),
    (("SERVOS", 2, 5), 1400, "SERVOS[2] (leg 1 tibia): need min_us <= centre_us <= max_us, got 600, 1500, 1400"),
    (("SERVOS", 5, 4), 1600, "SERVOS[5] (leg 2 tibia): need min_us <= centre_us <= max_us, got 1600, 1500, 2400"),
    (("SERVOS", 0, 3), 0, "SERVOS[0] (leg 1 coxa): direction: 0, allowed 1 or -1"),
    (("SERVOS", 0, 3), True, "SERVOS[0] (leg 1 coxa) direction: True, allowed an integer"),
    (("SERVOS", 0, 2), "1500", "SERVOS[0] (leg 1 coxa) centre_us: '1500', allowed an integer"),
    (("SERVOS", 0, 4), 600.0, "SERVOS[0] (leg 1 coxa) min_us: 600.0, allowed an integer"),
    (("SERVOS", 0, 5), 2600, "SERVOS[0] (leg 1 coxa): max_us: 2600 is outside 500..2500 us"),
    (("SONARS",), None, "SONARS: expected a tuple of sonar tuples, got NoneType"),
    (("SONARS", 4), DELETE, "SONARS: missing sonar right_rear"),
    (("SONARS", 1, 0), "front", "sonar front: listed twice"),
    (("SONARS", 0, 0), "rear", "SONARS[0] name: 'rear', allowed front, left_front, left_rear, right_front"),
    (("SONARS", 0), ("front", 6, 7, 1300, 0, 0), "SONARS[0]: expected 4 items (name, x, y, heading), got 6"),
    (("SONARS", 0), "front", "SONARS[0]: expected a tuple (name, x, y, heading), got str"),
    (("SONARS", 0, 1), 20000, "sonar front x: 20000, allowed -10000..10000 (0.1 mm)"),
    (("SONARS", 0, 2), 1.5, "sonar front y: 1.5, allowed -10000..10000 (0.1 mm)"),
    (("SONARS", 0, 3), 20000, "SONARS: sensor mounts: front heading 20000 cdeg, allowed -1000..1000"),
    (("SONARS", 0, 3), 0.0, "SONARS: sensor mounts: front: (1300, 0, 0.0), allowed (x, y, heading) integers"),
    (("SONARS", 1, 3), 4500, "SONARS: sensor mounts: left_front heading 4500 cdeg, allowed 8000..10000"),
    (("SONARS", 3, 1), -1000, "SONARS: sensor mounts: right_front x -1000 must be at least 500 (50 mm) ahead"),
    (("SONARS", 2, 2), -2100, "SONARS: sensor mounts: left_rear y -2100 must be > 0 (left)"),
    (("SONARS", 0, 3), 1500, "SONARS: sensor mounts: front heading 1500 cdeg, allowed -1000..1000"),
]


def run_mutations(rt, mutations):
    return rt.call(SCENARIO + "mutations", [m[:2] for m in mutations])


def test_the_shipped_calibration_passes_and_a_copy_too(rt):
    assert rt.call(SCENARIO + "shipped") == ["accepted", "accepted", "accepted", True, 18]


def test_many_bad_calibrations_each_fail_with_a_clear_value_error(rt):
    messages = run_mutations(rt, MUTATIONS)
    for (path, value, want), msg in zip(MUTATIONS, messages, strict=True):
        assert msg.startswith("robot 'default': "), msg
        assert msg[len("robot 'default': ") :].startswith(want), (path, value, msg)
    assert len(set(messages)) == len(messages)  # every mutation is told apart


def test_messages_are_identical_on_both_runtimes(both_runtimes):
    cpython, micropython = both_runtimes.call(SCENARIO + "mutations", [m[:2] for m in MUTATIONS])
    assert cpython == micropython


def test_a_failing_validation_changes_nothing(rt):
    assert rt.call(SCENARIO + "failing_changes_nothing") == (True, True, True)


@pytest.mark.parametrize(
    "name,fragment",
    [
        ("nope", "robot 'nope': no robots/nope_cal.py (the robot's servo calibration and sonar mounts)"),
        ("../default", "robot name '../default': allowed a file name in robots/"),
        (5, "robot name 5"),
    ],
)
def test_loading_an_unknown_robot_is_a_value_error(rt, name, fragment):
    assert fragment in rt.call(SCENARIO + "load_error", name)


def test_servo_maps_give_seed_001_pulses_and_the_mounts_come_in_sonar_order(rt):
    # The rows the board files carried before the move (centre_us at angle 0, direction): every
    # angle inside the joint limits maps to the same pulse, 10 us per degree (seed 001).
    old = [(1500, 1), (1500, 1), (2400, 1)] * 3 + [(1500, 1), (1500, -1), (600, -1)] * 3
    pulses, refs, mounts, fresh = rt.call(SCENARIO + "maps_and_mounts")
    limits = (-9000, 9000, -9000, 9000, -18000, 0)  # robots/default.py LIMITS
    for k, (centre, direction) in enumerate(old):
        lo, hi = limits[2 * (k % 3)], limits[2 * (k % 3) + 1]
        assert pulses[k] == [centre + direction * ((a * 1000 + 5000) // 10000) for a in range(lo, hi + 1, 50)], k
    assert refs == [0, 0, -9000] and fresh
    assert mounts == (
        (1300, 0, 0),
        (1000, 2100, 9000),
        (-1000, 2100, 9000),
        (1000, -2100, -9000),
        (-1000, -2100, -9000),
    )
