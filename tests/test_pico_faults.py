"""The fault log through a soft reset on the emulated Pico (real rp2 MicroPython in rp2040js, whose
watchdog models SCRATCH0-7): main.fault_keeper() picks the watchdog scratch registers on rp2, two
faults recorded before machine.soft_reset() are there after it, and nothing else is."""

import pytest

from hexapod_host.pico import emulator as pico

REASON = pico.missing()
pytestmark = pytest.mark.skipif(REASON is not None, reason=REASON or "")

BEFORE = """
import machine, main
from hexapod import faultlog
keeper = main.fault_keeper()
print("keeper", type(keeper).__name__)
log = faultlog.FaultLog(keeper)
print("at power-up", log.count(), log.kept)
log.record(faultlog.I2C, 1, 1234)
log.record(faultlog.SONAR, 2, 5000)
LEFT_BEHIND = 1
machine.soft_reset()
"""

AFTER = """
import machine, main
from hexapod import faultlog
print("globals gone", "LEFT_BEHIND" not in globals())
log = faultlog.FaultLog(main.fault_keeper())
print("kept", log.kept, [log.entry(i) for i in range(log.count())])
print("scratch", [hex(machine.mem32[0x4005800C + 4 * i]) for i in range(8)])
"""


def test_the_fault_log_outlives_a_soft_reset(tmp_path):
    a, b = tmp_path / "before.py", tmp_path / "after.py"
    a.write_text(BEFORE)
    b.write_text(AFTER)
    with pico.flashed() as fs:
        status, out, err, _ = pico.run([str(a), str(b)], fs=fs, timeout=300)
    assert status == 0, out + err
    lines = out.splitlines()
    assert lines[:2] == ["keeper Rp2Scratch", "at power-up 0 0"]  # the emulator powers up with scratch 0
    assert lines[2] == "globals gone True"  # a real soft reset ran between the two scripts
    assert lines[3] == "kept 2 [(1, 1, 1234, True), (3, 2, 5000, True)]"
    # packed by hand: 0x10000000 | kind << 25 | what << 22 | frame; SCRATCH4-7 untouched (the bootrom's)
    assert lines[4] == "scratch ['0x124004d2', '0x16801388', '0x0', '0x0', '0x0', '0x0', '0x0', '0x0']"
