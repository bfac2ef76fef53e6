"""Board entry point (MicroPython): the only file that touches real hardware.

Loads the board file and the robot's files named below (robots/ROBOT.py, its build, and
robots/ROBOT_cal.py, its servo calibration and sonar mounts), builds the loop (runner.Runner), stands
the robot up and runs 50 Hz frames for ever, printing a status line every 5 s; with a "follow"
setting in the board file it follows that wall once standing (hexapod.follow); with a
"battery" setting it watches the pack on that ADC pin (hexapod.battery). Edit BOARD and
ROBOT to match yours (files in boards/ and robots/).
"""

import time

BOARD = "pico"
ROBOT = "default"
# The robot file first, into a heap the loop's modules have not yet cut up: imported after them it
# found no block big enough on an emulated Pico (MemoryError with 78 KB free, none over 5.9 KB,
# 2026-11-27). main() releases it once the robot is built.
__import__("robots." + ROBOT)

from machine import I2C, Pin, time_pulse_us  # noqa: E402
from runner import BOOT_ONLY, FRAME_MS, Runner, release  # noqa: E402

from drivers import hcsr04, pca9685  # noqa: E402
from hexapod import geometry, sensors  # noqa: E402

STATUS_FRAMES = 250  # 5 s of 20 ms frames
# Pings per median, hexapod.sensors order: each sensor pings every 100 ms, so a median of n
# lags about (n - 1) * 50 ms. The wall follower steers on the side sonars: no median there
# (its PID takes each fresh reading once); the front one keeps 3 against a stray echo.
SONAR_SAMPLES = (3, 1, 1, 1, 1)


def build(board_name=BOARD, robot_name=ROBOT, clock=time, max_range=10000, samples=SONAR_SAMPLES, bank=None):
    """The Runner for a board and robot on this machine's I2C and pins (max_range: 0.1 mm;
    samples: pings per median for each sonar, hexapod.sensors order; bank: where frames go,
    None for the board's PCA9685s on its I2C)."""
    from hexapod import board as boards  # boot only: main() releases these (runner.release)
    from hexapod import robotcal

    board = boards.load(board_name)
    robot_module = __import__("robots." + robot_name, None, None, ("NAME",))
    robot = geometry.load(robot_module)
    cal = robotcal.load(robot_name, robot.limits)
    table = boards.servo_table(board, robotcal.servo_maps(cal))
    if bank is None:
        bus = board["i2c"]
        i2c = I2C(bus["id"], scl=Pin(bus["scl"]), sda=Pin(bus["sda"]), freq=bus["freq"])
        bank = pca9685.servo_bank(i2c, board["pca9685"], table, sleep_us=clock.sleep_us)
    rangers = []
    pins = boards.sonar_pins(board)
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

        monitor = battery.Monitor(*boards.battery_args(board["battery"]))
        adc = ADC(Pin(board["battery"]["pin"]))
    sonars = sensors.Sonars(hcsr04.RoundRobin(rangers, tick_ms=FRAME_MS), len(rangers))
    r = Runner(
        robot,
        [row[2] for row in table],
        bank,
        sonars,
        clock,
        robotcal.sensor_mounts(cal),
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


def main(frames=-1, clock=time, board_name=BOARD, robot_name=ROBOT, reader=None, boot=None, calibrated=None):
    """Build, power up (runner.power_up: relaxed, or with the board file's "boot": "stand" and a
    valid calibration file stand up, then follow the board's "follow" wall, if set), run frames
    (for ever when -1) with a status line every 5 s; returns the Runner. boot ("relaxed",
    "stand") overrides the board file's; calibrated (True/False) says whether the servos are
    calibrated where no calibration file is read (host runs; None: the file, loaded by the
    console). With a console reader (the
    board entry: console.PollReader on sys.stdin) the console and the calibration file take
    over from the status line (docs/console.md); Ctrl-C relaxes the servos (or holds them,
    the board file's on_exit) and leaves `runner` for the REPL."""
    global runner
    r = runner = build(board_name, robot_name, clock)
    # The boot-only modules (the board and robot files and their checks): their heap back to the loop.
    release(*BOOT_ONLY, "robots." + robot_name, "robots.%s_cal" % robot_name)
    r.bring_up(reader, boot, calibrated)
    if reader is not None and r.board.get("watchdog_ms"):
        from machine import WDT

        r.watchdog = WDT(timeout=r.board["watchdog_ms"])
    r.serve(frames, 0 if reader is not None else STATUS_FRAMES)
    return r


runner = None  # the Runner main() built: the REPL's handle after Ctrl-C

if __name__ == "__main__":
    import console

    main(reader=console.PollReader())
