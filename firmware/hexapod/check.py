"""Checks for plain-data files (boards/, robots/): one ValueError naming the file, the place, what
is wrong and what is allowed. Pure, imports nothing; never runs in the frame. Boot-only: the board
and robot checks import it, main.main forgets it with them once the loop is built (hexapod.release).
"""


class Check:
    """Carries the file's kind and name ("board 'pico'", "robot 'default'") into every message.

    Names and short strings here (and in the other boot-only checks) reuse what the firmware has
    anyway where they can: each new one is a qstr, which stays in the board's heap after the
    module is released (hexapod.release), and a few dozen more cost a new qstr pool (8 KB)."""

    def __init__(self, label, name):
        self.name = label + " " + repr(name)  # what every message starts with

    def fail(self, where, msg):
        raise ValueError(self.name + ": " + where + ": " + msg)

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

    def one_of(self, where, v, required):
        if v not in required:
            self.fail(where, "%r, allowed %s" % (v, ", ".join(required)))
        return v

    def named(self, where, v, length, shape, required, label):
        """Rows (name, ...) of `length` items, one for each name in required: {name: row}. Fails on
        a row of another length, an unknown or repeated name ("<label> NAME: listed twice") or a
        missing one."""
        self.seq(where, v, -1, "of %s tuples" % label)
        by = {}
        for i in range(len(v)):
            at = "%s[%d]" % (where, i)
            s = self.seq(at, v[i], length, shape)
            self.one_of(at + " name", s[0], required)
            if s[0] in by:
                self.fail(label + " " + s[0], "listed twice")
            by[s[0]] = s
        for n in required:
            if n not in by:
                self.fail(where, "missing %s %s" % (label, n))
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
