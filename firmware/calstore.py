"""The servo calibration file on the board's flash: trim, direction and range per servo.

A text file: a version line, 18 rows "leg joint trim direction min_us max_us" (legs 1..6,
joints coxa femur tibia, us), then "crc XXXX", the CRC-16/CCITT-FALSE of every byte before
that line. Version 2: `trim` is added to the robot calibration's centre_us, the pulse at the
servo's reference angle (robots/<robot>_cal.py REFERENCE), and a direction other than the
robot file's mirrors the servo about that reference. Version 1 files (before the reference:
trim added to the pulse at angle 0, a flipped direction mirrored about 0) load too; they mean
the same pulses unless they flip the direction of a servo whose reference is not 0, which the
console refuses to load (consolecal.load_file; docs/console.md). Written atomically: the whole text
goes to TMP, is read back, then renamed over FILE (where the filesystem cannot rename over an
existing file, FILE is removed first; load() then takes the complete TMP). So a save cut at
any point leaves the old calibration or the new one, never a broken one.

Filesystem access is handed in (the `os` module and `open`) so tests can use a stub that
loses power mid-write. Nothing here runs in the 50 Hz frame. Writing (encode, save) lives with the
`save` command in consolecal: its code is on the heap only while a jog session lasts, not in the
walking loop's (tests/test_pico.py's resident floor).
"""

VERSION = 2  # what consolecal.save writes
READS = (1, 2)  # what load() reads
FILE = "hexapod_cal.txt"
TMP = "hexapod_cal.tmp"
JOINTS = ("coxa", "femur", "tibia")
TRIM_MAX = 300  # largest |trim|, us
HEADER = "hexapod-cal %d\n"


def crc16(data):
    """CRC-16/CCITT-FALSE (poly 0x1021, initial 0xFFFF) of bytes; small ints only. A byte a step
    without a table: the eight bit steps of x^16 + x^12 + x^5 + 1 folded into shifts of the byte's
    top bits (x) and its high nibble folded back in (the bit loop took ~60 ms of a Pico's boot)."""
    crc = 0xFFFF
    for b in data:
        x = (crc >> 8) ^ b
        x ^= x >> 4
        crc = ((crc << 8) ^ (x << 12) ^ (x << 5) ^ x) & 0xFFFF
    return crc


def parse(data):
    """(rows, version) from a calibration file's bytes in the form `save` writes (one space between
    fields, no sign but '-', a lower-case checksum, valid rows); None for any other bytes:
    consolecal.decode then reads them (the forms split() also takes) or says why not. Reads data
    in place: only the rows are allocated, so the boot's load fits the heap the loop leaves free
    (no collection before the first frame)."""
    n = len(data) - 9  # where "crc XXXX\n" starts
    if n < 14 or data[n + 8] != 10 or not data.startswith(b"crc ", n) or not data.startswith(b"hexapod-cal "):
        return None
    v = data[12] - 48
    if data[13] != 10 or v not in READS:
        return None
    want = 0
    for p in range(n + 4, n + 8):
        c = data[p]
        if 48 <= c <= 57:
            want = want * 16 + c - 48
        elif 97 <= c <= 102:
            want = want * 16 + c - 87
        else:
            return None
    if want != crc16(memoryview(data)[:n]):
        return None
    rows = []
    f = [0, 0, 0, 0]
    p = 14
    for k in range(18):
        name = _NAMES[k % 3]
        if data[p] != 49 + k // 3 or data[p + 1] != 32 or not data.startswith(name, p + 2):
            return None
        p += 2 + len(name)
        for i in range(4):
            s = 1
            if data[p] == 45:
                s = -1
                p += 1
            x = 0
            q = p
            while 48 <= data[p] <= 57 and p - q < 5:
                x = x * 10 + data[p] - 48
                p += 1
            if p == q or data[p] != (10 if i == 3 else 32):
                return None
            p += 1
            f[i] = s * x
        t, d, lo, hi = f
        if t < -TRIM_MAX or t > TRIM_MAX or (d != 1 and d != -1) or lo < 500 or hi > 2500 or lo >= hi:
            return None  # consolecal.check_row's refusals
        rows.append((t, d, lo, hi))
    return (rows, v) if p == n else None


_NAMES = (b"coxa ", b"femur ", b"tibia ")


def _full(data):
    """(rows, version) of a file parse() did not take, by consolecal.decode (the forms split() also
    takes), or its ValueError saying why not; consolecal let go again unless it was loaded."""
    import sys

    from hexapod import release

    kept = "consolecal" in sys.modules
    import consolecal

    try:
        text = data.decode()
        return consolecal.decode(text), consolecal.version(text)
    finally:
        consolecal = None
        if not kept:
            release("consolecal")


class Store:
    """Reads and writes the calibration file through an `os` module and an `open` function."""

    def __init__(self, os, opener=open, path=FILE, tmp=TMP):
        self.os = os
        self.open = opener
        self.path = path
        self.tmp = tmp

    def read(self, name, mode="r"):
        f = self.open(name, mode)
        try:
            return f.read()
        finally:
            f.close()

    def decode(self, name):
        """(rows, version) of file name; OSError if unreadable, ValueError says why it is refused."""
        data = self.read(name, "rb")
        return parse(data) or _full(data)

    def exists(self, name):
        try:
            self.os.stat(name)
            return True
        except OSError:
            return False

    def load(self):
        """(rows, where, version) from FILE, else from a complete TMP; ValueError says why neither."""
        try:
            rows, v = self.decode(self.path)
            return rows, self.path, v
        except OSError as e:
            why = "no %s" % self.path if _errno(e) == 2 else "%s unreadable (%s)" % (self.path, e)
        except ValueError as e:
            why = "%s %s" % (self.path, e)
        try:
            rows, v = self.decode(self.tmp)
            return rows, self.tmp, v
        except (OSError, ValueError):
            raise ValueError(why) from None

    def check(self):
        """The CRC of FILE as it is on the flash now (a self-test; the calibration in force is not
        touched); ValueError says why the file cannot be used."""
        try:
            data = self.read(self.path, "rb")
        except OSError as e:
            raise ValueError("no %s" % self.path if _errno(e) == 2 else "%s unreadable (%s)" % (self.path, e)) from None
        try:
            parse(data) or _full(data)
        except ValueError as e:
            raise ValueError("%s %s" % (self.path, e)) from None
        return int(data[data.rfind(b"crc ") + 4 :].strip(), 16)


def _errno(e):
    return e.args[0] if e.args and isinstance(e.args[0], int) else 0
