"""Source text shared by the console tests: the pico board's loop on the stub machine (PCA9685
and HC-SR04 models, virtual clock) with a console reading from a BufferReader. Runs on CPython
and in the MicroPython VM.

    say(line) -> the reply line, after the frames it took (one poll per frame, as Runner.run)
    frames(n) -> runs n frames
    channels() -> the PCA9685 models' 18 servo pulse widths (us), leg/joint order
    unsafe() -> servos whose output is neither off nor inside their calibrated min..max
"""

import pytest

RIG = """
import _stub_clock as clock
import _stub_i2c
import _stub_pins
import hcsr04_model
import stub_board
from hexapod import board as boards
from hexapod import robotcal
import console
import main

BOARD = stub_board.reset("pico")
TABLE = boards.servo_table(BOARD, robotcal.servo_maps(robotcal.load("default")))
bus, chips = stub_board.pca9685_models(BOARD)
SONAR = stub_board.sonar_models(BOARD, [3000 + 1000 * k for k in range(5)])
r = main.build(clock=clock)
reader = console.BufferReader()
REPLIES = []


def out(line, more=None):  # as print: a tagged reply comes as (tag, line)
    REPLIES.append(line if more is None else line + " " + more)


con = console.start(r, reader, None, out=out)
SERVOS = r.robot.servos


def frames(n):
    for _ in range(n):
        r.step()
        con.poll()
        r.wait()


def say(line):
    before = len(REPLIES)
    reader.feed(line.encode() + b"\\n")
    for _ in range(20):
        frames(1)
        if len(REPLIES) > before:
            return REPLIES[-1]
    return None


def channels():
    return [chips[a].pulse_us(ch) for a, ch, _ in TABLE]


def unsafe():
    bad = []
    for k in range(18):
        a, ch, _ = TABLE[k]
        s = SERVOS[k]
        ns = chips[a].pulse_ns(ch)
        m = chips[a]
        half = (m.prescale() + 1) * 500000000 // m.clock_hz() + 1
        if ns and not s.min_us * 1000 - half <= ns <= s.max_us * 1000 + half:
            bad.append((k, ns))
    return bad


def state():
    return (list(r.robot.pulses), list(r.robot.angles), r.robot.mode,
            [(s.centre_us, s.direction, s.min_us, s.max_us) for s in SERVOS], list(con.trims))
"""


@pytest.fixture(autouse=True)
def clean_stubs():
    """The CPython runs share this process's stub modules: leave no bus, chip or wire behind."""
    yield
    import _stub_clock
    import _stub_i2c
    import _stub_pins

    _stub_i2c.reset()
    _stub_pins.reset()
    _stub_clock.reset(0)
