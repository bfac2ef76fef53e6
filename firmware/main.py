"""Board entry point (MicroPython): the only file that touches real hardware.

Loads the board file and the robot file named below, builds the loop (runner.Runner), stands
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
from runner import Runner, release  # noqa: E402

from drivers import hcsr04, pca9685  # noqa: E402
from hexapod import geometry  # noqa: E402

STATUS_FRAMES = 250  # 5 s of 20 ms frames
# Pings per median, drivers.hcsr04 order: each sensor pings every 100 ms, so a median of n
# lags about (n - 1) * 50 ms. The wall follower steers on the side sonars: no median there
# (its PID takes each fresh reading once); the front one keeps 3 against a stray echo.
SONAR_SAMPLES = (3, 1, 1, 1, 1)


def build(board_name=BOARD, robot_name=ROBOT, clock=time, max_range=10000, samples=SONAR_SAMPLES, bank=None):
    """The Runner for a board and robot on this machine's I2C and pins (max_range: 0.1 mm;
    samples: pings per median for each sensor, drivers.hcsr04 order; bank: where frames go,
    None for the board's PCA9685s on its I2C)."""
    from hexapod import board as boards  # boot only: main() releases it (runner.release)

    board = boards.load(board_name)
    robot_module = __import__("robots." + robot_name, None, None, ("NAME",))
    table = boards.servo_table(board)
    if bank is None:
        bus = board["i2c"]
        i2c = I2C(bus["id"], scl=Pin(bus["scl"]), sda=Pin(bus["sda"]), freq=bus["freq"])
        bank = pca9685.servo_bank(i2c, board["pca9685"], table, sleep_us=clock.sleep_us)
    sensors = []
    pins = boards.sensor_pins(board)
    for k in range(len(pins)):
        trigger, echo = pins[k]
        sensors.append(
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
    r = Runner(
        geometry.load(robot_module),
        [row[2] for row in table],
        bank,
        sensors,
        clock,
        boards.sensor_mounts(board),
        battery=monitor,
        adc=adc,
    )
    r.board = board
    r.sonar_pins = pins
    return r


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
    release("hexapod.board", "hexapod.robotfile", "robots." + robot_name)  # boot-only: its heap back to the loop
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
