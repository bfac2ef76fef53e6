"""Board files: load one from boards/ and check it whole before any pin or bus is touched.

Pure: no hardware imports. A board file is plain data, a dict named BOARD (see boards/pico.py).
Any mistake raises one ValueError that names the board, where in the file, what is wrong and
what is allowed; nothing else ever escapes from validate(). Units as everywhere: lengths in
0.1 mm, headings in centidegrees (counter-clockwise from forward), pulses in us, rates in Hz.
"""

from hexapod.servo import ServoMap

JOINTS = ("coxa", "femur", "tibia")
SENSORS = ("front", "left_front", "left_rear", "right_front", "right_rear")  # drivers.hcsr04 order
RUNTIMES = ("micropython", "circuitpython")
LEGS = 6

_TOP = ("name", "runtime", "i2c", "pca9685", "servos", "sensors")
_OPTIONAL = ("notes", "follow", "watchdog_ms", "on_exit", "walk_timeout_ms", "boot", "battery")
ON_EXIT = ("relax", "hold")  # what leaving the loop (Ctrl-C) does to the servos
# What power-up does: stay relaxed (no pulse until `stand`), or stand, and only with a valid
# calibration file (runner.power_up).
BOOT = ("relaxed", "stand")
# The battery monitor (hexapod.battery): the ADC pin and the divider's ratio; the cell count
# and the per-cell thresholds default to a 2S LiPo's (hexapod.battery says where they come from).
_BATTERY = ("pin", "divider_permille")
_BATTERY_OPTIONAL = ("cells", "cell_warn_mv", "cell_cutoff_mv", "cell_resume_mv")
_FOLLOW = ("side", "setpoint")
_FOLLOW_OPTIONAL = ("speed", "form")
_I2C = ("id", "sda", "scl", "freq")
_PCA = ("pwm_hz", "chips")
_CHIP = ("address", "osc_hz")
_SERVO = "(leg, joint, address, channel, centre_us, direction, min_us, max_us)"
_SENSOR = "(name, trigger, echo, x, y, heading)"
_ALLCALL = 0x70  # a PCA9685 answers there by default (MODE1.ALLCALL): no chip may use it


class _Check:
    """Carries the board's name into every message."""

    def __init__(self, board):
        self.name = "?"
        if isinstance(board, dict) and isinstance(board.get("name"), str) and board["name"]:
            self.name = board["name"]

    def fail(self, where, msg):
        raise ValueError("board %r: %s: %s" % (self.name, where, msg))

    def dict_of(self, where, v, required, optional=()):
        if not isinstance(v, dict):
            self.fail(where, "expected a dict, got %s" % (type(v).__name__,))
        for k in v:
            if k not in required and k not in optional:
                self.fail(where, "unknown key %r (allowed: %s)" % (k, ", ".join(required + optional)))
        for k in required:
            if k not in v:
                self.fail(where, "missing key %r" % (k,))
        return v

    def seq(self, where, v, length=-1, shape=""):
        if not isinstance(v, (tuple, list)):
            self.fail(where, "expected a tuple %s, got %s" % (shape, type(v).__name__))
        if length >= 0 and len(v) != length:
            self.fail(where, "expected %d items %s, got %d" % (length, shape, len(v)))
        return v

    def int_in(self, where, v, lo, hi, unit=""):
        if not isinstance(v, int) or isinstance(v, bool) or v < lo or v > hi:
            self.fail(where, "%r, allowed %d..%d%s" % (v, lo, hi, unit))
        return v

    def pin(self, where, v, runtime):
        if v is None:
            self.fail(where, "no pin given")
        if isinstance(v, str) and v and _is_identifier(v):
            return v
        if runtime == "micropython" and isinstance(v, int) and not isinstance(v, bool) and 0 <= v <= 63:
            return v
        if runtime == "circuitpython":
            self.fail(where, "%r, allowed a `board` pin name such as 'D5'" % (v,))
        self.fail(where, "%r, allowed a GPIO number 0..63 or a pin name" % (v,))


def _is_identifier(s):
    for i in range(len(s)):
        c = s[i]
        if not (c == "_" or "a" <= c <= "z" or "A" <= c <= "Z" or (i and "0" <= c <= "9")):
            return False
    return True


def validate(board):
    """Check a BOARD dict; return it unchanged, or raise ValueError naming the first mistake."""
    ck = _Check(board)
    ck.dict_of("board", board, _TOP, _OPTIONAL)
    name = board["name"]
    if not isinstance(name, str) or not name or not _is_identifier(name):
        ck.fail("name", "%r, allowed a non-empty identifier" % (name,))
    runtime = board["runtime"]
    if runtime not in RUNTIMES:
        ck.fail("runtime", "%r, allowed %s" % (runtime, " or ".join(RUNTIMES)))
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

    _servos(ck, ck.seq("servos", board["servos"], -1, "of servo tuples"), addresses)
    _sensors(ck, ck.seq("sensors", board["sensors"], -1, "of sensor tuples"), runtime, claim)
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


def battery_args(setting):
    """A board file's "battery" dict -> hexapod.battery.Monitor's arguments, defaults filled in:
    (cells, divider_permille, cell_warn_mv, cell_cutoff_mv, cell_resume_mv)."""
    from hexapod import battery

    return (
        setting.get("cells", battery.CELLS),
        setting["divider_permille"],
        setting.get("cell_warn_mv", battery.CELL_WARN_MV),
        setting.get("cell_cutoff_mv", battery.CELL_CUTOFF_MV),
        setting.get("cell_resume_mv", battery.CELL_RESUME_MV),
    )


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
    """Sensor mounts the wall follower can use, and the optional start-up wall following: None,
    or {"side", "setpoint"[, "speed", "form"]} (hexapod.follow's units)."""
    from hexapod import follow

    try:
        follow.check_mounts(sensor_mounts(board))
    except ValueError as e:
        ck.fail("sensors", str(e))
    setting = board.get("follow")
    if setting is None:
        return
    ck.dict_of("follow", setting, _FOLLOW, _FOLLOW_OPTIONAL)
    try:
        follow.check_request(setting["side"], setting["setpoint"], setting.get("speed"), setting.get("form", "yaw"))
    except ValueError as e:
        ck.fail("follow", str(e))


def _servos(ck, servos, addresses):
    seen = {}
    channels = {}
    for i in range(len(servos)):
        where = "servos[%d]" % i
        s = ck.seq(where, servos[i], 8, _SERVO)
        leg = ck.int_in(where + " leg", s[0], 1, LEGS)
        if s[1] not in JOINTS:
            ck.fail(where + " joint", "%r, allowed %s" % (s[1], ", ".join(JOINTS)))
        who = "leg %d %s" % (leg, s[1])
        where = "%s (%s)" % (where, who)
        if who in seen:
            ck.fail(where, "listed twice (first at servos[%d])" % seen[who])
        seen[who] = i
        a = s[2]
        if not isinstance(a, int) or isinstance(a, bool) or a not in addresses:
            ck.fail(
                where + " address", "%r is not one of the chips (%s)" % (a, ", ".join("0x%02x" % x for x in addresses))
            )
        ch = ck.int_in(where + " channel", s[3], 0, 15)
        key = a * 16 + ch
        if key in channels:
            ck.fail(where, "chip 0x%02x channel %d already drives %s" % (a, ch, channels[key]))
        channels[key] = who
        for k, field in ((4, "centre_us"), (5, "direction"), (6, "min_us"), (7, "max_us")):
            v = s[k]
            if not isinstance(v, int) or isinstance(v, bool):
                ck.fail(where + " " + field, "%r, allowed an integer" % (v,))
        try:
            ServoMap(centre_us=s[4], direction=s[5], min_us=s[6], max_us=s[7])
        except ValueError as e:
            ck.fail(where, str(e))
    for leg in range(1, LEGS + 1):
        for joint in JOINTS:
            if "leg %d %s" % (leg, joint) not in seen:
                ck.fail("servos", "missing servo leg %d %s" % (leg, joint))


def _sensors(ck, sensors, runtime, claim):
    seen = []
    for i in range(len(sensors)):
        where = "sensors[%d]" % i
        s = ck.seq(where, sensors[i], 6, _SENSOR)
        if s[0] not in SENSORS:
            ck.fail(where + " name", "%r, allowed %s" % (s[0], ", ".join(SENSORS)))
        where = "sensor %s" % s[0]
        if s[0] in seen:
            ck.fail(where, "listed twice")
        seen.append(s[0])
        claim(where + " trigger", ck.pin(where + " trigger", s[1], runtime))
        claim(where + " echo", ck.pin(where + " echo", s[2], runtime))
        ck.int_in(where + " x", s[3], -10000, 10000, " (0.1 mm)")
        ck.int_in(where + " y", s[4], -10000, 10000, " (0.1 mm)")
        ck.int_in(where + " heading", s[5], -18000, 18000, " (0.01 deg)")
    for name in SENSORS:
        if name not in seen:
            ck.fail("sensors", "missing sensor %s" % name)


def load(name):
    """Import boards/<name>.py and return its validated BOARD."""
    if not isinstance(name, str) or not name or not _is_identifier(name):
        raise ValueError("board name %r: allowed a file name in boards/ without .py" % (name,))
    try:
        module = __import__("boards." + name, None, None, ("BOARD",))
    except ImportError:
        raise ValueError("board %r: no boards/%s.py" % (name, name)) from None
    board = getattr(module, "BOARD", None)
    if board is None:
        raise ValueError("board %r: boards/%s.py defines no BOARD" % (name, name))
    return validate(board)


def servo_table(board):
    """18 (address, channel, ServoMap) in leg/joint order: index (leg - 1) * 3 + joint."""
    table = [None] * (LEGS * 3)
    for s in board["servos"]:
        table[(s[0] - 1) * 3 + JOINTS.index(s[1])] = (
            s[2],
            s[3],
            ServoMap(centre_us=s[4], direction=s[5], min_us=s[6], max_us=s[7]),
        )
    return tuple(table)


def sensor_mounts(board):
    """Five (x, y, heading) in drivers.hcsr04 order: 0.1 mm and cdeg, body frame."""
    by_name = {}
    for s in board["sensors"]:
        by_name[s[0]] = (s[3], s[4], s[5])
    return tuple(by_name[n] for n in SENSORS)


def sensor_pins(board):
    """Five (trigger, echo) pins in drivers.hcsr04 order: front, left_front, left_rear, ..."""
    by_name = {}
    for s in board["sensors"]:
        by_name[s[0]] = (s[1], s[2])
    return tuple(by_name[n] for n in SENSORS)
