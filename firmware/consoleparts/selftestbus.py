"""selftest's bus checks (`i2c`, `pca9685 <address>`) and their wiring hints: selftest.Checks imports
this module for its first step, and the console drops it with selftest when the job ends (on
CircuitPython, which compiles a module's source at each import, two smaller compiles than one).
"""

_GROUND = "common ground with the Pico?"


def _hex(a):
    return "0x%02x" % a


def jumper_hint(address):
    """Which address jumpers a PCA9685 board at address (0x40..0x7f) has bridged."""
    bits = address - 0x40
    if not 0 <= bits < 64:
        return "is it a PCA9685 at all?"
    if not bits:
        return "are all its address jumpers (A0-A5) open?"
    on = ["A%d" % i for i in range(6) if bits >> i & 1]
    return "is its %s jumper bridged (and no other)?" % "+".join(on)


def no_answer_hint(address):
    return "%s is its VCC on 3V3? SDA and SCL wired through? %s" % (jumper_hint(address), _GROUND)


def run(checks, out, board, chips):
    """The bus's checks, each a line: the scan, then each chip."""
    i2c(checks, out, board, chips)
    for c in chips:
        chip(checks, out, c)


def i2c(checks, out, board, chips):
    """The bus's scan: every chip of the board file answers, nothing else (0x70: ALLCALL)."""
    if not chips:
        checks._line(out, True, "i2c n/a (no PCA9685 bank on this loop)")
        return
    for c in chips:
        c.sync()  # a background burst (rp2) finishes before the bus is scanned
    i2c = chips[0].i2c
    try:
        locked = hasattr(i2c, "try_lock")  # busio.I2C (CircuitPython) is scanned under its lock
        while locked and not i2c.try_lock():
            pass
        try:
            found = i2c.scan()
        finally:
            if locked:
                i2c.unlock()
    except OSError as e:
        checks._line(out, False, "i2c scan failed (%s): SDA or SCL held low? pull-ups? %s" % (e, _GROUND))
        return
    want = [c.address for c in chips]
    missing = [a for a in want if a not in found]
    extra = [a for a in found if a not in want]
    names = " ".join(_hex(a) for a in found) if found else "nothing"
    text = "i2c found " + names
    if extra:
        text += " (not in the board file: %s%s)" % (
            " ".join(_hex(a) for a in extra),
            "; 0x70 is a PCA9685's power-on ALLCALL address" if 0x70 in extra else "",
        )
    if not found:
        pins = board["i2c"] if board else {}
        checks._line(
            out,
            False,
            "%s: no chip answers: SDA on %s and SCL on %s? the PCA9685 boards powered (VCC on 3V3)? %s"
            % (text, pins.get("sda", "?"), pins.get("scl", "?"), _GROUND),
        )
    elif missing:
        checks._line(
            out,
            False,
            "%s, missing %s: %s" % (text, " ".join(_hex(a) for a in missing), no_answer_hint(missing[0])),
        )
    else:
        checks._line(out, True, text)


def chip(checks, out, c):
    """Chip c answers, MODE1 and PRE_SCALE read back as the driver wrote them."""
    name = "pca9685 " + _hex(c.address)
    mode1, pre = c.read_back()
    want1 = c.mode1_written()
    if mode1 < 0 or pre < 0:
        checks._line(out, False, "%s: no answer: %s" % (name, no_answer_hint(c.address)))
        return
    got = "MODE1 %s PRE_SCALE %s" % (_hex(mode1), _hex(pre))
    if mode1 != want1 or pre != c.prescale:
        checks._line(
            out,
            False,
            "%s %s, the driver wrote MODE1 %s PRE_SCALE %s: it reset since start-up (a brownout: servo "
            "power sagging into its VCC? VCC on 3V3, not on the servo supply) or another I2C master "
            "writes it; the loop sets it up again within %d frames"
            % (name, got, _hex(want1), _hex(c.prescale), c._check_every),
        )
        return
    checks._line(out, True, "%s %s (%d Hz at osc %d Hz)" % (name, got, c.freq_hz, c.osc_hz))
