"""Board files and their validation: the four boards pass; many mutations of them fail with a clear
ValueError naming the board, the place and the rule, identically on CPython and MicroPython. A
board file holds the board's data only: the robot's calibration and sonar mounts are refused
there with a message saying where they went (tests/test_robot_cal.py checks those files)."""

import pytest

BOARDS = ("pico", "esp32_devkit", "feather_rp2040", "feather_rp2040_micropython")
DELETE = "<delete>"
APPEND = "<append>"

P, E, F, _ = BOARDS
# (board, path, new value, fragment the message must contain)
MUTATIONS = [
    (P, (), [], "board '?': board: expected a dict, got list"),
    (P, ("i2cc",), {}, "unknown key 'i2cc'"),
    (P, ("channels",), DELETE, "board: missing key 'channels'"),
    (P, ("name",), "", "name: '', allowed a non-empty identifier"),
    (P, ("name",), 5, "name: 5, allowed"),
    (P, ("runtime",), "cpython", "runtime: 'cpython', allowed micropython or circuitpython"),
    (P, ("arch",), DELETE, "board: missing key 'arch'"),
    (P, ("arch",), "armv7", "arch: 'armv7', allowed an mpy-cross -march name: x86, x64, armv6, armv6m"),
    (E, ("arch",), None, "arch: None, allowed an mpy-cross -march name"),
    (F, ("arch",), "armv6m", "arch: 'armv6m', allowed None: CircuitPython boards get .py sources, no mpy-cross"),
    (P, ("servos",), (), 'servos: moved: the channel map stays here as "channels"; the calibration moved to robots/'),
    (E, ("sensors",), (), 'sensors: moved: "sonars": (name, trigger, echo) stay here; the mounts moved to robots/'),
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
    (P, ("pca9685", "chips", 1), DELETE, "channels[3][0] (leg 4 coxa) address: 65 is not one of the chips (0x40)"),
    (P, ("channels", 0, 1, 1), 0, "channels[0][1] (leg 1 femur): chip 0x40 channel 0 already drives leg 1 coxa"),
    (E, ("channels", 5, 2, 1), 0, "channels[5][2] (leg 6 tibia): chip 0x41 channel 0 already drives leg 4 coxa"),
    (P, ("channels", 5), DELETE, "channels: expected 6 items (one per leg: ((address, channel) of its coxa, femur"),
    (P, ("channels",), [], "channels: expected 6 items"),
    (P, ("channels", 2), ((0x40, 6), (0x40, 7)), "channels[2]: expected 3 items ((address, channel) of its coxa"),
    (P, ("channels", 0, 2), (0x40,), "channels[0][2] (leg 1 tibia): expected 2 items (address, channel), got 1"),
    (P, ("channels", 0, 2), 0x40, "channels[0][2] (leg 1 tibia): expected a tuple (address, channel), got int"),
    (P, ("channels", 0, 0, 0), 0x42, "channels[0][0] (leg 1 coxa) address: 66 is not one of the chips (0x40, 0x41)"),
    (P, ("channels", 0, 0, 0), True, "channels[0][0] (leg 1 coxa) address: True is not one of the chips"),
    (P, ("channels", 0, 0, 1), 16, "channels[0][0] (leg 1 coxa) channel: 16, allowed 0..15"),
    (P, ("channels", 0, 0, 1), -1, "channel: -1, allowed 0..15"),
    (P, ("channels", 0, 0, 1), 1.0, "channels[0][0] (leg 1 coxa) channel: 1.0, allowed 0..15"),
    (P, ("channels",), None, "channels: expected a tuple (one per leg"),
    (P, ("sonars",), None, "sonars: expected a tuple of sonar tuples, got NoneType"),
    (P, ("sonars", 0, 2), DELETE, "sonars[0]: expected 3 items (name, trigger, echo), got 2"),
    (P, ("sonars", 2, 2), None, "sonar left_rear echo: no pin given"),
    (P, ("sonars", 2, 1), None, "sonar left_rear trigger: no pin given"),
    (P, ("sonars", 1, 1), 7, "sonar left_front trigger: pin 7 is already used as sonar front echo"),
    (P, ("sonars", 0, 1), 4, "sonar front trigger: pin 4 is already used as i2c.sda"),
    (E, ("sonars", 3, 2), 34, "sonar right_front echo: pin 34 is already used as sonar front echo"),
    (F, ("sonars", 4, 1), "SCL", "sonar right_rear trigger: pin 'SCL' is already used as i2c.scl"),
    (F, ("sonars", 0, 1), 6, "sonar front trigger: 6, allowed a `board` pin name"),
    (P, ("sonars", 0, 2), [7], "sonar front echo: [7], allowed a GPIO number"),
    (P, ("sonars", 0, 0), "rear", "sonars[0] name: 'rear', allowed front, left_front, left_rear"),
    (P, ("sonars", 1, 0), "front", "sonar front: listed twice"),
    (P, ("sonars", 4), DELETE, "sonars: missing sonar right_rear"),
    (P, ("sonars", 0), ("front", 6, 7, 1300, 0, 0), "sonars[0]: expected 3 items (name, trigger, echo), got 6"),
    (P, ("sonars", 0), {}, "sonars[0]: expected a tuple (name, trigger"),
    (P, ("follow",), "left", "follow: expected a dict, got str"),
    (P, ("follow",), {"side": "left"}, "follow: missing key 'setpoint'"),
    (P, ("follow",), {"side": "left", "setpoint": 800, "gain": 1}, "follow: unknown key 'gain'"),
    (P, ("follow",), {"side": "up", "setpoint": 800}, "follow: side: 'up', allowed 'left' or 'right'"),
    (E, ("follow",), {"side": "left", "setpoint": 80}, "follow: setpoint: 80 is outside 400..5000 (0.1 mm"),
    (F, ("follow",), {"side": "right", "setpoint": 800, "speed": 0}, "follow: speed: 0 is outside 100..3000"),
    (
        P,
        ("follow",),
        {"side": "right", "setpoint": 800, "form": "zigzag"},
        "follow: form: 'zigzag', allowed 'yaw', 'sweeps' or 'crab'",
    ),
]


# check() used to import the whole core from source (board -> follow -> tick -> walk -> _walk_viper)
# inside the VM, which needed a 512 KB heap; board.py now imports only hexapod.check, .limits and
# .sensors (test_board_validation_imports_nothing_above_the_data_it_checks). A small heap on
# purpose, to keep it so: these checks ran at 96 KB (2026-11-28), not at 80 KB.
HEAP = "256k"


def test_the_four_boards_pass_and_unchanged_copies_pass_too(rt):
    assert (
        rt.call("scenarios.boards:good_boards", BOARDS) == [(True, "accepted", "accepted", 18)] * 4 + ["accepted"] * 4
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
    # systematic: each servo moved onto every other servo's channel, each sonar pin onto every other pin
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
    table, sonar_pins = rt.call("scenarios.boards:pico_tables")
    assert [row[2] for row in table] == [True] * 18  # the robot's maps, in leg/joint order
    assert [row[:2] for row in table] == [(0x40 if k < 9 else 0x41, k % 9) for k in range(18)]
    assert sonar_pins == ((6, 7), (8, 9), (10, 11), (12, 13), (14, 15))


# What a board file's checks need: the checks' helpers, the command limits (the "follow"
# setting), the sensor contract (the sonars' names) and the helpers the loop takes the checked
# files through (hexapod.wiring, with hexapod.servo's ServoMap). Never the walker and what it stands on.
BOARD_IMPORTS = {"hexapod", "hexapod.board", "hexapod.check", "hexapod.limits", "hexapod.sensors"}
BOARD_IMPORTS |= {"hexapod.wiring", "hexapod.servo"}
IMPORTS = """
import sys
before = set(sys.modules)
from hexapod import board
board.load("pico")
print(sorted(m for m in sys.modules if m not in before and m.startswith("hexapod")))
"""


def test_board_validation_imports_nothing_above_the_data_it_checks(mp):
    import subprocess
    import sys

    from hexapod_host import mpvm

    env = dict(__import__("os").environ, PYTHONPATH=mpvm.search_path())
    cpython = subprocess.run([sys.executable, "-c", IMPORTS], capture_output=True, text=True, env=env, check=True)
    for out in (cpython.stdout, mp.run(IMPORTS)):
        loaded = set(__import__("ast").literal_eval(out.strip().splitlines()[-1]))
        assert loaded == BOARD_IMPORTS, loaded


# The Feather RP2040's silkscreen names as RP2040 GPIOs (Adafruit's pinout of the board).
FEATHER_GPIO = {"SDA": 2, "SCL": 3, "D4": 6, "D5": 7, "D6": 8, "D9": 9, "D10": 10, "D11": 11, "D12": 12, "D13": 13}
FEATHER_GPIO.update(A0=26, A1=27, A2=28, A3=29)


def test_the_two_feather_files_wire_the_same_pins():
    # A maker who moves a Feather from CircuitPython to MicroPython keeps every wire where it is.
    import boards.feather_rp2040 as cp
    import boards.feather_rp2040_micropython as mp

    assert mp.BOARD["i2c"] == dict(cp.BOARD["i2c"], id=1, sda=FEATHER_GPIO["SDA"], scl=FEATHER_GPIO["SCL"])
    assert mp.BOARD["sonars"] == tuple((n, FEATHER_GPIO[t], FEATHER_GPIO[e]) for n, t, e in cp.BOARD["sonars"])
    own = ("name", "runtime", "arch", "i2c", "sonars", "battery")  # battery: None, or absent on CircuitPython's
    assert {k: v for k, v in mp.BOARD.items() if k not in own} == {k: v for k, v in cp.BOARD.items() if k not in own}
    assert mp.BOARD["battery"] is cp.BOARD.get("battery") is None
