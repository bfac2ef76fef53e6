"""Board entry point on CircuitPython (it runs code.py): the CircuitPython twin of main.py.

Loads the board file and the robot's files named below (robots/ROBOT.py and
robots/ROBOT_cal.py, as main.py), builds the loop (runner.Runner) on
busio.I2C, the PCA9685 bank (drivers.cp_pca9685) and five non-blocking HC-SR04 rangers
(drivers.cp_hcsr04_pulsein), stands the robot up and runs 50 Hz frames for ever, printing a
status line every 5 s; with a "follow" setting in the board file it follows that wall once
standing (hexapod.follow). Edit BOARD and ROBOT to match yours (files in boards/ and robots/).
Needs adafruit_pca9685, adafruit_bus_device and adafruit_register in lib/ (docs/wiring.md).
"""

# isort: off
import gc
import sys

BOARD = "feather_rp2040"
ROBOT = "default"
STATUS_FRAMES = 250  # 5 s of 20 ms frames
SONAR_SAMPLES = (3, 1, 1, 1, 1)  # pings per median, hexapod.sensors order (see main.py)


def board_pin(board, name, where):
    """The `board` module's pin called name; ValueError naming the board file and place if absent."""
    import board as pins

    pin = getattr(pins, name, None)
    if pin is None:
        raise ValueError(
            "board %r: %s: pin %r is not in this CircuitPython board's `board` module (board_id %r)"
            % (board["name"], where, name, getattr(pins, "board_id", "?"))
        )
    return pin


def settings(board_name=BOARD, robot_name=ROBOT):
    """What the loop needs from the board file and the robot's files, checked: (board dict, robot
    geometry, servo table rows, sonar mounts, sonar pin names, the `board` module's sonar pins,
    SCL, SDA). ValueError naming the file, value and what is allowed."""
    from hexapod import board as boards  # boot only: released once read (hexapod.release)
    from hexapod import geometry, robotcal, sensors

    board = boards.load(board_name)
    if board["runtime"] != "circuitpython":
        raise ValueError(
            "board %r: runtime %r: code.py runs CircuitPython boards (e.g. feather_rp2040); use main.py on MicroPython"
            % (board_name, board["runtime"])
        )
    if not isinstance(robot_name, str) or not robot_name:
        raise ValueError("robot name %r: allowed a file name in robots/ without .py" % (robot_name,))
    try:
        robot_module = __import__("robots." + robot_name, None, None, ("NAME",))
    except ImportError:
        raise ValueError("robot %r: no robots/%s.py" % (robot_name, robot_name)) from None
    robot = geometry.load(robot_module)
    cal = robotcal.load(robot_name, robot.limits)
    bus = board["i2c"]
    scl = board_pin(board, bus["scl"], "i2c scl")
    sda = board_pin(board, bus["sda"], "i2c sda")
    sonar_pins = []
    pairs = boards.sonar_pins(board)
    for k in range(len(pairs)):  # every pin looked up before any is claimed
        trigger, echo = pairs[k]
        where = sensors.SENSOR_NAMES[k] + " sensor"
        sonar_pins.append((board_pin(board, trigger, where + " trigger"), board_pin(board, echo, where + " echo")))
    table = boards.servo_table(board, robotcal.servo_maps(cal))
    return board, robot, table, robotcal.sensor_mounts(cal), pairs, sonar_pins, scl, sda


def _release(robot_name):
    """The boot-only modules (the board and robot files and their checks) out of the heap."""
    from hexapod import BOOT_ONLY, release

    release(*BOOT_ONLY, "robots." + robot_name, "robots.%s_cal" % robot_name)


# Import order matters where the board compiles .py at import (CircuitPython cannot load
# MicroPython's .mpy): compiling a module needs several times its source in free heap, every module
# loaded before it leaves less, and the compiles' garbage left between the modules that stay cuts
# the heap into holes. A module's compile ends before its own imports run, so importing a module
# first compiles it on the emptiest heap and the modules it imports after it. On a board: the wall
# follower (hexapod.follow, 25 KB of source: compiled last, under everything else, it was what
# bound) and with it the core (hexapod.tick, which compiles walk); then console, whose reporting
# and setting commands (consoleparts.more, .setting) are compiled per command; then the biggest
# driver, drivers.pca9685; then the board and robot files, read and let go at once (their checks
# are not alive while the loop is built), then runner; a collection after each (docs/flashing.md:
# 4-6 KB less free heap needed at boot than pca9685, tick, the files, console, runner, 2026-11-28).
# A board file refused stops code.py here, with the message build() gave before. And from the first
# import until the loop runs (main(): build() and the power-up too), a collection each
# BOOT_GC_BYTES allocated (gc.threshold): the collector otherwise waits for the heap to fill, by
# when the compiles' and build()'s garbage lies between everything that stays, and the loop starts
# on a heap of small holes (56 KB free, the largest hole 2 KB, in the VM). `hexapod bench feather`
# (docs/flashing.md) has the figures.
BOOT_GC_BYTES = 4096
_boot_threshold = None  # gc.threshold() as the board had it, put back when the loop starts
_settings = None  # settings(BOARD, ROBOT), read at import on a board; build() takes it once
_on_board = False  # the board's own boot (not the host's tests): main() lets the builders go (_let_go_builders)
if sys.implementation.name != "cpython":  # CPython: the tests install fake modules first (and pdb imports a `code`)
    _on_board = True
    if hasattr(gc, "threshold"):
        _boot_threshold = gc.threshold()
        gc.threshold(BOOT_GC_BYTES)
    import hexapod.follow  # noqa: F401  (and the core: hexapod.tick, hexapod.walk, ...)

    gc.collect()
    import console  # noqa: F401

    gc.collect()
    from drivers import pca9685  # noqa: F401

    gc.collect()
    _settings = settings()
    _release(ROBOT)
    gc.collect()
    import runner  # noqa: F401

    gc.collect()

import console  # noqa: E402

if sys.implementation.name != "cpython":
    # The calibration file's commands: compiled here, where the next compile would find a fuller
    # heap, kept for the first jog session and let go once the robot walks (cal_until_walk: the
    # loop's commands then have its 8 KB); MicroPython loads their .mpy per command instead. The jog
    # and calibration commands (consoleparts.jog, .joint, .caledit, .calset: small compiles, on a
    # collected heap) at the session's first command of theirs: all five here took 3 KB more of the
    # Feather's heap (bench feather, 2026-11-28).
    import consolecal  # noqa: F401

    del consolecal  # sys.modules holds it: the console lets it go (hexapod.release)
    console.Console.cal_until_walk = True
    # consoleparts.more and selftest compiled per command on a collected heap, the former let go after
    # each (console.Console.compiles).
    console.Console.compiles = True
    gc.collect()
    from drivers import cp_clock, cp_hcsr04_pulsein, cp_pca9685  # noqa: F401
from runner import FRAME_MS, Runner  # noqa: E402
from hexapod import sensors  # noqa: E402

# isort: on


def build(board_name=BOARD, robot_name=ROBOT, clock=None, max_range=10000, samples=SONAR_SAMPLES):
    """The Runner for a CircuitPython board and robot file (max_range: 0.1 mm; samples: pings per
    median, hexapod.sensors order); clock: cp_clock.Clock."""
    global _settings
    if _settings is not None and (board_name, robot_name) == (BOARD, ROBOT):
        board, robot, table, mounts, pairs, sonar_pins, scl, sda = _settings
        _settings = None  # the Runner holds what it keeps: the rest is the loop's heap
    else:
        board, robot, table, mounts, pairs, sonar_pins, scl, sda = settings(board_name, robot_name)
    import busio

    from drivers import cp_clock, cp_hcsr04_pulsein, cp_pca9685, ranger  # loaded at the top on a board

    if clock is None:
        clock = cp_clock.Clock()
    rangers = []
    try:  # sonars first: a refused setting (max_range) leaves no pin claimed and the bus untouched
        for k in range(len(sonar_pins)):
            trigger, echo = sonar_pins[k]
            rangers.append(cp_hcsr04_pulsein.HCSR04(trigger, echo, clock, max_range=max_range, samples=samples[k]))
    except ValueError:
        for s in rangers:
            s.deinit()
        raise
    i2c = busio.I2C(scl, sda, frequency=board["i2c"]["freq"])
    bank = cp_pca9685.servo_bank(i2c, board["pca9685"], table)
    sonars = sensors.Sonars(ranger.RoundRobin(rangers, tick_ms=FRAME_MS), len(rangers))
    r = Runner(robot, [row[2] for row in table], bank, sonars, clock, mounts)
    r.board = board
    r.sonar_pins = pairs
    return r


def main(frames=-1, clock=None, board_name=BOARD, robot_name=ROBOT, reader=None, boot=None, calibrated=None):
    """Build, power up (runner.power_up: relaxed, or with the board file's "boot": "stand" and a
    valid calibration file stand up, then follow the board's "follow" wall, if set), run frames
    (for ever when -1) with a status line every 5 s; returns the Runner. boot ("relaxed",
    "stand") overrides the board file's; calibrated (True/False) says whether the servos are
    calibrated where no calibration file is read (host runs; None: the file, loaded by the
    console). With a console reader (the
    board entry: SerialReader) the console and the calibration file take over from
    the status line (docs/console.md); Ctrl-C relaxes the servos (or holds, on_exit)."""
    global runner
    r = runner = build(board_name, robot_name, clock)
    _release(robot_name)  # when build read them: their heap back to the loop
    if _on_board:
        _let_go_builders(False)
    r.bring_up(reader, boot, calibrated)
    if _on_board:
        _let_go_builders(True)
    if reader is not None and r.board.get("watchdog_ms"):
        from microcontroller import watchdog
        from watchdog import WatchDogMode

        watchdog.timeout = r.board["watchdog_ms"] / 1000  # the one float: CircuitPython wants seconds
        watchdog.mode = WatchDogMode.RESET
        r.watchdog = watchdog
    if _boot_threshold is not None:  # the boot's collections end where the loop's frames begin
        gc.threshold(_boot_threshold)
    r.serve(frames, 0 if reader is not None else STATUS_FRAMES)
    return r


def _let_go_builders(up):
    """The code that only builds the loop and powers it up, out of the heap once it ran (the board's
    boot, main()). up False, after build(): the constructors of the objects built once, the sonar
    slot planner, the servo bank's builders, the robot geometry's loaders and code.py's own
    settings() and build(); up True, after the power-up: the console's and runner's start-up
    (console.start gets the room of the first). On CircuitPython each was compiled at import and
    its bytecode would stay with its class or module for the whole run: about 9.5 KB of the
    running heap in the VM (bench.feather, 2026-11-28), the room a command's compile needs
    (docs/flashing.md). A class's __init__ becomes
    None (a later construction fails: none is made after boot; Ctrl-D reloads everything), a
    module function is deleted. A new constructor run after boot must not be listed here."""
    import runner as loop  # `runner` here is main()'s Runner

    if up:
        import calstore

        built_once = (console.Console, calstore.Store, SerialReader)
        loop.Runner.bring_up = loop.Runner.power_up = loop.Runner.follow_when_standing = None
        gone = ((console, ("start", "PollReader")),)
        names = ("_let_go_builders",)
    else:
        from drivers import cp_clock, cp_hcsr04_pulsein, cp_pca9685, pca9685, ranger
        from hexapod import faultlog, gait, geometry, leg, posture, tick, walk

        built_once = (tick.Robot, tick._Feet, walk.Walker, gait.GaitClock, posture.Posture, faultlog.FaultLog)
        built_once += (pca9685.PCA9685, pca9685.ServoBank, cp_pca9685.PCA9685, cp_hcsr04_pulsein.HCSR04)
        built_once += (ranger.MedianRanger, ranger.RoundRobin, sensors.Sonars, cp_clock.Clock, loop.Runner)
        built_once += (geometry.Geometry, leg.Leg)
        gone = ((pca9685, ("servo_bank",)), (cp_pca9685, ("servo_bank",)), (ranger, ("plan", "_place")))
        gone += ((geometry, ("leg_from", "load", "from_data")),)
        names = ("settings", "build", "board_pin", "_release")
    for cls in built_once:
        cls.__init__ = None  # assigned, not deleted: a deleted class attribute's slot kept the function
    for module, attrs in gone:
        for name in attrs:
            delattr(module, name)
    here = globals()
    for name in names:
        del here[name]
    gc.collect()


class SerialReader:
    """The console's reader on CircuitPython (here, not in console.py: a Pico's heap keeps no
    CircuitPython code): supervisor.runtime.serial_bytes_available, then sys.stdin.read(1)."""

    def __init__(self):
        import sys

        import supervisor

        self._rt = supervisor.runtime
        self._in = sys.stdin

    def read_byte(self):
        if not self._rt.serial_bytes_available:
            return -1
        c = self._in.read(1)
        if not c:
            return -1
        n = ord(c)
        return n if n < 256 else 255  # a multi-byte character is not text the console takes


runner = None  # the Runner main() built: the REPL's handle after Ctrl-C

if __name__ == "__main__":
    main(reader=SerialReader())
