"""The I2C bus model and the stub machine.I2C / SoftI2C, on CPython and in the MicroPython VM."""

import pytest

PRE = """
import machine
from i2c_bus import I2CBus
from pca9685_model import PCA9685Model
bus = I2CBus()
chip = bus.attach(PCA9685Model(0x40))
def err(fn, *a, **kw):
    try:
        return ('ok', fn(*a, **kw))
    except OSError as e:
        return ('OSError', e.args[0])
    except ValueError as e:
        return ('ValueError', str(e))
"""


def test_scan_lists_chip_and_its_power_on_allcall_address(rt):
    out = rt.value(PRE + "print([machine.I2C(0, bus=bus).scan(), machine.SoftI2C(bus=I2CBus()).scan()])")
    # 0x70 is ALLCALLADR 0xE0 >> 1: a PCA9685 answers it from power-on (MODE1.ALLCALL = 1).
    assert out == [[0x40, 0x70], []]


@pytest.mark.parametrize(
    "ctor, expect",
    [
        ("machine.SoftI2C(bus=bus)", 19),
        ("machine.I2C(0, bus=bus)", 19),
        ("machine.I2C(0, bus=bus, port='esp32')", 19),
        ("machine.I2C(0, bus=bus, port='rp2')", 5),
    ],
)
def test_absent_address_raises_like_micropython(rt, ctor, expect):
    src = PRE + "i2c = %s\nprint([err(i2c.writeto, 0x41, b'12'), err(i2c.readfrom, 0x41, 2), " % ctor
    src += "err(i2c.readfrom_mem, 0x41, 0, 1), err(i2c.writeto_mem, 0x41, 0, b'1')])"
    assert rt.value(src) == [("OSError", expect)] * 4


def test_data_nack_softi2c_returns_short_count_hardware_raises(rt):
    src = (
        PRE
        + """
soft = machine.SoftI2C(bus=bus)
hw = machine.I2C(0, bus=bus, port='rp2')
res = []
bus.fault(0x40, 'nack', byte=3)
res.append(err(soft.writeto, 0x40, bytes([0x06, 1, 2, 3, 4])))
bus.fault(0x40, 'nack', byte=3)
res.append(err(hw.writeto, 0x40, bytes([0x06, 7, 8, 9, 10])))
res.append(list(chip.regs[6:10]))
res.append(err(soft.writeto, 0x40, bytes([0xFE])))
print(res)
"""
    )
    soft, hw, regs, ok = rt.value(src)
    assert soft == ("ok", 2)  # pointer + one data byte acknowledged, the third byte NACKed
    assert hw == ("OSError", 5)
    # AI is off at power-on: every data byte lands in LED0_ON_L; the NACKed byte and those after never arrive.
    assert regs == [7, 0, 0, 0x10]
    assert ok == ("ok", 1)


def test_timeout_raises_etimedout_and_reset_fault_resets_chip(rt):
    src = (
        PRE
        + """
i2c = machine.I2C(0, bus=bus)
bus.fault(0x40, 'timeout', byte=0)
a = err(i2c.writeto, 0x40, b'\\x00\\x20')
b = err(i2c.writeto, 0x40, b'\\x00\\x20')
before = chip.resets
bus.fault(0x40, 'reset')
c = err(i2c.readfrom_mem, 0x40, 0, 1)
print([a, b, c[0], c[1][0], chip.resets - before, bus.timeouts])
"""
    )
    assert rt.value(src) == [("OSError", 110), ("ok", 2), "ok", 0x11, 1, 1]


def test_fault_count_covers_consecutive_transfers(rt):
    src = (
        PRE
        + """
i2c = machine.I2C(0, bus=bus)
bus.fault(0x40, 'nack', byte=0, count=2)
print([err(i2c.writeto, 0x40, b'\\x00') for _ in range(3)])
"""
    )
    assert rt.value(src) == [("OSError", 19), ("OSError", 19), ("ok", 1)]


def bits_write(n_data):
    """SCL periods of START + address + n data bytes + STOP (the documented formula)."""
    return 1 + 9 * (1 + n_data) + 1


@pytest.mark.parametrize("freq, t_buf", [(400000, 1300), (100000, 4700), (1000000, 500)])
def test_wire_figures_follow_the_documented_formula(rt, freq, t_buf):
    src = (
        PRE
        + """
i2c = machine.I2C(0, %d, bus=bus)
bus.reset_stats()
i2c.writeto(0x40, bytearray(65))
a = bus.stats()
bus.reset_stats()
buf = bytearray(2)
i2c.readfrom_mem_into(0x40, 0, buf)
b = bus.stats()
print([a['transactions'], a['bytes'], a['bits'], a['time_ns'], b['transactions'], b['bytes'], b['bits'], b['time_ns']])
"""
        % freq
    )
    ta, ya, ba, na, tb, yb, bb, nb = rt.value(src)
    assert (ta, ya, ba) == (1, 66, bits_write(65))
    assert na == ba * 10**9 // freq + t_buf
    # pointer write, repeated START, address + 2 bytes read: one transaction
    assert (tb, yb, bb) == (1, 5, 1 + 9 * 2 + 1 + 9 * 3 + 1)
    assert nb == bb * 10**9 // freq + t_buf


def test_mem_calls_writevto_and_addrsize(rt):
    src = (
        PRE
        + """
i2c = machine.SoftI2C(bus=bus)
i2c.writeto_mem(0x40, 0x00, b'\\x30')
i2c.writevto(0x40, (b'\\x06', b'\\x01\\x02', b'\\x03\\x04'))
a = i2c.readfrom_mem(0x40, 0x06, 4)
bus.reset_stats()
i2c.readfrom_mem(0x40, 0x0006, 1, addrsize=16)
print([list(a), bus.bytes, chip.regs[0]])
"""
    )
    regs, nbytes, mode1 = rt.value(src)
    assert regs == [1, 2, 3, 4]  # MODE1 0x30 sets AI: the burst walked LED0_ON_L..LED0_OFF_H
    assert nbytes == 1 + 2 + 1 + 1  # address, two memory address bytes, address again, data
    # The chip has 8-bit register addresses: of the two address bytes the first sets the pointer
    # (MODE1) and the second is written there as data.
    assert mode1 == 0x06


BAD_CALLS = [
    "machine.I2C(0, bus=bus, port='stm32')",
    "machine.I2C(-1, bus=bus)",
    "machine.I2C(0, 0, bus=bus)",
    "machine.I2C(0, 'fast', bus=bus)",
    "machine.SoftI2C(freq=-5, bus=bus)",
    "machine.SoftI2C(timeout=-1, bus=bus)",
    "machine.SoftI2C(bus=bus).readfrom_mem(0x40, 0, 1, addrsize=12)",
    "bus.fault(0x40, 'smoke')",
    "bus.fault(0x40, 'nack', byte=-1)",
    "bus.fault(0x40, 'nack', count=0)",
    "bus.attach(PCA9685Model(0x40))",
    "bus.attach(PCA9685Model(0x80))",
    "PCA9685Model(0x41, osc_hz=1000)",
]


@pytest.mark.parametrize("call", BAD_CALLS)
def test_bad_arguments_raise_valueerror_naming_the_problem(rt, call):
    kind, msg = rt.value(PRE + "print(err(lambda: %s))" % call)
    assert kind == "ValueError"
    assert any(w in msg for w in ("allowed", "taken", "7-bit", "doesn't exist"))


def test_default_bus_is_shared_per_id(rt):
    src = """
import machine, _stub_i2c
from pca9685_model import PCA9685Model
_stub_i2c.reset()  # other tests in this process (the console's rig) leave chips on bus 0
_stub_i2c.shared_bus(1).attach(PCA9685Model(0x41))
print([machine.I2C(1).scan(), machine.I2C(0).scan()])
"""
    assert rt.value(src) == [[0x41, 0x70], []]


def test_transfers_allocate_nothing(mp):
    src = (
        PRE
        + """
import gc
i2c = machine.I2C(0, bus=bus)
buf = bytearray(65); buf[0] = 2  # SUBADR1: no violation to record
one = bytearray(b'\\x04')
def go():
    i2c.writeto(0x40, buf)
    i2c.readfrom_mem_into(0x40, 0, one)
    i2c.writeto_mem(0x40, 0x01, one)
    i2c.readfrom_into(0x40, one)
go()
gc.collect(); gc.disable()
a = gc.mem_alloc()
for _ in range(10):
    go()
print(gc.mem_alloc() - a)
"""
    )
    assert mp.value(src) == 0


def test_external_clock_is_what_chips_see(rt):
    src = """
import machine
from i2c_bus import I2CBus
from pca9685_model import PCA9685Model
t = [0]
bus = I2CBus(clock_us=lambda: t[0])
chip = bus.attach(PCA9685Model(0x40))
i2c = machine.I2C(0, bus=bus)
i2c.writeto_mem(0x40, 0, b'\\x20')
bus.sleep_us(1000)  # the bus's own clock no longer counts
i2c.writeto_mem(0x40, 0, b'\\xa0')
a = chip.violation_codes()
chip.clear_violations()
i2c.writeto_mem(0x40, 0, b'\\x30'); i2c.writeto_mem(0x40, 0, b'\\x20')
t[0] += 500
i2c.writeto_mem(0x40, 0, b'\\xa0')
print([a, chip.violation_codes(), bus.now_us()])
"""
    assert rt.value(src) == [["RESTART_TOO_SOON"], [], 500]
