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


def check_row(where, t, d, lo, hi):
    """ValueError naming where and the bad value unless the row is a valid calibration."""
    if t < -TRIM_MAX or t > TRIM_MAX:
        raise ValueError("%s: trim %d is outside -%d..%d us" % (where, t, TRIM_MAX, TRIM_MAX))
    if d != 1 and d != -1:
        raise ValueError("%s: direction %d, allowed 1 or -1" % (where, d))
    if lo < 500 or hi > 2500 or lo >= hi:
        raise ValueError("%s: range %d..%d, allowed 500 <= min < max <= 2500 us" % (where, lo, hi))


def decode(text):
    """18 rows (trim, direction, min_us, max_us) from the file's text; ValueError says why not."""
    end = text.rfind("crc ")
    if end < 0 or not text.endswith("\n"):
        raise ValueError("truncated (no checksum line)")
    body = text[:end]
    want = text[end + 4 :].strip()
    if len(want) != 4 or "%04x" % crc16(body.encode()) != want:
        raise ValueError("checksum mismatch (corrupt)")
    lines = body.split("\n")
    if version(text) not in READS:
        raise ValueError(
            "version line %r, this firmware reads %s"
            % (lines[0][:20], " or ".join(repr((HEADER % v).strip()) for v in READS))
        )
    if len(lines) != 20 or lines[19] != "":
        raise ValueError("%d rows, need 18" % (len(lines) - 2))
    rows = []
    for k in range(18):
        f = lines[k + 1].split()
        where = "row %d" % (k + 1)
        if len(f) != 6 or f[0] != str(k // 3 + 1) or f[1] != JOINTS[k % 3]:
            raise ValueError("%s: expected leg %d %s" % (where, k // 3 + 1, JOINTS[k % 3]))
        try:
            row = (int(f[2]), int(f[3]), int(f[4]), int(f[5]))
        except ValueError:
            raise ValueError("%s: not whole numbers" % where) from None
        check_row(where, *row)
        rows.append(row)
    return rows


def version(text):
    """The version number of a calibration file's text (its first line), 0 when it has none."""
    head = text[: text.find("\n")] if "\n" in text else text
    for v in READS:
        if head == (HEADER % v).strip():
            return v
    return 0


class Store:
    """Reads and writes the calibration file through an `os` module and an `open` function."""

    def __init__(self, os, opener=open, path=FILE, tmp=TMP):
        self.os = os
        self.open = opener
        self.path = path
        self.tmp = tmp

    def read(self, name):
        f = self.open(name, "r")
        try:
            return f.read()
        finally:
            f.close()

    def exists(self, name):
        try:
            self.os.stat(name)
            return True
        except OSError:
            return False

    def load(self):
        """(rows, where, version) from FILE, else from a complete TMP; ValueError says why neither."""
        try:
            text = self.read(self.path)
            return decode(text), self.path, version(text)
        except OSError as e:
            why = "no %s" % self.path if _errno(e) == 2 else "%s unreadable (%s)" % (self.path, e)
        except ValueError as e:
            why = "%s %s" % (self.path, e)
        try:
            text = self.read(self.tmp)
            return decode(text), self.tmp, version(text)
        except (OSError, ValueError):
            raise ValueError(why) from None

    def check(self):
        """The CRC of FILE as it is on the flash now (a self-test; the calibration in force is not
        touched); ValueError says why the file cannot be used."""
        try:
            text = self.read(self.path)
        except OSError as e:
            raise ValueError("no %s" % self.path if _errno(e) == 2 else "%s unreadable (%s)" % (self.path, e)) from None
        try:
            decode(text)
        except ValueError as e:
            raise ValueError("%s %s" % (self.path, e)) from None
        return int(text[text.rfind("crc ") + 4 :].strip(), 16)


def _errno(e):
    return e.args[0] if e.args and isinstance(e.args[0], int) else 0
