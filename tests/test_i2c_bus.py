"""The I2C bus model and the stub machine.I2C / SoftI2C, on CPython and in the MicroPython VM.

The firmware side is tests/scenarios/i2c_bus.py: a bus with a PCA9685 model at 0x40."""

import pytest


def test_scan_lists_chip_and_its_power_on_allcall_address(rt):
    out = rt.call("scenarios.i2c_bus:scans")
    # 0x70 is ALLCALLADR 0xE0 >> 1: a PCA9685 answers it from power-on (MODE1.ALLCALL = 1).
    assert out == [[0x40, 0x70], [], [0x40, 0x70]]


@pytest.mark.parametrize(
    "ctor, expect",
    [
        ("soft", 19),  # machine.SoftI2C(bus=bus)
        ("hw", 19),  # machine.I2C(0, bus=bus)
        ("hw:esp32", 19),
        ("hw:rp2", 5),
    ],
)
def test_absent_address_raises_like_micropython(rt, ctor, expect):
    assert rt.call("scenarios.i2c_bus:absent_address", ctor) == [("OSError", expect)] * 4


def test_data_nack_softi2c_returns_short_count_hardware_raises(rt):
    soft, hw, regs, ok = rt.call("scenarios.i2c_bus:data_nack")
    assert soft == ("ok", 2)  # pointer + one data byte acknowledged, the third byte NACKed
    assert hw == ("OSError", 5)
    # AI is off at power-on: every data byte lands in LED0_ON_L; the NACKed byte and those after never arrive.
    assert regs == [7, 0, 0, 0x10]
    assert ok == ("ok", 1)


def test_timeout_raises_etimedout_and_reset_fault_resets_chip(rt):
    assert rt.call("scenarios.i2c_bus:timeout_and_reset") == [("OSError", 110), ("ok", 2), "ok", 0x11, 1, 1]


@pytest.mark.parametrize(
    "byte, regs, counted",
    [
        (1, [0, 0], 2),  # the pointer byte times out: address + pointer on the wire, nothing lands
        (2, [0, 0], 3),  # AI off: the pointer lands, the first data byte times out
        (3, [5, 0], 4),  # 5 lands in LED0_ON_L (AI off), the byte after it times out
        (4, [6, 0], 4),  # past the transfer's last byte: no timeout, 6 overwrites 5 (AI off)
    ],
)
def test_a_timeout_strikes_exactly_its_byte(rt, byte, regs, counted):
    a, got_regs, got_counted, timeouts, r = rt.call("scenarios.i2c_bus:timeout_at_byte", byte)
    struck = byte <= 3
    assert a == (("OSError", 110) if struck else ("ok", 3))
    assert (got_regs, got_counted) == (regs, counted)
    # the read's bytes are 1 and 2 after its address: a timeout at byte 3 or 4 never strikes it
    assert r == ("OSError" if byte <= 2 else "ok")
    assert timeouts == (byte <= 3) + (byte <= 2)


def test_fault_count_covers_consecutive_transfers(rt):
    assert rt.call("scenarios.i2c_bus:fault_count", 2, 3) == [("OSError", 19), ("OSError", 19), ("ok", 1)]


def bits_write(n_data):
    """SCL periods of START + address + n data bytes + STOP (the documented formula)."""
    return 1 + 9 * (1 + n_data) + 1


@pytest.mark.parametrize("freq, t_buf", [(400000, 1300), (100000, 4700), (1000000, 500)])
def test_wire_figures_follow_the_documented_formula(rt, freq, t_buf):
    ta, ya, ba, na, tb, yb, bb, nb = rt.call("scenarios.i2c_bus:wire_figures", freq)
    assert (ta, ya, ba) == (1, 66, bits_write(65))
    assert na == ba * 10**9 // freq + t_buf
    # pointer write, repeated START, address + 2 bytes read: one transaction
    assert (tb, yb, bb) == (1, 5, 1 + 9 * 2 + 1 + 9 * 3 + 1)
    assert nb == bb * 10**9 // freq + t_buf


def test_mem_calls_writevto_and_addrsize(rt):
    regs, nbytes, mode1 = rt.call("scenarios.i2c_bus:mem_calls")
    assert regs == [1, 2, 3, 4]  # MODE1 0x30 sets AI: the burst walked LED0_ON_L..LED0_OFF_H
    assert nbytes == 1 + 2 + 1 + 1  # address, two memory address bytes, address again, data
    # The chip has 8-bit register addresses: of the two address bytes the first sets the pointer
    # (MODE1) and the second is written there as data.
    assert mode1 == 0x06


# The calls are in tests/scenarios/i2c_bus.py's BAD_CALLS, by these names.
BAD_CALLS = [
    "port stm32",
    "id -1",
    "freq 0",
    "freq 'fast'",
    "soft freq -5",
    "soft timeout -1",
    "addrsize 12",
    "fault smoke",
    "fault byte -1",
    "fault count 0",
    "attach 0x40 twice",
    "attach 0x80",
    "osc_hz 1000",
]


def test_every_bad_call_is_tested():
    from scenarios import i2c_bus

    assert sorted(BAD_CALLS) == i2c_bus.bad_call_names()


@pytest.mark.parametrize("call", BAD_CALLS)
def test_bad_arguments_raise_valueerror_naming_the_problem(rt, call):
    kind, msg = rt.call("scenarios.i2c_bus:bad_call", call)
    assert kind == "ValueError"
    assert any(w in msg for w in ("allowed", "taken", "7-bit", "doesn't exist"))


def test_default_bus_is_shared_per_id(rt):
    assert rt.call("scenarios.i2c_bus:shared_default_bus") == [[0x41, 0x70], []]


def test_transfers_allocate_nothing(mp):
    assert mp.call("scenarios.i2c_bus:transfers_heap") == 0


def test_external_clock_is_what_chips_see(rt):
    assert rt.call("scenarios.i2c_bus:external_clock") == [["RESTART_TOO_SOON"], [], 500]
