"""hexapod.units: decimal text <-> fixed point, and shown()."""

from hexapod.units import format_fixed, parse_fixed, shown


def parse_and_format(cases):
    """Per (text, places): "value formatted" or "error message"."""
    out = []
    for text, places in cases:
        try:
            v = parse_fixed(text, places)
            out.append("%d %s" % (v, format_fixed(v, places)))
        except ValueError as err:
            out.append("error %s" % err)
    return out


def parse_edges(cases, shown_texts):
    """Per (text, places, limit): the value parse_fixed gives with unit "mm" or "error message"; then
    shown() of each of shown_texts, space-separated."""
    out = []
    for text, places, limit in cases:
        try:
            out.append(str(parse_fixed(text, places, limit, "mm")))
        except ValueError as err:
            out.append("error %s" % err)
    out.append(" ".join(shown(t) for t in shown_texts))
    return out


def fast_equals_general(seed, count):
    """parse_fixed (its one-pass form) against units._parse (the general form) on `count` texts made
    from digits, signs, points, spaces and a few other characters (a small LCG: the same texts on
    both runtimes), at 0..3 places, with and without a limit; format_fixed against the older
    str/zero-padding form on a range of values. Returns (texts compared, [mismatches])."""
    from hexapod import units

    def outcome(f, text, places, limit):
        try:
            return "v %d" % f(text, places, limit, "mm")
        except ValueError as err:
            return "error %s" % err

    def old_format(value, places):
        scale = 10**places
        sign = "-" if value < 0 else ""
        value = -value if value < 0 else value
        if not places:
            return "%s%d" % (sign, value)
        frac = str(value % scale)
        return "%s%d.%s%s" % (sign, value // scale, "0" * (places - len(frac)), frac)

    chars = "0123456789012345.-+ .e\t\u0663x"
    x = seed
    bad = []
    for _ in range(count):
        x = (x * 1103515245 + 12345) & 0x3FFFFFFF
        n = x % 14
        text = ""
        for _ in range(n):
            x = (x * 1103515245 + 12345) & 0x3FFFFFFF
            text += chars[(x >> 8) % len(chars)]
        for places in (0, 1, 2, 3):
            for limit in (None, 3000):
                a = outcome(parse_fixed, text, places, limit)
                b = outcome(units._parse, text, places, limit)
                if a != b:
                    bad.append((text, places, limit, a, b))
    for v in range(-2100, 2101, 3):
        for places in (0, 1, 2, 3):
            if format_fixed(v, places) != old_format(v, places):
                bad.append((v, places, format_fixed(v, places), old_format(v, places)))
    return count, bad
