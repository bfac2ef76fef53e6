"""calstore.Store on a filesystem that loses power after `budget` operations (open for writing, each
write, close, rename, remove). A cut write leaves half its bytes: open("w") truncates at once, so the
stub is harsher than littlefs (which keeps the old data until close)."""

import calstore
from scenarios.refusal import message

from hexapod import release


def cal_text(rows):
    """The calibration file's text for 18 rows (trim, direction, min_us, max_us), as `save` writes
    it (consolecal.encode), with consolecal let go after as on the board (the tests that count
    its comings and goings see the board's own)."""
    import consolecal

    text = consolecal.encode(rows)
    release("consolecal")
    return text


def decode(text):
    """consolecal.decode (the file's text read as split() reads it, or why not), consolecal let go after."""
    import consolecal

    try:
        return consolecal.decode(text)
    finally:
        release("consolecal")


def version(text):
    """consolecal.version, consolecal let go after."""
    import consolecal

    try:
        return consolecal.version(text)
    finally:
        release("consolecal")


def _save(store, rows):
    import consolecal

    try:
        return consolecal.save(store, rows)
    finally:
        release("consolecal")


class PowerCut(Exception):
    pass


class StubFS:
    def __init__(self, files=None, budget=-1, fat=False, readonly=False):
        self.files = dict(files or {})
        self.budget = budget
        self.fat = fat
        self.readonly = readonly
        self.ops = 0

    def _op(self):
        if self.budget >= 0 and self.ops >= self.budget:
            raise PowerCut()
        self.ops += 1

    def stat(self, name):
        if name not in self.files:
            raise OSError(2, "ENOENT")
        return (0,)

    def rename(self, a, b):
        if a not in self.files:
            raise OSError(2, "ENOENT")
        if self.fat and b in self.files:
            raise OSError(17, "EEXIST")
        self._op()
        self.files[b] = self.files.pop(a)

    def remove(self, name):
        if name not in self.files:
            raise OSError(2, "ENOENT")
        self._op()
        del self.files[name]

    def open(self, name, mode="r"):
        if mode in ("r", "rb"):
            if name not in self.files:
                raise OSError(2, "ENOENT")
            return Reader(self.files[name] if mode == "r" else self.files[name].encode())
        if self.readonly:
            raise OSError(30, "EROFS")
        self._op()
        self.files[name] = ""
        return Writer(self, name)


class Reader:
    def __init__(self, text):
        self.text = text

    def read(self):
        return self.text

    def close(self):
        pass


class Writer:
    def __init__(self, fs, name):
        self.fs = fs
        self.name = name

    def write(self, s):
        try:
            self.fs._op()
        except PowerCut:
            self.fs.files[self.name] += s[: len(s) // 2]
            raise
        self.fs.files[self.name] += s
        return len(s)

    def close(self):
        self.fs._op()


OLD = [(0, 1, 600, 2400)] * 18
NEW = [(k - 9, -1 if k % 2 else 1, 700 + k, 2300 - k) for k in range(18)]
NEWER = [(5, 1, 650, 2350)] * 18


def boot(fs):
    try:
        return calstore.Store(fs, fs.open).load()[0]
    except ValueError:
        return None


def save(fs, rows):
    try:
        _save(calstore.Store(fs, fs.open), rows)
        return True
    except PowerCut:
        return False


def cuts(fat, start, nested):
    seen = {}
    n = 0
    for b1 in range(40):
        fs = StubFS({calstore.FILE: cal_text(OLD)} if start else {}, b1, fat)
        done1 = save(fs, NEW)
        plans = range(40) if nested and not done1 else [-1]
        for b2 in plans:
            fs2 = StubFS(fs.files, b2, fat)
            done2 = save(fs2, NEWER) if b2 >= 0 else False
            got = boot(StubFS(fs2.files, -1, fat))
            name = "old" if got == OLD else "new" if got == NEW else "newer" if got == NEWER else repr(got)[:20]
            key = (done1, done2, name)
            seen[key] = seen.get(key, 0) + 1
            n += 1
        if done1:
            break
    return sorted(seen.items()), n


def format_checks():
    """Round trip and the refusals of a truncated, flipped, versioned and out-of-range file; see the test."""
    rows = [(k - 9, -1 if k % 2 else 1, 700 + k, 2300 - k) for k in range(18)]
    text = cal_text(rows)

    def why(t):
        return message(decode, t)

    body = text[: text.rfind("crc ")].replace("700 2300", "2400 2300")
    return [
        decode(text) == rows,
        [why(text[:n]) for n in (0, 10, len(text) // 2, len(text) - 1)],
        why(text.replace("2 femur -5", "2 femur -6")),
        why(text.replace("hexapod-cal 2", "hexapod-cal 3")),
        why(body + "crc %04x\n" % calstore.crc16(body.encode())),
        text.splitlines()[:2] + text.splitlines()[-1:],
    ]


def all_cuts():
    """cuts() of a first save on littlefs and FAT, with an old file and without."""
    return [cuts(fat, start, False) for fat in (False, True) for start in (True, False)]


class ShortWriter(Writer):
    """Drops the second half of each write yet reports every character written (a full flash that
    says nothing)."""

    def write(self, s):
        self.fs._op()
        self.fs.files[self.name] += s[: len(s) // 2]
        return len(s)


class ShortFS(StubFS):
    def open(self, name, mode="r"):
        if mode in ("r", "rb"):
            return StubFS.open(self, name, mode)
        self._op()
        self.files[name] = ""
        return ShortWriter(self, name)


def short_write():
    """A save onto a filesystem that writes short and reports success: (the error's errno, FILE kept,
    what the next boot loads)."""
    fs = ShortFS({calstore.FILE: cal_text(OLD)})
    try:
        _save(calstore.Store(fs, fs.open), NEW)
        err = None
    except OSError as e:
        err = e.args[0]
    return err, fs.files[calstore.FILE] == cal_text(OLD), boot(fs) == OLD


def versions():
    """Version 2, 1 and 3 of one file: [[consolecal.version of each and of ""], [decodes to its rows,
    or the error, of each]]."""
    rows = [(k - 9, -1 if k % 2 else 1, 700 + k, 2300 - k) for k in range(18)]
    v2 = cal_text(rows)
    body = v2[: v2.rfind("crc ")]
    v1 = signed(body.replace("hexapod-cal 2", "hexapod-cal 1"))
    v3 = signed(body.replace("hexapod-cal 2", "hexapod-cal 3"))

    def why(t):
        try:
            return decode(t) == rows
        except ValueError as e:
            return str(e)

    return [
        [version(v2), version(v1), version(v3), version("")],
        [why(v2), why(v1), why(v3)],
    ]


def signed(body):
    """body (a calibration file without its checksum line) with its checksum line."""
    return body + "crc %04x\n" % calstore.crc16(body.encode())


def parse_agrees():
    """calstore.parse (the boot's read of the form `save` writes) against consolecal.decode (every
    form split() reads) on a file with each character replaced, one at a time, by each of a few,
    with its checksum as it is and signed again: [variants, parse took, decode alone took, the ones
    where parse's rows or version differ from decode's]."""
    import consolecal

    rows = [(k - 9, -1 if k % 2 else 1, 700 + k, 2300 - k) for k in range(18)]
    text = cal_text(rows)
    body = text[: text.rfind("crc ")]
    seen = [0, 0, 0, []]  # variants, parse took, decode alone took, differ

    def check(v):
        got = calstore.parse(v.encode())
        try:
            want = (consolecal.decode(v), consolecal.version(v))
        except ValueError:
            want = None
        seen[0] += 1
        if got is not None:
            seen[1] += 1
            if got != want:
                seen[3].append(v)
        elif want is not None:
            seen[2] += 1

    for v in (text, signed(body.replace("hexapod-cal 2", "hexapod-cal 1")), text.replace("crc ", "crc  ")):
        check(v)
    for v in (text.upper(), text[:-1], text + "\n", body + "crc 0x12\n"):
        check(v)
    for i in range(len(body)):
        for c in " -0795+\t\nA":
            b = body[:i] + c + body[i + 1 :]
            check(b + text[len(body) :])
            check(signed(b))
    release("consolecal")
    seen[3] = seen[3][:3]
    return seen
