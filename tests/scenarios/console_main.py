"""main.py with the console (tests/test_console_main.py): Ctrl-C leaving the loop, the watchdog,
the select.poll reader, on the stub board (scenarios.console_rig). These print what the board
prints (main's notices, the console's replies on stdout): run them through rt.run."""

import _stub_clock as clock
import _stub_serial
import console
import main
from scenarios.console_rig import Board


class CtrlC(_stub_serial.BufferReader):
    """A reader holding `get 1` that raises KeyboardInterrupt (Ctrl-C) at its read number after + 1."""

    def __init__(self, after):
        _stub_serial.BufferReader.__init__(self, b"get 1\n")
        self.after = after
        self.calls = 0

    def read_byte(self):
        self.calls += 1
        if self.calls > self.after:
            raise KeyboardInterrupt
        return _stub_serial.BufferReader.read_byte(self)


def ctrl_c(on_exit):
    """main.main with the board file's on_exit (and a 4 s watchdog), booting standing, stopped by
    Ctrl-C after 400 reads; prints what the board prints, then [the runner is main.runner, frames,
    the PCA9685 channels (us), mode, watchdog expired, its timeout_ms]."""
    import boards.pico

    b = Board()
    boards.pico.BOARD["on_exit"] = on_exit
    boards.pico.BOARD["watchdog_ms"] = 4000
    try:
        r2 = main.main(clock=clock, reader=CtrlC(400), boot="stand", calibrated=True)
    finally:
        del boards.pico.BOARD["on_exit"]
        del boards.pico.BOARD["watchdog_ms"]
    print(
        repr((r2 is main.runner, r2.frames, b.channels(), r2.robot.mode, r2.watchdog.expired(), r2.watchdog.timeout_ms))
    )


def watchdog():
    """A 1 s watchdog fed for 60 frames, then the loop hung 1.1 s: [expired after the frames, after the hang]."""
    from machine import WDT

    r = Board().r
    r.watchdog = WDT(timeout=1000)
    r.run(60)
    fed = r.watchdog.expired()
    clock.advance_us(1100000)  # a loop hung for 1.1 s
    return [fed, r.watchdog.expired()]


def poll_reader():
    """The console on MicroPython's select.poll reader of stdin: prints the heap bytes of 100
    frames with nothing waiting, then answers on stdout until a line has come in."""
    import sys

    from scenarios.heap import heap_bytes

    b = Board()
    con = b.con
    con.reader = console.PollReader()
    con.out = print
    print(repr(heap_bytes(b.frames, 100)))
    if hasattr(sys.stdout, "flush"):
        sys.stdout.flush()
    while not con.lines:
        b.frames(1)
