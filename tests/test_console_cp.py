"""The console on CircuitPython's entry (firmware/code.py) with fake CircuitPython modules:
SerialReader on supervisor.runtime.serial_bytes_available and sys.stdin, the calibration file
through `os` (a temporary directory), replies on stdout (CPython only)."""

import sys

from tests.test_cp_code import rig  # noqa: F401 (fixture)


class FakeStdin:
    """sys.stdin on CircuitPython: read(1) returns one character; bytes arrive when fed."""

    def __init__(self):
        self.pending = ""

    def feed(self, text):
        self.pending += text

    def read(self, n):
        c, self.pending = self.pending[:n], self.pending[n:]
        return c


def test_console_runs_in_code_py_and_saves_through_os(rig, monkeypatch, tmp_path, capsys):  # noqa: F811
    g = rig()
    stdin = FakeStdin()

    class Runtime:
        @property
        def serial_bytes_available(self):
            return len(stdin.pending) > 0

    runtime = Runtime()
    monkeypatch.setattr(sys.modules["supervisor"], "runtime", runtime, raising=False)
    monkeypatch.setattr(sys, "stdin", stdin)
    monkeypatch.chdir(tmp_path)
    stdin.feed("get 2\r\nfoot 2 130 0 -80\r\ntrim 2 femur 15\r\nsave\r\n\xff\r\n")
    r = g.code.main(frames=200, clock=g.clock, reader=g.code.SerialReader(), boot="stand", calibrated=True)
    out = capsys.readouterr().out.splitlines()
    assert out.pop(0) == "cal: no hexapod_cal.txt; the robot file's calibration is in use"
    assert out[0] == "boot: standing up (the board file's boot setting is stand, the servos are calibrated)"
    # standing up; leg 2 is in the middle pair, which the soft start leaves off for its first 8 frames
    assert out[1].startswith("ok leg 2 angles 0.00 ") and " pulses 0 0 0 " in out[1]
    # main() stood the robot up at boot (boot stand, calibrated): a jog is refused while the posture move runs
    assert out[2] == "err foot: refused: a posture or pose move is still running"
    assert out[3].startswith("err trim: refused: a posture")
    assert out[4].startswith("ok saved hexapod_cal.txt crc ")
    assert out[5] == "err non-text byte 0xff in line (allowed: printable ASCII)"
    assert len(out) == 6 and r.frames == 200
    assert (tmp_path / "hexapod_cal.txt").read_text().startswith("hexapod-cal 2\n1 coxa 0 1 600 2400\n")
