"""The I2C bus model (host/stubs i2c_bus) and the stub machine.I2C / SoftI2C on it, a PCA9685 model at 0x40."""

import _stub_i2c
import machine
from _stub_cp import BusI2C
from i2c_bus import I2CBus
from pca9685_model import PCA9685Model


def _bus():
    bus = I2CBus()
    return bus, bus.attach(PCA9685Model(0x40))


def _make(ctor, bus):
    """The I2C object ctor names: "soft", "hw" (machine.I2C(0)), or "hw:<port>"."""
    if ctor == "soft":
        return machine.SoftI2C(bus=bus)
    if ctor == "hw":
        return machine.I2C(0, bus=bus)
    return machine.I2C(0, bus=bus, port=ctor[3:])


def err(fn, *a, **kw):
    """('ok', fn's value), ('OSError', errno) or ('ValueError', text)."""
    try:
        return ("ok", fn(*a, **kw))
    except OSError as e:
        return ("OSError", e.args[0])
    except ValueError as e:
        return ("ValueError", str(e))


def scans():
    """[scan of a bus with the chip, scan of an empty bus, CircuitPython's busio.I2C scan of the bus
    with the chip (locked first, as CircuitPython demands)]."""
    bus, _ = _bus()
    cp = BusI2C(bus)
    cp.try_lock()
    return [machine.I2C(0, bus=bus).scan(), machine.SoftI2C(bus=I2CBus()).scan(), cp.scan()]


def absent_address(ctor):
    """err() of writeto, readfrom, readfrom_mem and writeto_mem to 0x41, where nothing answers."""
    bus, _ = _bus()
    i2c = _make(ctor, bus)
    return [
        err(i2c.writeto, 0x41, b"12"),
        err(i2c.readfrom, 0x41, 2),
        err(i2c.readfrom_mem, 0x41, 0, 1),
        err(i2c.writeto_mem, 0x41, 0, b"1"),
    ]


def data_nack():
    """[SoftI2C's writeto with byte 3 NACKed, rp2's the same, LED0's registers, a clean SoftI2C write]."""
    bus, chip = _bus()
    soft = machine.SoftI2C(bus=bus)
    hw = machine.I2C(0, bus=bus, port="rp2")
    res = []
    bus.fault(0x40, "nack", byte=3)
    res.append(err(soft.writeto, 0x40, bytes([0x06, 1, 2, 3, 4])))
    bus.fault(0x40, "nack", byte=3)
    res.append(err(hw.writeto, 0x40, bytes([0x06, 7, 8, 9, 10])))
    res.append(list(chip.regs[6:10]))
    res.append(err(soft.writeto, 0x40, bytes([0xFE])))
    return res


def timeout_and_reset():
    """[a write that times out, the next, a read after a 'reset' fault's status and MODE1, chip resets,
    bus timeouts]."""
    bus, chip = _bus()
    i2c = machine.I2C(0, bus=bus)
    bus.fault(0x40, "timeout", byte=0)
    a = err(i2c.writeto, 0x40, b"\x00\x20")
    b = err(i2c.writeto, 0x40, b"\x00\x20")
    before = chip.resets
    bus.fault(0x40, "reset")
    c = err(i2c.readfrom_mem, 0x40, 0, 1)
    return [a, b, c[0], c[1][0], chip.resets - before, bus.timeouts]


def timeout_at_byte(byte):
    """[writeto of pointer 0x06 + 5, 6 with a timeout armed at byte `byte` (0 = the address), LED0_ON_L
    and _H, bus bytes counted, bus timeouts, a 2-byte readfrom with the same fault]."""
    bus, chip = _bus()
    i2c = machine.I2C(0, bus=bus)
    bus.reset_stats()
    bus.fault(0x40, "timeout", byte=byte)
    a = err(i2c.writeto, 0x40, bytes([0x06, 5, 6]))
    regs = list(chip.regs[6:8])
    counted = bus.bytes
    bus.fault(0x40, "timeout", byte=byte)
    r = err(i2c.readfrom, 0x40, 2)
    return [a, regs, counted, bus.timeouts, r[0]]


def fault_count(count, transfers):
    """err() of each of transfers writes after a NACK fault with count."""
    bus, _ = _bus()
    i2c = machine.I2C(0, bus=bus)
    bus.fault(0x40, "nack", byte=0, count=count)
    return [err(i2c.writeto, 0x40, b"\x00") for _ in range(transfers)]


def wire_figures(freq):
    """[transactions, bytes, bits, ns] of a 65-byte write, then the same of a 2-byte readfrom_mem_into."""
    bus, _ = _bus()
    i2c = machine.I2C(0, freq, bus=bus)
    bus.reset_stats()
    i2c.writeto(0x40, bytearray(65))
    a = bus.stats()
    bus.reset_stats()
    buf = bytearray(2)
    i2c.readfrom_mem_into(0x40, 0, buf)
    b = bus.stats()
    keys = ("transactions", "bytes", "bits", "time_ns")
    return [a[k] for k in keys] + [b[k] for k in keys]


def mem_calls():
    """[LED0's four registers after writeto_mem + writevto, bytes of a 16-bit-address read, MODE1]."""
    bus, chip = _bus()
    i2c = machine.SoftI2C(bus=bus)
    i2c.writeto_mem(0x40, 0x00, b"\x30")
    i2c.writevto(0x40, (b"\x06", b"\x01\x02", b"\x03\x04"))
    a = i2c.readfrom_mem(0x40, 0x06, 4)
    bus.reset_stats()
    i2c.readfrom_mem(0x40, 0x0006, 1, addrsize=16)
    return [list(a), bus.bytes, chip.regs[0]]


BAD_CALLS = {
    "port stm32": lambda bus: machine.I2C(0, bus=bus, port="stm32"),
    "id -1": lambda bus: machine.I2C(-1, bus=bus),
    "freq 0": lambda bus: machine.I2C(0, 0, bus=bus),
    "freq 'fast'": lambda bus: machine.I2C(0, "fast", bus=bus),
    "soft freq -5": lambda bus: machine.SoftI2C(freq=-5, bus=bus),
    "soft timeout -1": lambda bus: machine.SoftI2C(timeout=-1, bus=bus),
    "addrsize 12": lambda bus: machine.SoftI2C(bus=bus).readfrom_mem(0x40, 0, 1, addrsize=12),
    "fault smoke": lambda bus: bus.fault(0x40, "smoke"),
    "fault byte -1": lambda bus: bus.fault(0x40, "nack", byte=-1),
    "fault count 0": lambda bus: bus.fault(0x40, "nack", count=0),
    "attach 0x40 twice": lambda bus: bus.attach(PCA9685Model(0x40)),
    "attach 0x80": lambda bus: bus.attach(PCA9685Model(0x80)),
    "osc_hz 1000": lambda bus: PCA9685Model(0x41, osc_hz=1000),
}


def bad_call(name):
    """err() of BAD_CALLS[name] on a bus with the chip at 0x40."""
    bus, _ = _bus()
    return err(BAD_CALLS[name], bus)


def bad_call_names():
    return sorted(BAD_CALLS)


def shared_default_bus():
    """[scan of machine.I2C(1), of machine.I2C(0)] after a chip is put at 0x41 on the shared bus 1."""
    _stub_i2c.reset()  # other tests in this process (the console's rig) leave chips on bus 0
    _stub_i2c.shared_bus(1).attach(PCA9685Model(0x41))
    return [machine.I2C(1).scan(), machine.I2C(0).scan()]


def transfers_heap():
    """MicroPython only (gc.mem_alloc): heap bytes of ten rounds of writeto, readfrom_mem_into,
    writeto_mem and readfrom_into."""
    import gc

    bus, _ = _bus()
    i2c = machine.I2C(0, bus=bus)
    buf = bytearray(65)
    buf[0] = 2  # SUBADR1: no violation to record
    one = bytearray(b"\x04")

    def go():
        i2c.writeto(0x40, buf)
        i2c.readfrom_mem_into(0x40, 0, one)
        i2c.writeto_mem(0x40, 0x01, one)
        i2c.readfrom_into(0x40, one)

    go()
    gc.collect()
    gc.disable()
    a = gc.mem_alloc()
    for _ in range(10):
        go()
    used = gc.mem_alloc() - a
    gc.enable()
    return used


def external_clock():
    """[violations of a RESTART 1000 bus-us but 0 clock-us after wake, of one 500 clock-us after, bus.now_us()]
    on a bus whose chips read time from an outside clock."""
    t = [0]
    bus = I2CBus(clock_us=lambda: t[0])
    chip = bus.attach(PCA9685Model(0x40))
    i2c = machine.I2C(0, bus=bus)
    i2c.writeto_mem(0x40, 0, b"\x20")
    bus.sleep_us(1000)  # the bus's own clock no longer counts
    i2c.writeto_mem(0x40, 0, b"\xa0")
    a = chip.violation_codes()
    chip.clear_violations()
    i2c.writeto_mem(0x40, 0, b"\x30")
    i2c.writeto_mem(0x40, 0, b"\x20")
    t[0] += 500
    i2c.writeto_mem(0x40, 0, b"\xa0")
    return [a, chip.violation_codes(), bus.now_us()]
