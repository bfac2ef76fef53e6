"""Decimal text to and from the core's fixed-point integers, without floats.

The edges (CLI, serial console) speak mm and degrees; the core speaks 0.1 mm and
centidegrees. parse_fixed("12.34", 2) == 1234 and format_fixed(1234, 2) == "12.34".
Only ASCII is read and written, so CPython and MicroPython (whose str methods differ on
non-ASCII text) give the same value or the same message for any text.
"""

_DIGITS = "0123456789"
_SPACE = " \t\n\r\x0b\x0c"  # ASCII whitespace: the set both runtimes strip and split on
SHOWN_MAX = 20  # characters of a value quoted in a message before it is cut


def shown(text, limit=SHOWN_MAX):
    """text quoted for a message: cut to `limit` characters + '...', ASCII only (\\x, \\u escapes)."""
    cut = len(text) > limit
    parts = ["'"]
    for c in text[:limit] if cut else text:
        o = ord(c)
        if 32 <= o < 127 and c != "\\" and c != "'":
            parts.append(c)
        elif c == "\\" or c == "'":
            parts.append("\\" + c)
        elif o < 256:
            parts.append("\\x%02x" % o)
        elif o < 65536:
            parts.append("\\u%04x" % o)
        else:
            parts.append("\\U%08x" % o)
    parts.append("...'" if cut else "'")
    return "".join(parts)


def _all_digits(s):
    return all(c in _DIGITS for c in s)


class OutOfRange(ValueError):
    """A number past the limit parse_fixed was given (the message names the bound)."""


def _outside(text, places, limit, unit):
    """The OutOfRange error for a value past +-limit (scaled by 10**places), e.g. "'4000' is outside -3000..3000 mm"."""
    t = format_fixed(limit, places)
    if places:
        t = t.rstrip("0").rstrip(".")
    return OutOfRange("%s is outside the accepted -%s..%s%s" % (shown(text), t, t, " " + unit if unit else ""))


def parse_fixed(text, places, limit=None, unit=""):
    """Integer value of a decimal string scaled by 10**places, rounded half away from zero.

    Accepts an optional sign, ASCII digits and one point ('-12.5', '.5', '5.'), nothing else.
    Raises ValueError naming the text (cut to SHOWN_MAX characters) when it is not such a
    number, or, given a limit (scaled like the result), when the rounded value is past +-limit
    (the message then names the bound, in `unit`).
    """
    # One pass over the characters for what a console line holds (a sign, at most 9 whole digits,
    # a point, digits, within the limit): no slice, partition or generator (a console `walk`
    # line's three numbers took ~1.5 ms on the emulated Pico). Anything else, every error
    # included, goes to the general form (_parse), which gives the same value for what this
    # one accepts (tests/test_units_servo.py compares both on many texts).
    s = text.strip(_SPACE)
    n = len(s)
    k = 1 if n and (s[0] == "-" or s[0] == "+") else 0
    j = k
    v = 0
    while j < n:
        c = ord(s[j]) - 48
        if c < 0 or c > 9:
            break
        v = v * 10 + c
        j += 1
    w = j - k  # whole digits
    f = 0  # fraction digits
    up = 0
    if j < n and s[j] == ".":
        j += 1
        while j < n:
            c = ord(s[j]) - 48
            if c < 0 or c > 9:
                break
            if f < places:
                v = v * 10 + c
            elif f == places and c >= 5:
                up = 1  # rounded half away from zero
            f += 1
            j += 1
    if j != n or w > 9 or not (w or f):
        return _parse(text, places, limit, unit)
    if f < places:
        v *= 10 ** (places - f)
    v += up
    if limit is not None and v > limit:
        return _parse(text, places, limit, unit)
    return -v if k and s[0] == "-" else v


def _parse(text, places, limit, unit):
    """parse_fixed's general form: the same value, and the error that says why not."""
    s = text.strip(_SPACE)
    body = s[1:] if s[:1] in ("-", "+") else s
    whole, dot, frac = body.partition(".")
    if not (whole or frac) or not _all_digits(whole) or not _all_digits(frac):
        for c in s:
            if ord(c) > 126:
                raise ValueError("%s is not a number: only ASCII digits 0-9, '-' and '.' are accepted" % shown(text))
        mant, e, exp = body.replace("E", "e").partition("e")
        m_whole, _, m_frac = mant.partition(".")
        if e and (m_whole or m_frac) and _all_digits(m_whole) and _all_digits(m_frac):
            digits = exp[1:] if exp[:1] in ("-", "+") else exp
            if digits and _all_digits(digits):
                raise ValueError("%s is not a number: exponents are not accepted, write it out in full" % shown(text))
        raise ValueError("%s is not a number" % shown(text))
    whole = whole.lstrip("0")
    if len(whole) > 9:
        if limit is not None:
            raise _outside(text, places, limit, unit)
        raise ValueError("%s is too large" % shown(text))
    scale = 10**places
    value = int(whole or "0") * scale
    digits = frac[:places]
    if digits:
        value += int(digits) * 10 ** (places - len(digits))
    if len(frac) > places and frac[places] >= "5":
        value += 1
    if limit is not None and value > limit:
        raise _outside(text, places, limit, unit)
    return -value if s[:1] == "-" else value


def format_fixed(value, places):
    """A scaled integer as a decimal string with `places` decimals: (-5, 2) -> '-0.05'."""
    # One format, no intermediate strings (each reply of a console `walk` line has three).
    if not places:
        return "%d" % value
    scale = 10**places
    if value < 0:
        value = -value
        return "-%d.%0*d" % (value // scale, places, value % scale)
    return "%d.%0*d" % (value // scale, places, value % scale)
