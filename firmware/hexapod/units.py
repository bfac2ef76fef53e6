"""Decimal text to and from the core's fixed-point integers, without floats.

The edges (CLI, serial console) speak mm and degrees; the core speaks 0.1 mm and
centidegrees. parse_fixed("12.34", 2) == 1234 and format_fixed(1234, 2) == "12.34".
"""


def parse_fixed(text, places):
    """Integer value of a decimal string scaled by 10**places, rounded half away from zero.

    Raises ValueError naming the text when it is not a plain decimal number.
    """
    s = text.strip()
    body = s[1:] if s[:1] in ("-", "+") else s
    whole, dot, frac = body.partition(".")
    if not (whole or frac) or not (whole.isdigit() or not whole) or not (frac.isdigit() or not frac):
        raise ValueError("%r is not a number" % text)
    if len(whole) > 9:
        raise ValueError("%r is too large" % text)
    scale = 10**places
    value = int(whole or "0") * scale
    digits = frac[:places]
    if digits:
        value += int(digits) * 10 ** (places - len(digits))
    if len(frac) > places and frac[places] >= "5":
        value += 1
    return -value if s[:1] == "-" else value


def format_fixed(value, places):
    """A scaled integer as a decimal string with `places` decimals: (-5, 2) -> '-0.05'."""
    scale = 10**places
    sign = "-" if value < 0 else ""
    value = -value if value < 0 else value
    if not places:
        return "%s%d" % (sign, value)
    frac = str(value % scale)
    return "%s%d.%s%s" % (sign, value // scale, "0" * (places - len(frac)), frac)
