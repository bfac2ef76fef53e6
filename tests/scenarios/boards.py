"""Board files and hexapod.board's validation: copies of the shipped boards with one thing changed."""

from scenarios.refusal import message

import boards.esp32_devkit
import boards.feather_rp2040
import boards.feather_rp2040_micropython
import boards.pico
from hexapod import board as hb

GOOD = {
    "pico": boards.pico.BOARD,
    "esp32_devkit": boards.esp32_devkit.BOARD,
    "feather_rp2040": boards.feather_rp2040.BOARD,
    "feather_rp2040_micropython": boards.feather_rp2040_micropython.BOARD,
}
MAPS = ["map %d" % k for k in range(18)]  # stand-ins for the robot's 18 ServoMaps
DELETE = "<delete>"
APPEND = "<append>"


def thaw(o):
    """A deep copy with every tuple a list."""
    if isinstance(o, dict):
        return dict((k, thaw(v)) for k, v in o.items())
    if isinstance(o, (tuple, list)):
        return [thaw(v) for v in o]
    return o


def mutated(name, path, value):
    """A copy of the board with the item at path set to value (DELETE: removed; (APPEND, v): v appended)."""
    b = thaw(GOOD[name])
    if not path:
        return value
    o = b
    for k in path[:-1]:
        o = o[k]
    if value == DELETE:
        del o[path[-1]]
    elif isinstance(value, tuple) and value and value[0] == APPEND:
        o[path[-1]].append(value[1])
    else:
        o[path[-1]] = value
    return b


def check(b):
    """validate()'s message, or "accepted"."""
    return message(hb.validate, b)


def good_boards(names):
    """Per board (load() gives the file's dict, check of it, check of a thawed copy, servo table length),
    then the checks of four optional-key changes."""
    out = [
        (hb.load(n) is GOOD[n], check(GOOD[n]), check(thaw(GOOD[n])), len(hb.servo_table(GOOD[n], MAPS))) for n in names
    ]
    out.append(check(mutated("pico", ("notes",), "spare servo in the drawer")))
    out.append(check(mutated("pico", ("follow",), {"side": "left", "setpoint": 800})))
    out.append(check(mutated("esp32_devkit", ("follow",), {"side": "right", "setpoint": 1600, "form": "sweeps"})))
    out.append(check(mutated("feather_rp2040", ("follow",), DELETE)))
    return out


def checks(mutations):
    """check() of each (board, path, value) mutation."""
    return [check(mutated(n, p, v)) for n, p, v in mutations]


def channel_and_pin_moves(name):
    """(moves, moves refused as such): each servo onto every other servo's channel, each sonar pin
    onto every other pin of the board."""
    b = GOOD[name]
    out = []
    for i in range(18):
        for j in range(18):
            if i != j:
                m = mutated(name, ("channels", i // 3, i % 3), list(b["channels"][j // 3][j % 3]))
                out.append("already drives" in check(m))
    pins = [b["i2c"]["sda"], b["i2c"]["scl"]]
    for s in b["sonars"]:
        pins += [s[1], s[2]]
    for k in range(5):
        for col in (1, 2):
            for p in pins:
                if p != b["sonars"][k][col]:
                    out.append("is already used as" in check(mutated(name, ("sonars", k, col), p)))
    return (len(out), out.count(True))


def failing_validation():
    """(the refused copy unchanged, refused as a channel clash, the board file unchanged)."""
    b = mutated("pico", ("channels", 0, 1, 1), 0)
    before = repr(b)
    r = check(b)
    return (repr(b) == before, "already drives" in r, repr(GOOD["pico"]) == repr(boards.pico.BOARD))


def load_error(name):
    """load(name)'s message, or "accepted"."""
    return message(hb.load, name)


def pico_tables():
    """([(address, channel, whether the map is the robot's k-th)] of the servo table, sonar pins)."""
    b = GOOD["pico"]
    t = hb.servo_table(b, MAPS)
    return ([(a, c, m is MAPS[k]) for k, (a, c, m) in enumerate(t)], hb.sonar_pins(b))
