"""The body of main.py, the board entry point (MicroPython): with it, the only files that touch
real hardware. main.py keeps the names to edit (BOARD, ROBOT) and imports this, which `hexapod
flash` puts on the board compiled (.mpy): MicroPython compiles main.py from its source at every
boot (62 ms of the power-up on an emulated Pico before this split) and never loads a
main.mpy.

build() loads the board file and the robot's files (robots/ROBOT.py, its build, and
robots/ROBOT_cal.py, its servo calibration and sonar mounts) and makes the loop (runner.Runner)
on this machine's I2C and pins; run() stands the robot up and runs 50 Hz frames for ever,
printing a status line every 5 s; with a "follow" setting in the board file it follows that wall
once standing (hexapod.follow); with a "battery" setting it watches the pack on that ADC pin
(hexapod.battery). main.main does both.

main.py imports the robot file before this module, into a heap the loop's modules have not yet
cut up: imported after them it found no block big enough on an emulated Pico (MemoryError with
78 KB free, none over 5.9 KB, 2026-11-27). run() releases it once the robot is built.
"""

import time

from machine import I2C, Pin, time_pulse_us
from runner import FRAME_MS, Runner

from drivers import hcsr04, pca9685
from hexapod import BOOT_ONLY, geometry, release, sensors

STATUS_FRAMES = 250  # 5 s of 20 ms frames
# Pings per median, hexapod.sensors order: each sensor pings every 100 ms, so a median of n
# lags about (n - 1) * 50 ms. The wall follower steers on the side sonars: no median there
# (its PID takes each fresh reading once); the front one keeps 3 against a stray echo.
SONAR_SAMPLES = (3, 1, 1, 1, 1)


def build(board_name, robot_name, clock=time, max_range=10000, samples=SONAR_SAMPLES, bank=None):
    """The Runner for a board and robot on this machine's I2C and pins (max_range: 0.1 mm;
    samples: pings per median for each sonar, hexapod.sensors order; bank: where frames go,
    None for the board's PCA9685s on its I2C)."""
    from hexapod import wiring  # boot only: run() releases it (hexapod.BOOT_ONLY)

    files = wiring.load(board_name, robot_name)
    if files is None:  # not as flashed (or no marker): checked here
        # Collected first: the checks' modules did not load into the heap the imports left
        # (MemoryError for 1,280 B with 98 KB free on an emulated Pico, 2026-11-28); a rare path.
        import gc

        gc.collect()
        from hexapod import board as boards
        from hexapod import robotcal

        board = boards.load(board_name)
        robot = geometry.load(__import__("robots." + robot_name, None, None, ("NAME",)))
        cal = robotcal.load(robot_name, robot.limits)
    else:  # as flashed: checked on the host, built without the checks (hexapod.wiring)
        board, robot_module, cal = files
        robot = geometry.load(robot_module, False)
    table = wiring.servo_table(board, wiring.servo_maps(cal))
    if bank is None:
        bus = board["i2c"]
        i2c = I2C(bus["id"], scl=Pin(bus["scl"]), sda=Pin(bus["sda"]), freq=bus["freq"])
        bank = pca9685.servo_bank(i2c, board["pca9685"], table, sleep_us=clock.sleep_us)
    rangers = []
    pins = wiring.sonar_pins(board)
    for k in range(len(pins)):
        trigger, echo = pins[k]
        rangers.append(
            hcsr04.HCSR04(
                Pin(trigger, Pin.OUT),
                Pin(echo, Pin.IN),
                clock,
                time_pulse_us,
                max_range=max_range,
                samples=samples[k],
                irq=True,  # the echo timed by its pin's IRQ: nothing waits for it (drivers/hcsr04.py)
            )
        )
    monitor = adc = None
    if board.get("battery") is not None:  # the pack through its divider on an ADC pin (docs/wiring.md)
        from machine import ADC

        from hexapod import battery

        monitor = battery.Monitor(*wiring.battery_args(board["battery"]))
        adc = ADC(Pin(board["battery"]["pin"]))
    sonars = sensors.Sonars(hcsr04.RoundRobin(rangers, tick_ms=FRAME_MS), len(rangers))
    r = Runner(
        robot,
        [row[2] for row in table],
        bank,
        sonars,
        clock,
        wiring.sensor_mounts(cal),
        battery=monitor,
        adc=adc,
        keeper=fault_keeper(),
    )
    r.board = board
    r.sonar_pins = pins
    r.note_reset(watchdog_reset())
    return r


def fault_keeper():
    """Where this port keeps the fault log through a soft reset (drivers.faultkeep), or None."""
    import sys

    if sys.platform not in ("rp2", "esp32"):
        return None
    import machine

    from drivers import faultkeep

    return faultkeep.for_port(machine, sys.platform)


def watchdog_reset():
    """True when the port says the last reset was the watchdog's."""
    import machine

    cause = getattr(machine, "reset_cause", None)
    return cause is not None and cause() == getattr(machine, "WDT_RESET", -1)


def run(r, frames=-1, robot_name=None, reader=None, boot=None, calibrated=None):
    """Power up the built Runner r (runner.power_up: relaxed, or with the board file's "boot":
    "stand" and a valid calibration file stand up, then follow the board's "follow" wall, if
    set) and run frames (for ever when -1) with a status line every 5 s (main.main). boot
    ("relaxed", "stand") overrides the board file's; calibrated (True/False) says whether the
    servos are calibrated where no calibration file is read (host runs; None: the file, loaded
    by the console). With a console reader (the board entry: console.PollReader on sys.stdin)
    the console and the calibration file take over from the status line (docs/console.md); a
    boot that does not stand reads the file and powers up in the first frames (bring_up's later:
    the first frame sooner). Ctrl-C relaxes the servos (or holds them, the board file's on_exit)."""
    # The boot-only modules (the board and robot files and their checks): their heap back to the loop.
    release(*BOOT_ONLY, "robots." + robot_name, "robots.%s_cal" % robot_name)
    r.bring_up(reader, boot, calibrated, True)
    if reader is not None and r.board.get("watchdog_ms"):
        from machine import WDT

        r.watchdog = WDT(timeout=r.board["watchdog_ms"])
    r.serve(frames, 0 if reader is not None else STATUS_FRAMES)
