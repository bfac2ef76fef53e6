"""The calibration file (firmware/calstore.py): CRC, format, and saves cut by a power loss at
every step of the write, on a filesystem that renames over a file (littlefs) and on one that
cannot (FAT): the next boot always finds the old calibration or the new one."""

import ast
import binascii

from tests.console_rig import RIG, clean_stubs  # noqa: F401 (autouse fixture)

# The stub filesystem that loses power, and the cut saves: tests/scenarios/calstore.py.
STUB_FS = "import calstore\nfrom scenarios.calstore import StubFS\n"


def test_crc16_is_ccitt_false():
    import calstore

    assert calstore.crc16(b"123456789") == 0x29B1  # the catalogue's check value
    data = bytes(range(256)) * 3
    assert calstore.crc16(data) == binascii.crc_hqx(data, 0xFFFF)


def test_format_round_trips_and_refuses_damage(rt):
    out = rt.call("scenarios.calstore:format_checks")
    assert out[0] is True
    assert out[1] == ["truncated (no checksum line)"] * 4
    assert out[2] == "checksum mismatch (corrupt)"
    assert out[3] == "checksum mismatch (corrupt)"  # the CRC covers the version line too
    assert out[4] == "row 1: range 2400..2300, allowed 500 <= min < max <= 2500 us"
    assert out[5][:2] == ["hexapod-cal 2", "1 coxa -9 1 700 2300"] and out[5][2].startswith("crc ")


def test_a_save_cut_at_every_step_keeps_old_or_new(rt):
    out = rt.with_heapsize("4m").call("scenarios.calstore:all_cuts")
    for k, (seen, n) in enumerate(out):
        names = {name for (_, _, name), _ in seen}
        if k % 2 == 0:  # an old file: every cut boots old (before the rename) or new (after)
            assert names <= {"old", "new"} and "old" in names and "new" in names, seen
        else:  # no file yet: defaults (None) or the new one, never a broken one
            assert names <= {"None", "new"} and "new" in names, seen
        assert n >= 22  # 18 row writes + header + crc + open + close + rename at least: every one cut
        assert [c for (done, _, name), c in seen if done] == [1] and [name for (d, _, name), _ in seen if d] == ["new"]


def test_two_cut_saves_in_a_row_never_lose_the_last_good_file():
    # A first save cut between FAT's remove and rename leaves the good copy only in the temp
    # file; a second save must not overwrite it before making it the file again.
    from scenarios.calstore import cuts

    for fat in (False, True):
        seen, n = cuts(fat, True, True)
        names = {name for (_, _, name), _ in seen}
        assert names <= {"old", "new", "newer"}, seen
        assert n > 500


# The console tests below run tests/console_rig.py's RIG, source text, with the stub filesystem imported.
def test_read_only_filesystem_refuses_save_and_keeps_the_file(rt):
    src = (
        RIG
        + STUB_FS
        + """
fs = StubFS({calstore.FILE: calstore.encode([(0, 1, 600, 2400)] * 18)}, -1, True, True)
con.store = calstore.Store(fs, fs.open)
print(repr(say("trim 1 coxa 40")))
print(repr(say("save")))
print(repr(fs.files[calstore.FILE] == calstore.encode([(0, 1, 600, 2400)] * 18)))
fs.readonly = False
print(repr(say("save")))
print(repr(say("defaults")))
print(repr(say("cal 1 coxa")))
print(repr(say("load")))
print(repr(say("cal 1 coxa")))
_w = say("status").split()
print(repr(_w[_w.index("cal") : _w.index("cal") + 2]))
"""
    )
    out = [ast.literal_eval(x) for x in rt.run(src, heapsize="4m").splitlines()]
    assert out[0].endswith("trim 40 dir 1 min_us 600 max_us 2400")
    assert out[1].startswith("err save: the filesystem is read-only (") and out[1].endswith("the previous file is kept")
    assert out[2] is True
    assert out[3].startswith("ok saved hexapod_cal.txt crc ")
    assert out[4] == "ok defaults" and out[5].endswith("trim 0 dir 1 min_us 600 max_us 2400")
    assert out[6] == "ok loaded hexapod_cal.txt" and out[7].endswith("trim 40 dir 1 min_us 600 max_us 2400")
    assert out[8] == ["cal", "file"]


def test_boot_with_missing_or_broken_file_says_so_once_and_uses_the_robot_file(rt):
    src = (
        RIG
        + STUB_FS
        + """
good = calstore.encode([(25, 1, 600, 2400)] * 18)
for files in ({}, {calstore.FILE: good[:40]}, {calstore.FILE: good.replace("25", "26", 1)},
              {calstore.FILE: good}, {calstore.FILE: "x", calstore.TMP: good}):
    fs = StubFS(files)
    said = []
    c = console.start(r, None, fs, fs.open, out=said.append)
    print(repr((said, c.cal_source, c.trims[0], r.robot.servos[0].centre_us)))
    c.do("defaults")  # the next boot starts from the robot file again
"""
    )
    out = [ast.literal_eval(x) for x in rt.run(src, heapsize="4m").splitlines()]
    assert out[0] == (["cal: no hexapod_cal.txt; the robot file's calibration is in use"], "defaults", 0, 1500)
    assert out[1] == (
        ["cal: hexapod_cal.txt truncated (no checksum line); the robot file's calibration is in use"],
        "defaults",
        0,
        1500,
    )
    assert out[2][0] == ["cal: hexapod_cal.txt checksum mismatch (corrupt); the robot file's calibration is in use"]
    assert out[3] == ([], "file", 25, 1525)
    assert out[4] == ([], "file", 25, 1525)  # a complete temp file left by a cut save


def test_versions_read_and_refused(rt):
    """save writes version 2; a version 1 file (written before the tibia's reference moved to -90
    degrees) still decodes; any other version line, with a right checksum, is refused naming both."""
    src = """
import calstore
ROWS = [(k - 9, -1 if k % 2 else 1, 700 + k, 2300 - k) for k in range(18)]
v2 = calstore.encode(ROWS)
body = v2[: v2.rfind("crc ")]
def signed(b):
    return b + "crc %04x\\n" % calstore.crc16(b.encode())
v1 = signed(body.replace("hexapod-cal 2", "hexapod-cal 1"))
v3 = signed(body.replace("hexapod-cal 2", "hexapod-cal 3"))
def why(t):
    try:
        return calstore.decode(t) == ROWS
    except ValueError as e:
        return str(e)
print(repr([calstore.version(v2), calstore.version(v1), calstore.version(v3), calstore.version("")]))
print(repr([why(v2), why(v1), why(v3)]))
"""
    out = [ast.literal_eval(x) for x in rt.run(src).splitlines()]
    assert out[0] == [2, 1, 0, 0]
    assert out[1][:2] == [True, True]
    assert out[1][2] == "version line 'hexapod-cal 3', this firmware reads 'hexapod-cal 1' or 'hexapod-cal 2'"


def test_a_version_1_file_loads_with_its_pulses_unless_it_flips_a_tibia(both_runtimes):
    """Version 1 trims were added to the pulse at angle 0, version 2's to the pulse at the
    reference: the same shift, so a version 1 file means the same pulses (a trim of 20 us on leg 2's
    tibia: 2420 us at 0 degrees, 1520 at -90, 10 us per degree). A version 1 file that flips a
    tibia's direction mirrored it about 0 degrees, which version 2 cannot say: refused, naming the
    servo, and the robot file's calibration stays in force."""
    src = (
        RIG
        + STUB_FS
        + """
import calstore
def v1(rows):
    body = calstore.encode(rows)
    body = body[: body.rfind("crc ")].replace("hexapod-cal 2", "hexapod-cal 1")
    return body + "crc %04x\\n" % calstore.crc16(body.encode())
base = [(0, s.direction, s.min_us, s.max_us) for s in r.robot.servos]
trimmed = list(base)
trimmed[5] = (20, 1, 600, 2400)
flipped = list(base)
flipped[14] = (0, 1, 600, 2400)  # leg 5 tibia: direction -1 in robots/default_cal.py
for rows in (trimmed, flipped):
    fs = StubFS({calstore.FILE: v1(rows)})
    said = []
    c = console.start(r, None, fs, fs.open, out=said.append)
    print(repr((said, c.cal_source, [r.robot.servos[5].raw(a) for a in (0, -9000)], c.do("cal 2 tibia"))))
    print(repr(c.do("load")))
    c.do("defaults")
fs = StubFS({calstore.FILE: v1(trimmed)})
c = console.start(r, None, fs, fs.open, out=said.append)
print(repr((c.do("save"), fs.files[calstore.FILE].split("\\n")[:7:6])))
"""
    )
    cp, mp = both_runtimes(src, heapsize="4m")
    assert cp == mp
    out = [ast.literal_eval(x) for x in cp.splitlines()]
    assert out[0] == (
        [],
        "file",
        [2420, 1520],
        "ok leg 2 joint tibia centre_us 1500 ref_deg -90.00 trim 20 dir 1 min_us 600 max_us 2400",
    )
    assert out[1] == "ok loaded hexapod_cal.txt"
    why = (
        "hexapod_cal.txt is version 1 and flips leg 5 tibia, which it mirrored about 0 deg; now its reference "
        "is -90.00 deg: 'defaults', set it again and 'save'"
    )
    assert out[2] == (["cal: load: " + why], "defaults", [2400, 1500], out[2][3])
    assert out[2][3].endswith("trim 0 dir 1 min_us 600 max_us 2400")
    assert out[3] == "err load: " + why
    assert out[4][0].startswith("ok saved hexapod_cal.txt crc ") and out[4][1] == [
        "hexapod-cal 2",
        "2 tibia 20 1 600 2400",
    ]


def test_a_short_write_that_reports_success_is_caught_by_the_read_back(rt):
    # Every write() answers "all written" but half reaches the file: the temp file reads back
    # different, save raises OSError 28 (ENOSPC, "filesystem full?") before the rename, and the
    # old file stays the one the next boot loads.
    assert rt.call("scenarios.calstore:short_write") == (28, True, True)


def test_the_jog_and_calibration_commands_module_stays_for_a_jog_session(rt):
    # consolecal is the console's jog and calibration commands: imported at a session's first
    # command and kept while it goes on (an import per command overran the Pico's frame), let go
    # (hexapod.release) 30 s (CAL_KEEP_MS) after the last one or once the robot walks; the boot's
    # file load lets it go at once. On CPython release does nothing (the host's tests share one
    # process). CircuitPython's code.py keeps it (keep_cal).
    src = (
        RIG
        + STUB_FS
        + """
import sys
fs = StubFS({calstore.FILE: calstore.encode([(0, 1, 600, 2400)] * 18)})
said = []
c = console.start(r, None, fs, fs.open, out=said.append)
r.console = c
seen = [c.cal_source, "consolecal" in sys.modules]


def frames(n):
    for _ in range(n):
        clock.advance_us(20000)
        r.step()
        c.poll()
    return "consolecal" in sys.modules


for line in ("trim 1 coxa 5", "trim 1 coxa 999", "foot 9 0 0 0", "get 1"):
    seen += [c.do(line)[:3], "consolecal" in sys.modules]
seen.append(frames(1499))  # 29.98 s after the last jog command: kept
seen.append(frames(1))  # 30 s: let go
seen += [c.do("stand")[:3], frames(150), c.do("cal 1 coxa")[:3], frames(1)]  # standing: kept again
seen += [c.do("walk 100 0 0")[:3], frames(1), r.robot.mode]  # walking: let go
c.keep_cal = True
seen += [c.do("cal 1 coxa")[:3], frames(1600)]
c.keep_cal = False
print(repr((sys.implementation.name, seen)))
"""
    )
    name, seen = ast.literal_eval(rt.run(src, heapsize="4m").splitlines()[-1])
    kept = name == "cpython"
    assert seen == (
        ["file", kept, "ok ", True, "err", True, "err", True, "ok ", True, True, kept]
        + ["ok ", kept, "ok ", True, "ok ", kept, 4, "ok ", True]
    )
