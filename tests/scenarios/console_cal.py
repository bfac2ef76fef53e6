"""The console's calibration file on the stub filesystem (tests/test_calstore.py): save on a
read-only filesystem, boots with a missing, broken or left-over file, version 1 files, and the
jog and calibration module kept through a jog session. On the stub board (scenarios.console_rig)."""

import _stub_clock as clock
import calstore
import console
from scenarios.calstore import StubFS, cal_text, signed
from scenarios.console_rig import Board


def read_only():
    """`trim 1 coxa 40`, `save` on a read-only filesystem, then writable: save, defaults, load.
    Returns [trim's reply, save's, the file unchanged, save's, defaults', cal's, load's, cal's,
    status's two words from `cal`]."""
    b = Board()
    rows = cal_text([(0, 1, 600, 2400)] * 18)
    fs = StubFS({calstore.FILE: rows}, -1, True, True)
    b.con.store = calstore.Store(fs, fs.open)
    out = [b.say("trim 1 coxa 40"), b.say("save"), fs.files[calstore.FILE] == rows]
    fs.readonly = False
    out += b.says(["save", "defaults", "cal 1 coxa", "load", "cal 1 coxa"])
    w = b.say("status").split()
    out.append(w[w.index("cal") : w.index("cal") + 2])
    return out


def boots():
    """A console started on: no file, a truncated one, a corrupt one, a good one (trim 25), a
    broken file beside a complete temp file. Each: [what it said, cal_source, leg 1 coxa's trim,
    its centre_us]."""
    b = Board()
    r = b.r
    good = cal_text([(25, 1, 600, 2400)] * 18)
    out = []
    for files in (
        {},
        {calstore.FILE: good[:40]},
        {calstore.FILE: good.replace("25", "26", 1)},
        {calstore.FILE: good},
        {calstore.FILE: "x", calstore.TMP: good},
    ):
        fs = StubFS(files)
        said = []
        c = console.start(r, None, fs, fs.open, out=said.append)
        out.append((said, c.cal_source, c.trims[0], r.robot.servos[0].centre_us))
        c.do("defaults")  # the next boot starts from the robot file again
    return out


def version_1(rows):
    """rows as a version 1 file (written before the tibia's reference moved to -90 degrees)."""
    body = cal_text(rows)
    return signed(body[: body.rfind("crc ")].replace("hexapod-cal 2", "hexapod-cal 1"))


def version_1_files():
    """Boots on a version 1 file trimming leg 2's tibia by 20 us, and on one flipping leg 5's tibia;
    each: [what it said, cal_source, leg 2 tibia's pulses at 0 and -90 deg, `cal 2 tibia`], then
    `load`'s reply. Last, [save's reply, the saved file's lines 1 and 7] after a boot on the first."""
    b = Board()
    r = b.r
    base = [(0, s.direction, s.min_us, s.max_us) for s in r.robot.servos]
    trimmed = list(base)
    trimmed[5] = (20, 1, 600, 2400)
    flipped = list(base)
    flipped[14] = (0, 1, 600, 2400)  # leg 5 tibia: direction -1 in robots/default_cal.py
    out = []
    said = []
    for rows in (trimmed, flipped):
        fs = StubFS({calstore.FILE: version_1(rows)})
        said = []
        c = console.start(r, None, fs, fs.open, out=said.append)
        out.append((said, c.cal_source, [r.robot.servos[5].raw(a) for a in (0, -9000)], c.do("cal 2 tibia")))
        out.append(c.do("load"))
        c.do("defaults")
    fs = StubFS({calstore.FILE: version_1(trimmed)})
    c = console.start(r, None, fs, fs.open, out=said.append)
    out.append((c.do("save"), fs.files[calstore.FILE].split("\n")[:7:6]))
    return out


def cal_module_session():
    """The jog session's modules (console.CALS: any of them) in sys.modules through a jog session:
    after the boot's file load, after each of
    a few commands, 29.98 s and 30 s after the last one, standing and a command again, walking,
    with keep_cal, and with cal_until_walk 32 s after a command and then walking, then standing, a
    command, `wall off`, a command and `wall left 12`: [implementation name, [cal_source, loaded, (reply's
    first 3 characters, loaded)..., the robot's mode while walking, ...]]."""
    import sys

    b = Board()
    r = b.r
    fs = StubFS({calstore.FILE: cal_text([(0, 1, 600, 2400)] * 18)})
    said = []
    c = console.start(r, None, fs, fs.open, out=said.append)
    r.console = c
    seen = [c.cal_source, any(m in sys.modules for m in console.CALS)]

    def frames(n):
        for _ in range(n):
            clock.advance_us(20000)
            r.step()
            c.poll()
        return any(m in sys.modules for m in console.CALS)

    for line in ("trim 1 coxa 5", "trim 1 coxa 999", "foot 9 0 0 0", "get 1"):
        seen += [c.do(line)[:3], any(m in sys.modules for m in console.CALS)]
    seen.append(frames(1499))  # 29.98 s after the last jog command: kept
    seen.append(frames(1))  # 30 s: let go
    seen += [c.do("stand")[:3], frames(150), c.do("cal 1 coxa")[:3], frames(1)]  # standing: kept again
    seen += [c.do("walk 100 0 0")[:3], frames(1), r.robot.mode]  # walking: let go
    c.keep_cal = True
    seen += [c.do("cal 1 coxa")[:3], frames(1600)]
    c.keep_cal = False
    c.cal_until_walk = True  # CircuitPython's: no timeout, let go once walking
    seen += [c.do("cal 1 coxa")[:3], frames(1600), c.do("walk 100 0 0")[:3], frames(1), r.robot.mode]
    # and `wall` lets it go before its own module's compile (`wall off` too): standing again
    seen += [c.do("stop")[:3], frames(150), r.robot.mode, c.do("cal 1 coxa")[:3], c.do("wall off")[:3]]
    seen += [any(m in sys.modules for m in console.CALS), c.do("cal 1 coxa")[:3], c.do("wall left 12")[:3]]
    seen += [any(m in sys.modules for m in console.CALS), c.do("wall off")[:3]]
    c.cal_until_walk = False
    return [sys.implementation.name, seen]
