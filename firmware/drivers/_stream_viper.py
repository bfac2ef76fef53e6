"""stream.digits compiled by MicroPython's viper emitter: the same integer steps, as machine code
(docs/viper.md lists every viper twin). A telemetry line's 46 fields: 2.1 ms as plain bytecode on
the emulated Pico, far over the frame budget a line may take.

Viper integers are machine words; a field is a 32-bit array("i") value (ptr32). stream's no-value
field (_NONE, -0x3FFFFFFF) is written out below as a literal: viper folds only a module's own
const()s. tests/test_console_stream.py proves digits equal to stream.digits.
"""

import micropython


@micropython.viper
def digits(buf, at: int, vals, count: int) -> int:
    """stream.digits: vals[0:count] as ' ' and ASCII decimal ('-' for the no-value field) into buf
    from at, then '\\n'; returns the end."""
    sb = 1
    sb <<= 31  # (v ^ sb) - sb sign-extends a ptr32 load (unsigned on a 64-bit VM); on a board it is v
    b = ptr8(buf)  # noqa: F821 (a viper built-in)
    v = ptr32(vals)  # noqa: F821
    for k in range(count):
        x = (v[k] ^ sb) - sb
        b[at] = 32
        at += 1
        if x < 0:
            b[at] = 45
            at += 1
            if x == 0 - 1073741823:  # stream._NONE: the whole field is '-'
                continue
            x = 0 - x
        end = at + 1
        t = x // 10
        while t:
            end += 1
            t = t // 10
        at = end
        while True:  # from the last digit back
            end -= 1
            b[end] = 48 + x % 10
            x = x // 10
            if not x:
                break
    b[at] = 10
    return at + 1
