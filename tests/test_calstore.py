"""The calibration file (firmware/calstore.py): CRC, format, and saves cut by a power loss at
every step of the write, on a filesystem that renames over a file (littlefs) and on one that
cannot (FAT): the next boot always finds the old calibration or the new one."""

import binascii

from tests.console_rig import clean_stubs  # noqa: F401 (autouse fixture)

# The console with its calibration file on the stub filesystem: tests/scenarios/console_cal.py.
CONSOLE = "scenarios.console_cal:"


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


def test_the_boots_parse_reads_what_decode_reads_or_leaves_it_to_decode(both_runtimes):
    # calstore.parse reads only the form `save` writes, in place (the boot's load then fits the
    # heap the loop leaves free); any other text goes to consolecal.decode, which says why it is
    # refused or reads it (a form split() takes: a tab, a '+'). On every variant parse took, its
    # rows and version are decode's, in both runtimes.
    cp, mp = both_runtimes.call("scenarios.calstore:parse_agrees")
    assert cp == mp
    n, took, fallback, differ = cp
    assert differ == [] and n > 7000
    assert took > 500 and fallback > 100, cp  # parse took most valid ones (804), decode read the others (146)


def test_a_save_cut_at_every_step_keeps_old_or_new(rt):
    out = rt.call("scenarios.calstore:all_cuts")
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


def test_read_only_filesystem_refuses_save_and_keeps_the_file(rt):
    out = rt.call(CONSOLE + "read_only")
    assert out[0].endswith("trim 40 dir 1 min_us 600 max_us 2400")
    assert out[1].startswith("err save: the filesystem is read-only (") and out[1].endswith("the previous file is kept")
    assert out[2] is True
    assert out[3].startswith("ok saved hexapod_cal.txt crc ")
    assert out[4] == "ok defaults" and out[5].endswith("trim 0 dir 1 min_us 600 max_us 2400")
    assert out[6] == "ok loaded hexapod_cal.txt" and out[7].endswith("trim 40 dir 1 min_us 600 max_us 2400")
    assert out[8] == ["cal", "file"]


def test_boot_with_missing_or_broken_file_says_so_once_and_uses_the_robot_file(rt):
    out = rt.call(CONSOLE + "boots")
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
    out = rt.call("scenarios.calstore:versions")
    assert out[0] == [2, 1, 0, 0]
    assert out[1][:2] == [True, True]
    assert out[1][2] == "version line 'hexapod-cal 3', this firmware reads 'hexapod-cal 1' or 'hexapod-cal 2'"


def test_a_version_1_file_loads_with_its_pulses_unless_it_flips_a_tibia(both_runtimes):
    """Version 1 trims were added to the pulse at angle 0, version 2's to the pulse at the
    reference: the same shift, so a version 1 file means the same pulses (a trim of 20 us on leg 2's
    tibia: 2420 us at 0 degrees, 1520 at -90, 10 us per degree). A version 1 file that flips a
    tibia's direction mirrored it about 0 degrees, which version 2 cannot say: refused, naming the
    servo, and the robot file's calibration stays in force."""
    cp, mp = both_runtimes.call(CONSOLE + "version_1_files")
    assert cp == mp
    out = cp
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
    # consoleparts.jog, .caledit and consolecal (console.CALS) are the console's jog and calibration
    # commands: imported at a session's first command (each as its commands need it) and kept
    # while it goes on (an import per command overran the Pico's frame), let go
    # (hexapod.release) 30 s (CAL_KEEP_MS) after the last one or once the robot walks; the boot's
    # file load lets it go at once. On CPython release does nothing (the host's tests share one
    # process). CircuitPython's code.py compiles it at boot and keeps it until the robot walks
    # (cal_until_walk: no timeout), and lets it go at `wall` before the compile of the command's
    # module (`wall off` too).
    name, seen = rt.call(CONSOLE + "cal_module_session")
    kept = name == "cpython"
    assert seen == (
        ["file", kept, "ok ", True, "err", True, "err", True, "ok ", True, True, kept]
        + ["ok ", kept, "ok ", True, "ok ", kept, 4, "ok ", True]
        + ["ok ", True, "ok ", kept, 4]
        + ["ok ", kept, 3, "ok ", "ok ", kept, "ok ", "ok ", kept, "ok "]
    )


def test_the_jog_sessions_parts_write_out_the_values_they_would_import():
    # consoleparts.caledit and .calset import little at their top (each import cost the module's own
    # ~0.4 ms on the emulated Pico, where its import must fit a frame's slack): their copies must be
    # the originals.
    import calstore
    import console
    from consoleparts import caledit, calset

    from hexapod import tick

    assert caledit.JOINTS == calstore.JOINTS == console.JOINTS
    assert calset.TRIM_MAX == calstore.TRIM_MAX and calset.JOG_SERVO == tick.JOG_SERVO
