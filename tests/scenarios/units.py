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
