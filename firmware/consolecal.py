"""The console's calibration file commands (`save`, `load`, `defaults`), the calibration file's
load at boot, and the file's text (decode, encode, save): imported by console.py when one of them
runs and let go after it (hexapod.release), so the walking loop has their code's heap
(docs/console.md). The jog commands are consoleparts/jog.py's, `cal`, `trim`, `dir` and `range`
consoleparts/caledit.py's (this module's import with them took 36 ms on the emulated Pico: a late
frame). None runs while walking. The console names the command in an err reply.
"""

import calstore
from calstore import JOINTS, TRIM_MAX

from hexapod.units import format_fixed


def check_row(row, t, d, lo, hi):
    """ValueError naming the row (1..18) and the bad value unless the row is a valid calibration."""
    if t < -TRIM_MAX or t > TRIM_MAX:
        raise ValueError("row %d: trim %d is outside -%d..%d us" % (row, t, TRIM_MAX, TRIM_MAX))
    if d != 1 and d != -1:
        raise ValueError("row %d: direction %d, allowed 1 or -1" % (row, d))
    if lo < 500 or hi > 2500 or lo >= hi:
        raise ValueError("row %d: range %d..%d, allowed 500 <= min < max <= 2500 us" % (row, lo, hi))


def decode(text):
    """18 rows (trim, direction, min_us, max_us) from the file's text; ValueError says why not.
    The boot reads the file with calstore.parse, which takes only the form `save` writes (without
    this code on the heap); calstore.Store comes here for any other text, to read it or say why not."""
    end = text.rfind("crc ")
    if end < 0 or not text.endswith("\n"):
        raise ValueError("truncated (no checksum line)")
    body = text[:end]
    want = text[end + 4 :].strip()
    if len(want) != 4 or "%04x" % calstore.crc16(body.encode()) != want:
        raise ValueError("checksum mismatch (corrupt)")
    lines = body.split("\n")
    if version(text) not in calstore.READS:
        raise ValueError(
            "version line %r, this firmware reads %s"
            % (lines[0][:20], " or ".join(repr((calstore.HEADER % v).strip()) for v in calstore.READS))
        )
    if len(lines) != 20 or lines[19] != "":
        raise ValueError("%d rows, need 18" % (len(lines) - 2))
    rows = []
    for k in range(18):
        f = lines[k + 1].split()
        if len(f) != 6 or f[0] != str(k // 3 + 1) or f[1] != JOINTS[k % 3]:
            raise ValueError("row %d: expected leg %d %s" % (k + 1, k // 3 + 1, JOINTS[k % 3]))
        try:
            row = (int(f[2]), int(f[3]), int(f[4]), int(f[5]))
        except ValueError:
            raise ValueError("row %d: not whole numbers" % (k + 1)) from None
        check_row(k + 1, *row)
        rows.append(row)
    return rows


def version(text):
    """The version number of a calibration file's text (its first line), 0 when it has none."""
    head = text[: text.find("\n")] if "\n" in text else text
    for v in calstore.READS:
        if head == (calstore.HEADER % v).strip():
            return v
    return 0


def command(con, word, args):
    """The reply to a calibration file command line's word and arguments on console con."""
    if word == "boot":  # console.start: the calibration file's (rows, where, version) it read
        return put_file(con, *args)
    con._args(args, 0, "no arguments")
    if word == "save":
        return _save(con)
    if word == "load":
        reply = load_file(con)
        if reply.startswith("ok defaults"):
            _defaults(con)
        return reply
    return _defaults(con)


def rows(con):
    """The calibration in force: 18 (trim, direction, min_us, max_us)."""
    return [(con.trims[k], s.direction, s.min_us, s.max_us) for k, s in enumerate(con.robot.servos)]


def apply(con, new):
    """Put 18 rows in force, all or none; returns 0 or the refusing reason code."""
    old = rows(con)
    robot = con.robot
    for k in range(18):
        t, d, lo, hi = new[k]
        code = robot.calibrate(k, con.base[k][0] + t, d, lo, hi)
        if code:
            for j in range(k):
                t, d, lo, hi = old[j]
                robot.calibrate(j, con.base[j][0] + t, d, lo, hi)
                con.trims[j] = t  # all or none: the trims too
            return code
        con.trims[k] = t
    return 0


def _save(con):
    store = con.cal_store()
    if store is None:
        raise ValueError("no calibration file on this board")
    try:
        crc = save(store, rows(con))
    except OSError as e:
        why = "the filesystem is read-only" if e.args and e.args[0] == 30 else "the filesystem refused"
        return "err save: %s (%s); the previous file is kept" % (why, e)
    con.cal_source = "file"
    return "ok saved %s crc %04x" % (store.path, crc)


def load_file(con):
    """Calibration from the store, else the robot file's defaults; returns the reply."""
    store = con.cal_store()
    if store is None:
        raise ValueError("no calibration file on this board")
    try:
        new, where, version = store.load()
    except ValueError as e:
        return "ok defaults (%s)" % (e,)
    return put_file(con, new, where, version)


def put_file(con, new, where, version):
    """The rows a calibration file held (calstore.Store.load) in force; returns the reply."""
    if version == 1:
        # Version 1 mirrored a flipped servo about angle 0, version 2 about its reference:
        # the same pulses everywhere else, different ones there.
        for k in range(18):
            s = con.robot.servos[k]
            if new[k][1] != con.base[k][1] and s.ref_cdeg:
                return (
                    "err load: %s is version 1 and flips leg %d %s, which it mirrored about 0 deg; now "
                    "its reference is %s deg: 'defaults', set it again and 'save'"
                    % (where, k // 3 + 1, JOINTS[k % 3], format_fixed(s.ref_cdeg, 2))
                )
    code = apply(con, new)
    if code:
        return "err load: %s kept the calibration in force: %s" % (where, con._refused(code)[4:])
    con.cal_source = "file"
    return "ok loaded " + where


def _defaults(con):
    code = apply(con, [(0, b[1], b[2], b[3]) for b in con.base])
    if code:
        return con._refused(code)
    con.cal_source = "defaults"
    return "ok defaults"


def encode(rows):
    """The file's text for 18 rows (trim, direction, min_us, max_us), leg/joint order."""
    parts = [calstore.HEADER % calstore.VERSION]
    for k in range(18):
        t, d, lo, hi = rows[k]
        parts.append("%d %s %d %d %d %d\n" % (k // 3 + 1, JOINTS[k % 3], t, d, lo, hi))
    body = "".join(parts)
    return body + "crc %04x\n" % calstore.crc16(body.encode())


def save(store, rows):
    """Write rows atomically to store (calstore.Store); OSError (the old file kept) when the filesystem refuses."""
    text = encode(rows)
    if not store.exists(store.path) and store.exists(store.tmp):
        # A save cut between remove and rename left the good copy in TMP: make it FILE first,
        # so writing TMP again never destroys the only good copy.
        try:
            decode(store.read(store.tmp))
            store.os.rename(store.tmp, store.path)
        except ValueError:
            pass
    f = store.open(store.tmp, "w")
    try:
        for line in text.split("\n")[:-1]:
            f.write(line + "\n")
    finally:
        f.close()
    if store.read(store.tmp) != text:
        raise OSError(28, "written file reads back different (filesystem full?)")
    try:
        store.os.rename(store.tmp, store.path)
    except OSError:
        if not store.exists(store.path):
            raise
        store.os.remove(store.path)  # FAT cannot rename over a file: TMP is complete by now
        store.os.rename(store.tmp, store.path)
    return calstore.crc16(text[: text.rfind("crc ")].encode())
