"""machine.ADC as MicroPython's rp2 port has it, reading voltages a test sets on the virtual clock.

ADC(id): a Pin (GPIO 26..29) or an int: 26..29 (the GPIO), 0..3 (the channel: GPIO 26 + n) or
4 (the temperature sensor); anything else is the port's ValueError. read_u16() converts the
pin's voltage as the RP2040 does (datasheet, ADC: 12 bits, the 3.3 V ADC_AVDD as the reference,
code = V * 4096 / 3.3 V rounded, at most 4095) and scales it to 16 bits as the rp2 port's
ports/rp2/machine_adc.c does: code << 4 | code >> 8 (4095 -> 65535, 2048 -> 32776).

A pin's voltage comes from a source a test sets:
    battery(28, 333, [(0, 8000), (5000, 7000)])   # a pack through a 333 permille divider:
                                                  # 8000 mV from t = 0 ms, 7000 mV from 5000 ms
    volts(28, [(0, 2500)])                        # the pin's own mV, as steps
Steps are (from_ms, mV) in time order; the value holds until the next step (virtual time,
_stub_clock.now_us()). A pin with no source reads 0 (tied to ground). Nothing on the read path
allocates (small integers only).
"""

import _stub_clock as clock

REF_MV = 3300
_sources = {}  # GPIO -> [divider_permille, steps]


def reset():
    """Forget every source (between tests)."""
    _sources.clear()


def battery(gpio, divider_permille, steps):
    """The pin sees a pack's mV (steps of (from_ms, pack mV)) through divider_permille (1..1000)."""
    _check(gpio, steps)
    if not isinstance(divider_permille, int) or not 1 <= divider_permille <= 1000:
        raise ValueError("divider_permille: %r, allowed 1..1000" % (divider_permille,))
    _sources[gpio] = [divider_permille, list(steps)]


def volts(gpio, steps):
    """The pin's own voltage: steps of (from_ms, mV at the pin)."""
    _check(gpio, steps)
    _sources[gpio] = [1000, list(steps)]


def _check(gpio, steps):
    if gpio not in (26, 27, 28, 29):
        raise ValueError("gpio %r has no ADC on the RP2040 (allowed 26..29)" % (gpio,))
    last = -1
    for t, mv in steps:
        if not isinstance(t, int) or not isinstance(mv, int) or t < last or mv < 0:
            raise ValueError("steps: need (from_ms, mV) pairs of ints >= 0 in time order, got %r" % ((t, mv),))
        last = t


def pin_mv(gpio):
    """The pin's voltage now (mV): the source's present step through its divider."""
    src = _sources.get(gpio)
    if src is None:
        return 0
    now_ms = clock.now_us() // 1000
    mv = 0
    for t, v in src[1]:
        if t > now_ms:
            break
        mv = v
    return mv * src[0] // 1000


def code12(mv):
    """The RP2040's 12-bit code for mV at the pin (rounded, clamped to 0..4095)."""
    if mv >= REF_MV:
        return 4095
    c = (mv * 4096 + REF_MV // 2) // REF_MV
    return c if c < 4095 else 4095


class ADC:
    CORE_TEMP = 4

    def __init__(self, id):
        if isinstance(id, int):
            if 0 <= id <= 3:
                id = 26 + id
            elif id != 4 and not 26 <= id <= 29:
                raise ValueError("invalid channel")
            self.gpio = id
        else:
            gpio = getattr(id, "id", None)
            if not isinstance(gpio, int) or not 26 <= gpio <= 29:
                raise ValueError("Pin doesn't have ADC capabilities")
            self.gpio = gpio

    def read_u16(self):
        c = code12(pin_mv(self.gpio)) if self.gpio != 4 else 876  # ~27 C on the sensor
        return c << 4 | c >> 8

    def __repr__(self):
        return "<ADC channel=%d>" % (self.gpio - 26 if self.gpio != 4 else 4)
