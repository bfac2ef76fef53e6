"""hexapod.wiring.load against the board's checks (tests/test_wiring.py): what main.build makes of a
board file and the robot's two files, built checked and built unchecked from a marker that lists
them, as plain values to compare."""

from hexapod import board as boards
from hexapod import geometry, robotcal, wiring


def names(robot_name, board_name):
    return ("boards." + board_name, "robots." + robot_name, "robots.%s_cal" % robot_name)


def write_marker(marker, board_name, robot_name, changed=None, left_out=None):
    """marker listing the three modules' files as `hexapod flash` does; changed: a module name
    whose file's bytes are listed with one byte added (the file edited after the flash);
    left_out: a module name not listed (a .py uploaded beside the flashed .mpy)."""
    with open(marker, "w") as f:
        for name in names(robot_name, board_name):
            m = __import__(name, None, None, ("NAME",))
            with open(m.__file__, "rb") as g:
                data = g.read()
            if name == changed:
                data += b" "
            if name != left_out:
                f.write(wiring.line(m.__file__, data))


def plain(v):
    """v as nested lists of plain values: objects by their attributes (name order), arrays and
    tuples as lists, dicts as sorted (key, value) pairs; methods by name."""
    if v is None or isinstance(v, (bool, int, float, str)):
        return v
    if isinstance(v, dict):
        return sorted([k, plain(v[k])] for k in v)
    if isinstance(v, (tuple, list)) or type(v).__name__ == "array":
        return [plain(x) for x in v]
    if callable(v):
        return "callable"
    d = v.__dict__
    out = [type(v).__name__] + sorted([k, plain(d[k])] for k in d)
    if type(v).__name__ == "Leg":
        # Its solver's geometry only: slots 9-12 (G_EXCESS, G_T1..G_T3) are results the next
        # solve overwrites, left by the checks' reachability solves on the first leg.
        out = [item if item[0] != "_g" else ["_g", item[1][:9]] for item in out]
    return out


def summary(board, robot, cal):
    """Everything main.build takes from the three files, as plain values."""
    table = wiring.servo_table(board, wiring.servo_maps(cal))
    battery = board.get("battery")
    return [
        plain(board),
        plain(robot),
        plain(cal),
        plain(table),
        plain(wiring.sonar_pins(board)),
        plain(wiring.sensor_mounts(cal)),
        plain(wiring.battery_args(battery)) if battery is not None else None,
    ]


def both(marker, board_name, robot_name="default", battery=None):
    """[checked summary, unchecked summary or None] with marker listing the files unchanged;
    battery: a "battery" setting put in the board's BOARD meanwhile (no shipped board has one)."""
    write_marker(marker, board_name, robot_name)
    if battery is None:
        return _both(marker, board_name, robot_name)
    module = __import__("boards." + board_name, None, None, ("BOARD",))
    module.BOARD["battery"] = battery
    try:
        return _both(marker, board_name, robot_name)
    finally:
        module.BOARD["battery"] = None


def _both(marker, board_name, robot_name):
    board = boards.load(board_name)
    robot = geometry.load(__import__("robots." + robot_name, None, None, ("NAME",)))
    checked = summary(board, robot, robotcal.load(robot_name, robot.limits))
    files = wiring.load(board_name, robot_name, marker)
    if files is None:
        return [checked, None]
    board, module, cal = files
    return [checked, summary(board, geometry.load(module, False), cal)]


def trusted(marker, board_name, robot_name="default", changed=None, left_out=None, write=True):
    """Whether hexapod.wiring.load builds unchecked from marker (written unless write is False)."""
    if write:
        write_marker(marker, board_name, robot_name, changed, left_out)
    return wiring.load(board_name, robot_name, marker) is not None
