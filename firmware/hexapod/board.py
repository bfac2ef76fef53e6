"""Board files: load one from boards/ and check it whole before any pin or bus is touched.

Pure: no hardware imports. A board file is plain data, a dict named BOARD (see boards/pico.py):
what belongs to the board, its runtime, the code emitter of its .mpy files (arch), the I2C bus,
the PCA9685 chips, which chip channel drives which servo, the sonars' pins. What belongs to the
robot (each servo's calibration, where each sonar sits) is in robots/<robot>_cal.py
(hexapod.robotcal). Any mistake raises one ValueError that names the board, where in the
file, what is wrong and what is allowed; nothing else ever escapes from validate(). Units as
everywhere: pulses in us, rates in Hz.
"""

from micropython import const

from hexapod.check import Check, is_identifier
from hexapod.limits import check_request
from hexapod.sensors import SENSOR_NAMES
from hexapod.wiring import JOINTS, LEGS, battery_args, servo_table, sonar_pins  # noqa: F401 (this module's names too)

RUNTIMES = ("micropython", "circuitpython")
# mpy-cross -march names in the order of MicroPython's .mpy header (arch number = index + 1).
ARCHES = ("x86", "x64", "armv6", "armv6m", "armv7m", "armv7em", "armv7emsp", "armv7emdp", "xtensa", "xtensawin")
ARCHES += ("rv32imc",)
# The private tables below are const(): folded into the code, no name kept on the board (each
# module-level name is a qstr, which stays in the heap after hexapod.release forgets this module).

_TOP = const(("name", "runtime", "arch", "i2c", "pca9685", "channels", "sonars"))
_OPTIONAL = const(("notes", "follow", "watchdog_ms", "on_exit", "walk_timeout_ms", "boot", "battery"))
ON_EXIT = ("relax", "hold")  # what leaving the loop (Ctrl-C) does to the servos
# What power-up does: stay relaxed (no pulse until `stand`), or stand, and only with a valid
# calibration file (runner.power_up).
BOOT = ("relaxed", "stand")
# The battery monitor (hexapod.battery): the ADC pin and the divider's ratio; the cell count
# and the per-cell thresholds default to a 2S LiPo's (hexapod.battery says where they come from).
_BATTERY = const(("pin", "divider_permille"))
_BATTERY_OPTIONAL = const(("cells", "cell_warn_mv", "cell_cutoff_mv", "cell_resume_mv"))
_FOLLOW = const(("side", "setpoint"))
_FOLLOW_OPTIONAL = const(("speed", "form"))
_I2C = const(("id", "sda", "scl", "freq"))
_PCA = const(("pwm_hz", "chips"))
_CHIP = const(("address", "osc_hz"))
_ALLCALL = const(0x70)  # a PCA9685 answers there by default (MODE1.ALLCALL): no chip may use it


class _Check(Check):
    """A board file's checks: its name in every message, and pins."""

    def __init__(self, board):
        name = "?"
        if isinstance(board, dict) and is_identifier(board.get("name")):
            name = board["name"]
        Check.__init__(self, "board", name)

    def pin(self, where, v, runtime):
        if v is None:
            self.fail(where, "no pin given")
        if isinstance(v, str) and is_identifier(v):
            return v
        if runtime == "micropython" and isinstance(v, int) and not isinstance(v, bool) and 0 <= v <= 63:
            return v
        if runtime == "circuitpython":
            self.fail(where, "%r, allowed a `board` pin name such as 'D5'" % (v,))
        self.fail(where, "%r, allowed a GPIO number 0..63 or a pin name" % (v,))


def validate(board):
    """Check a BOARD dict; return it unchanged, or raise ValueError naming the first mistake."""
    ck = _Check(board)
    if isinstance(board, dict):
        # Keys of the board files before the robot's data moved out (docs/wiring.md says how to move
        # them), written out here: a module-level name would stay in the board's heap (a qstr).
        for key, why in (
            (
                "servos",
                'moved: the channel map stays here as "channels"; the calibration moved to robots/<robot>_cal.py',
            ),
            ("sensors", 'moved: "sonars": (name, trigger, echo) stay here; the mounts moved to robots/<robot>_cal.py'),
        ):
            if key in board:
                ck.fail(key, why + " (docs/wiring.md)")
    ck.dict_of("board", board, _TOP, _OPTIONAL)
    name = board["name"]
    if not is_identifier(name):
        ck.fail("name", "%r, allowed a non-empty identifier" % (name,))
    runtime = board["runtime"]
    if runtime not in RUNTIMES:
        ck.fail("runtime", "%r, allowed %s" % (runtime, " or ".join(RUNTIMES)))
    arch = board["arch"]
    if runtime == "circuitpython" and arch is not None:
        ck.fail("arch", "%r, allowed None: CircuitPython boards get .py sources, no mpy-cross" % (arch,))
    if runtime == "micropython" and arch not in ARCHES:
        ck.fail("arch", "%r, allowed an mpy-cross -march name: %s" % (arch, ", ".join(ARCHES)))
    pins = {}

    def claim(where, pin):
        if pin in pins:
            ck.fail(where, "pin %r is already used as %s" % (pin, pins[pin]))
        pins[pin] = where

    i2c = ck.dict_of("i2c", board["i2c"], _I2C)
    if runtime == "micropython" or i2c["id"] is not None:
        ck.int_in("i2c.id", i2c["id"], 0, 9)
    claim("i2c.sda", ck.pin("i2c.sda", i2c["sda"], runtime))
    claim("i2c.scl", ck.pin("i2c.scl", i2c["scl"], runtime))
    ck.int_in("i2c.freq", i2c["freq"], 10000, 1000000, " Hz")

    pca = ck.dict_of("pca9685", board["pca9685"], _PCA)
    ck.int_in("pca9685.pwm_hz", pca["pwm_hz"], 40, 333, " Hz (servo frame rates)")
    chips = ck.seq("pca9685.chips", pca["chips"], -1, "of chip dicts")
    if not chips:
        ck.fail("pca9685.chips", "no chip given")
    addresses = []
    for i in range(len(chips)):
        where = "pca9685.chips[%d]" % i
        chip = ck.dict_of(where, chips[i], _CHIP)
        a = ck.int_in(where + ".address", chip["address"], 0x40, 0x7F, " (PCA9685 addresses 0x40..0x7f)")
        if a == _ALLCALL:
            ck.fail(where + ".address", "0x70 is the PCA9685 all-call address; every chip answers it")
        if a in addresses:
            ck.fail(where + ".address", "0x%02x is listed twice" % a)
        addresses.append(a)
        ck.int_in(where + ".osc_hz", chip["osc_hz"], 22500000, 27500000, " Hz (25 MHz +-10 %)")

    _servos(ck, board["channels"], addresses)
    sonars = ck.named("sonars", board["sonars"], 3, "(name, trigger, echo)", SENSOR_NAMES, "sonar")
    for name in SENSOR_NAMES:
        where = "sonar %s trigger" % name
        claim(where, ck.pin(where, sonars[name][1], runtime))
        where = "sonar %s echo" % name
        claim(where, ck.pin(where, sonars[name][2], runtime))
    _follow(ck, board)
    _console(ck, board)
    _battery(ck, board, runtime, claim)
    return board


def _battery(ck, board, runtime, claim):
    """The optional battery monitor: None (no monitor), or {"pin", "divider_permille"[, "cells",
    "cell_warn_mv", "cell_cutoff_mv", "cell_resume_mv"]}; MicroPython boards only (main.py reads
    machine.ADC; code.py has no ADC driver yet)."""
    setting = board.get("battery")
    if setting is None:
        return
    ck.dict_of("battery", setting, _BATTERY, _BATTERY_OPTIONAL)
    if runtime != "micropython":
        ck.fail("battery", "a battery monitor runs on MicroPython boards only (code.py has no ADC driver); remove it")
    claim("battery.pin", ck.pin("battery.pin", setting["pin"], runtime))
    from hexapod import battery

    try:
        battery.check(*battery_args(setting))
    except ValueError as e:
        key, _, msg = str(e).partition(": ")
        ck.fail("battery." + key, msg)


def _console(ck, board):
    """The console's settings (docs/console.md): watchdog_ms None or 4000..8000 (machine.WDT fed
    every frame; the rp2 allows at most 8388 ms; a gait, pose or height change runs the servo
    guard, 1.5-1.8 s without a frame on an emulated Pico, so less would reset the board),
    on_exit "relax"/"hold", boot "relaxed"/"stand" (runner.power_up), walk_timeout_ms 200..10000
    (a console walk's life without renewal)."""
    if board.get("watchdog_ms") is not None:
        ck.int_in("watchdog_ms", board["watchdog_ms"], 4000, 8000, " ms (or None: no watchdog)")
    if board.get("on_exit", "relax") not in ON_EXIT:
        ck.fail("on_exit", "%r, allowed %s" % (board["on_exit"], " or ".join(repr(x) for x in ON_EXIT)))
    if board.get("boot", "relaxed") not in BOOT:
        ck.fail("boot", "%r, allowed %s" % (board["boot"], " or ".join(repr(x) for x in BOOT)))
    if board.get("walk_timeout_ms") is not None:
        ck.int_in("walk_timeout_ms", board["walk_timeout_ms"], 200, 10000, " ms")


def _follow(ck, board):
    """The optional start-up wall following: None, or {"side", "setpoint"[, "speed", "form"]}
    (hexapod.limits.check_request's units)."""
    setting = board.get("follow")
    if setting is None:
        return
    ck.dict_of("follow", setting, _FOLLOW, _FOLLOW_OPTIONAL)
    try:
        check_request(setting["side"], setting["setpoint"], setting.get("speed"), setting.get("form", "crab"))
    except ValueError as e:
        ck.fail("follow", str(e))


def _servos(ck, channels, addresses):
    """Six legs of three (address, channel): coxa, femur, tibia; each output drives one servo."""
    used = {}
    ck.seq("channels", channels, LEGS, "(one per leg: ((address, channel) of its coxa, femur, tibia))")
    for leg in range(LEGS):
        ck.seq("channels[%d]" % leg, channels[leg], 3, "((address, channel) of its coxa, femur, tibia)")
        for j in range(3):
            who = "leg %d %s" % (leg + 1, JOINTS[j])
            where = "channels[%d][%d] (%s)" % (leg, j, who)
            pair = ck.seq(where, channels[leg][j], 2, "(address, channel)")
            a = pair[0]
            if not isinstance(a, int) or isinstance(a, bool) or a not in addresses:
                ck.fail(
                    where + " address",
                    "%r is not one of the chips (%s)" % (a, ", ".join("0x%02x" % x for x in addresses)),
                )
            ch = ck.int_in(where + " channel", pair[1], 0, 15)
            key = a * 16 + ch
            if key in used:
                ck.fail(where, "chip 0x%02x channel %d already drives %s" % (a, ch, used[key]))
            used[key] = who


def load(name):
    """Import boards/<name>.py and return its validated BOARD."""
    if not is_identifier(name):
        raise ValueError("board name %r: allowed a file name in boards/ without .py" % (name,))
    try:
        module = __import__("boards." + name, None, None, ("BOARD",))
    except ImportError:
        raise ValueError("board %r: no boards/%s.py" % (name, name)) from None
    board = getattr(module, "BOARD", None)
    if board is None:
        raise ValueError("board %r: boards/%s.py defines no BOARD" % (name, name))
    return validate(board)
