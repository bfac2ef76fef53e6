"""Checks for plain-data files (boards/, robots/): one ValueError naming the file, the place, what
is wrong and what is allowed; and is_whole, the integer test every value check in the core uses.
Pure, imports nothing; never runs in the frame.
"""


def is_whole(v):
    """True for an int that is not a bool."""
    return isinstance(v, int) and not isinstance(v, bool)


class Check:
    """Carries the file's kind and name ("board 'pico'", "robot 'default'") into every message."""

    def __init__(self, kind, name):
        self.kind = kind
        self.name = name

    def fail(self, where, msg):
        raise ValueError("%s %r: %s: %s" % (self.kind, self.name, where, msg))

    def dict_of(self, where, v, required, optional=()):
        if not isinstance(v, dict):
            self.fail(where, "expected a dict, got %s" % (type(v).__name__,))
        for k in v:
            if k not in required and k not in optional:
                self.fail(where, "unknown key %r (allowed: %s)" % (k, ", ".join(required + optional)))
        for k in required:
            if k not in v:
                self.fail(where, "missing key %r" % (k,))
        return v

    def seq(self, where, v, length=-1, shape=""):
        if not isinstance(v, (tuple, list)):
            self.fail(where, "expected a tuple %s, got %s" % (shape, type(v).__name__))
        if length >= 0 and len(v) != length:
            self.fail(where, "expected %d items %s, got %d" % (length, shape, len(v)))
        return v

    def int_in(self, where, v, lo, hi, unit=""):
        if not isinstance(v, int) or isinstance(v, bool) or v < lo or v > hi:
            self.fail(where, "%r, allowed %d..%d%s" % (v, lo, hi, unit))
        return v

    def one_of(self, where, v, allowed):
        if v not in allowed:
            self.fail(where, "%r, allowed %s" % (v, ", ".join(allowed)))
        return v

    def named(self, where, rows, width, shape, names, what):
        """Rows (name, ...) of `width` items, one for each of names: {name: row}. Fails on a row of
        another width, an unknown or repeated name ("<what> NAME: listed twice") or a missing one."""
        self.seq(where, rows, -1, "of %s tuples" % what)
        by = {}
        for i in range(len(rows)):
            at = "%s[%d]" % (where, i)
            s = self.seq(at, rows[i], width, shape)
            self.one_of(at + " name", s[0], names)
            if s[0] in by:
                self.fail("%s %s" % (what, s[0]), "listed twice")
            by[s[0]] = s
        for n in names:
            if n not in by:
                self.fail(where, "missing %s %s" % (what, n))
        return by


def is_identifier(s):
    """True for a non-empty ASCII identifier (a file name, a pin name)."""
    if not isinstance(s, str) or not s:
        return False
    for i in range(len(s)):
        c = s[i]
        if not (c == "_" or "a" <= c <= "z" or "A" <= c <= "Z" or (i and "0" <= c <= "9")):
            return False
    return True
