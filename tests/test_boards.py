"""Board files and their validation: the three boards pass; many mutations of them fail with a clear
ValueError naming the board, the place and the rule, identically on CPython and MicroPython."""

import pytest

BOARDS = ("pico", "esp32_devkit", "feather_rp2040")
DELETE = "<delete>"
APPEND = "<append>"

P, E, F = BOARDS
# (board, path, new value, fragment the message must contain)
MUTATIONS = [
    (P, (), [], "board '?': board: expected a dict, got list"),
    (P, ("i2cc",), {}, "unknown key 'i2cc'"),
    (P, ("servos",), DELETE, "board: missing key 'servos'"),
    (P, ("name",), "", "name: '', allowed a non-empty identifier"),
    (P, ("name",), 5, "name: 5, allowed"),
    (P, ("runtime",), "cpython", "runtime: 'cpython', allowed micropython or circuitpython"),
    (P, ("i2c",), None, "i2c: expected a dict, got NoneType"),
    (P, ("i2c", "id"), -1, "i2c.id: -1, allowed 0..9"),
    (P, ("i2c", "id"), None, "i2c.id: None, allowed 0..9"),
    (P, ("i2c", "freq"), 5000000, "i2c.freq: 5000000, allowed 10000..1000000 Hz"),
    (P, ("i2c", "freq"), 400000.0, "i2c.freq: 400000.0"),
    (P, ("i2c", "sda"), 5, "i2c.scl: pin 5 is already used as i2c.sda"),
    (P, ("i2c", "scl"), DELETE, "i2c: missing key 'scl'"),
    (P, ("i2c", "baud"), 1, "i2c: unknown key 'baud' (allowed: id, sda, scl, freq)"),
    (P, ("i2c", "sda"), 99, "i2c.sda: 99, allowed a GPIO number 0..63 or a pin name"),
    (P, ("i2c", "sda"), "4x-", "i2c.sda: '4x-', allowed a GPIO number"),
    (P, ("i2c", "sda"), True, "i2c.sda: True, allowed"),
    (F, ("i2c", "sda"), 3, "i2c.sda: 3, allowed a `board` pin name such as 'D5'"),
    (F, ("i2c", "id"), "0", "i2c.id: '0', allowed 0..9"),
    (P, ("pca9685", "pwm_hz"), 1000, "pca9685.pwm_hz: 1000, allowed 40..333 Hz"),
    (P, ("pca9685", "chips"), [], "pca9685.chips: no chip given"),
    (P, ("pca9685", "chips"), 0x40, "pca9685.chips: expected a tuple of chip dicts, got int"),
    (P, ("pca9685", "chips", 1, "address"), 0x40, "pca9685.chips[1].address: 0x40 is listed twice"),
    (P, ("pca9685", "chips", 1, "address"), 0x70, "0x70 is the PCA9685 all-call address"),
    (P, ("pca9685", "chips", 0, "address"), 0x20, "pca9685.chips[0].address: 32, allowed 64..127"),
    (P, ("pca9685", "chips", 0, "osc_hz"), 30000000, "pca9685.chips[0].osc_hz: 30000000, allowed 22500000..27500000"),
    (P, ("pca9685", "chips", 0), (0x40, 25000000), "pca9685.chips[0]: expected a dict, got tuple"),
    (P, ("pca9685", "chips", 0, "trim"), 1, "pca9685.chips[0]: unknown key 'trim'"),
    (P, ("pca9685", "chips", 1), DELETE, "servos[9] (leg 4 coxa) address: 65 is not one of the chips (0x40)"),
    (P, ("servos", 1, 3), 0, "servos[1] (leg 1 femur): chip 0x40 channel 0 already drives leg 1 coxa"),
    (E, ("servos", 17, 3), 0, "servos[17] (leg 6 tibia): chip 0x41 channel 0 already drives leg 4 coxa"),
    (P, ("servos", 17), DELETE, "servos: missing servo leg 6 tibia"),
    (P, ("servos",), [], "servos: missing servo leg 1 coxa"),
    (P, ("servos", 4, 0), 1, "servos[4] (leg 1 femur): listed twice (first at servos[1])"),
    (P, ("servos", 0, 0), 7, "servos[0] leg: 7, allowed 1..6"),
    (P, ("servos", 0, 0), "1", "servos[0] leg: '1', allowed 1..6"),
    (P, ("servos", 0, 1), "knee", "servos[0] joint: 'knee', allowed coxa, femur, tibia"),
    (P, ("servos", 0, 2), 0x42, "servos[0] (leg 1 coxa) address: 66 is not one of the chips (0x40, 0x41)"),
    (P, ("servos", 0, 2), True, "servos[0] (leg 1 coxa) address: True is not one of the chips"),
    (P, ("servos", 0, 3), 16, "servos[0] (leg 1 coxa) channel: 16, allowed 0..15"),
    (P, ("servos", 0, 3), -1, "channel: -1, allowed 0..15"),
    (P, ("servos", 0, 6), 400, "servos[0] (leg 1 coxa): min_us: 400 is outside 500..2500 us"),
    (P, ("servos", 0, 7), 2600, "servos[0] (leg 1 coxa): max_us: 2600 is outside 500..2500 us"),
    (P, ("servos", 3, 4), 2450, "servos[3] (leg 2 coxa): need min_us <= centre_us <= max_us, got 600, 2450, 2400"),
    (P, ("servos", 3, 4), 100, "centre_us: 100 is outside 500..2500 us"),
    (P, ("servos", 0, 5), 0, "servos[0] (leg 1 coxa): direction: 0, allowed 1 or -1"),
    (P, ("servos", 0, 4), "1500", "servos[0] (leg 1 coxa) centre_us: '1500', allowed an integer"),
    (P, ("servos", 0, 6), 500.0, "servos[0] (leg 1 coxa) min_us: 500.0, allowed an integer"),
    (P, ("servos", 0, 5), True, "direction: True, allowed an integer"),
    (P, ("servos", 0), [1, "coxa", 0x40, 0], "servos[0]: expected 8 items (leg, joint, address, channel,"),
    (P, ("servos", 0), "coxa", "servos[0]: expected a tuple (leg, joint"),
    (P, ("servos",), (APPEND, (7, "coxa", 0x41, 9, 1500, 1, 600, 2400)), "servos[18] leg: 7, allowed 1..6"),
    (P, ("servos",), (APPEND, (6, "coxa", 0x41, 9, 1500, 1, 600, 2400)), "servos[18] (leg 6 coxa): listed twice"),
    (P, ("servos",), None, "servos: expected a tuple of servo tuples, got NoneType"),
    (P, ("sensors",), None, "sensors: expected a tuple of sensor tuples, got NoneType"),
    (P, ("sensors", 0, 2), DELETE, "sensors[0]: expected 6 items (name, trigger, echo, x, y, heading), got 5"),
    (P, ("sensors", 2, 2), None, "sensor left_rear echo: no pin given"),
    (P, ("sensors", 2, 1), None, "sensor left_rear trigger: no pin given"),
    (P, ("sensors", 1, 1), 7, "sensor left_front trigger: pin 7 is already used as sensor front echo"),
    (P, ("sensors", 0, 1), 4, "sensor front trigger: pin 4 is already used as i2c.sda"),
    (E, ("sensors", 3, 2), 34, "sensor right_front echo: pin 34 is already used as sensor front echo"),
    (F, ("sensors", 4, 1), "SCL", "sensor right_rear trigger: pin 'SCL' is already used as i2c.scl"),
    (F, ("sensors", 0, 1), 6, "sensor front trigger: 6, allowed a `board` pin name"),
    (P, ("sensors", 0, 2), [7], "sensor front echo: [7], allowed a GPIO number"),
    (P, ("sensors", 0, 0), "rear", "sensors[0] name: 'rear', allowed front, left_front, left_rear"),
    (P, ("sensors", 1, 0), "front", "sensor front: listed twice"),
    (P, ("sensors", 4), DELETE, "sensors: missing sensor right_rear"),
    (P, ("sensors", 0, 5), 20000, "sensor front heading: 20000, allowed -18000..18000 (0.01 deg)"),
    (P, ("sensors", 0, 3), 20000, "sensor front x: 20000, allowed -10000..10000 (0.1 mm)"),
    (P, ("sensors", 0, 4), 1.5, "sensor front y: 1.5, allowed"),
    (P, ("sensors", 0), ("front", 6, 7), "sensors[0]: expected 6 items"),
    (P, ("sensors", 0), {}, "sensors[0]: expected a tuple (name, trigger"),
    (P, ("sensors", 1, 5), 4500, "sensors: sensor mounts: left_front heading 4500 cdeg, allowed 8000..10000"),
    (E, ("sensors", 4, 3), 1000, "sensors: sensor mounts: right_front x 1000 must be at least 500 (50 mm) ahead"),
    (F, ("sensors", 2, 4), -2100, "sensors: sensor mounts: left_rear y -2100 must be > 0 (left)"),
    (P, ("follow",), "left", "follow: expected a dict, got str"),
    (P, ("follow",), {"side": "left"}, "follow: missing key 'setpoint'"),
    (P, ("follow",), {"side": "left", "setpoint": 800, "gain": 1}, "follow: unknown key 'gain'"),
    (P, ("follow",), {"side": "up", "setpoint": 800}, "follow: side: 'up', allowed 'left' or 'right'"),
    (E, ("follow",), {"side": "left", "setpoint": 80}, "follow: setpoint: 80 is outside 400..5000 (0.1 mm"),
    (F, ("follow",), {"side": "right", "setpoint": 800, "speed": 0}, "follow: speed: 0 is outside 100..3000"),
    (P, ("follow",), {"side": "right", "setpoint": 800, "form": "crab"}, "follow: form: 'crab', allowed 'yaw'"),
]


# check() imports the whole core from source (board -> follow -> tick -> walk -> _walk_viper) inside the VM:
# its compiler fits in ~250 KB, but whether a given heap does depends on fragmentation (main at
# 97c1045 failed at 236-248 KB and at 292 KB, passed at 252-288 KB; measured 2026-11-24): 512 KB.
HEAP = "512k"


def test_the_three_boards_pass_and_unchanged_copies_pass_too(rt):
    assert (
        rt.call("scenarios.boards:good_boards", BOARDS) == [(True, "accepted", "accepted", 18)] * 3 + ["accepted"] * 4
    )


def test_many_bad_boards_each_fail_with_a_clear_value_error(rt):
    messages = rt.with_heapsize(HEAP).call("scenarios.boards:checks", [m[:3] for m in MUTATIONS])
    for (name, path, value, fragment), msg in zip(MUTATIONS, messages, strict=True):
        assert fragment in msg, (name, path, value, msg)
        if path:
            assert msg.startswith("board %r: " % (name if path != ("name",) else "?")), msg
    assert len(set(messages)) == len(messages)  # every mutation is told apart


def test_messages_are_identical_on_both_runtimes(both_runtimes):
    cpython, micropython = both_runtimes.with_heapsize(HEAP).call("scenarios.boards:checks", [m[:3] for m in MUTATIONS])
    assert cpython == micropython


@pytest.mark.parametrize("name", BOARDS)
def test_every_channel_and_pin_mutation_is_caught(rt, name):
    # systematic: each servo moved onto every other servo's channel, each sensor pin onto every other pin
    total, caught = rt.call("scenarios.boards:channel_and_pin_moves", name)
    assert total == 18 * 17 + 10 * 11
    assert caught == total


def test_a_failing_validation_changes_nothing(rt):
    assert rt.call("scenarios.boards:failing_validation") == (True, True, True)


@pytest.mark.parametrize(
    "name,fragment",
    [("nope", "board 'nope': no boards/nope.py"), ("../pico", "allowed a file name"), (5, "board name 5")],
)
def test_loading_an_unknown_board_is_a_value_error(rt, name, fragment):
    assert fragment in rt.call("scenarios.boards:load_error", name)


def test_tables_come_out_in_leg_joint_and_driver_order(rt):
    table, sensor_pins, same_order = rt.call("scenarios.boards:pico_tables")
    assert same_order
    assert table[0] == (0x40, 0, 1, 600) and table[17] == (0x41, 8, -1, 600)
    assert [row[:2] for row in table] == [(0x40 if k < 9 else 0x41, k % 9) for k in range(18)]
    assert sensor_pins == ((6, 7), (8, 9), (10, 11), (12, 13), (14, 15))
