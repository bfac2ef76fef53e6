"""The board file and the robot's calibration file as the loop takes them (the servo table, the
sonar pins, the battery monitor's arguments, the servo maps, the sonar mounts), and whether they
are the files `hexapod flash` checked.

flash checks the board file, the robot file and its calibration file on the host before it stages
them (hexapod_host.serial.flash.stage: what the board would refuse at boot is refused there) and
writes MARKER beside them: one line "CRC32 PATH" per staged file, the CRC32 (binascii/zlib) of the
file's bytes in 8 hex digits. At boot main.py's build reads each imported module's own file (its
__file__: a hand-uploaded .py that shadows the .mpy is another path) and, only when every one is
listed with its CRC32, builds from them without the board's checks (hexapod.board, .robotfile,
.robotcal, .check are never imported): less time from power-up to the first frame on a Pico, and
the checks' code and names never reach its heap. Anything else (no marker, another path, one
changed byte) is checked on the board as before, with the same messages. No checks here:
hexapod.board and hexapod.robotcal hold them and give the helpers' names too. Boot-only:
startup.run releases it (hexapod.BOOT_ONLY). Units as everywhere: pulses in us, lengths 0.1 mm, angles cdeg.
"""

from hexapod.sensors import SENSOR_NAMES
from hexapod.servo import ServoMap

JOINTS = ("coxa", "femur", "tibia")
LEGS = 6


def servo_table(board, servo_maps):
    """18 (address, channel, ServoMap) in leg/joint order (index (leg - 1) * 3 + joint): the
    board's channel map joined with the robot's 18 servo maps (hexapod.robotcal.servo_maps)."""
    ch = board["channels"]
    return tuple((ch[k // 3][k % 3][0], ch[k // 3][k % 3][1], servo_maps[k]) for k in range(LEGS * 3))


def sonar_pins(board):
    """Five (trigger, echo) pins in hexapod.sensors order: front, left_front, left_rear, ..."""
    by_name = {}
    for s in board["sonars"]:
        by_name[s[0]] = (s[1], s[2])
    return tuple(by_name[n] for n in SENSOR_NAMES)


def battery_args(setting):
    """A board file's "battery" dict -> hexapod.battery.Monitor's arguments, defaults filled in:
    (cells, divider_permille, cell_warn_mv, cell_cutoff_mv, cell_resume_mv)."""
    from hexapod import battery

    return (
        setting.get("cells", battery.CELLS),
        setting["divider_permille"],
        setting.get("cell_warn_mv", battery.CELL_WARN_MV),
        setting.get("cell_cutoff_mv", battery.CELL_CUTOFF_MV),
        setting.get("cell_resume_mv", battery.CELL_RESUME_MV),
    )


def servo_maps(cal):
    """18 new ServoMaps in leg/joint order (index (leg - 1) * 3 + joint)."""
    maps = [None] * 18
    ref = cal["REFERENCE"]
    for s in cal["SERVOS"]:
        j = JOINTS.index(s[1])
        maps[(s[0] - 1) * 3 + j] = ServoMap(centre_us=s[2], direction=s[3], min_us=s[4], max_us=s[5], ref_cdeg=ref[j])
    return maps


def sensor_mounts(cal):
    """Five (x, y, heading) in hexapod.sensors order: 0.1 mm and cdeg, body frame."""
    by_name = {}
    for s in cal["SONARS"]:
        by_name[s[0]] = (s[1], s[2], s[3])
    return tuple(by_name[n] for n in SENSOR_NAMES)


MARKER = "hexapod.checked"


def line(path, data):
    """MARKER's line for a file at path (on the board) holding data (bytes)."""
    import binascii

    return "%08x %s\n" % (binascii.crc32(data) & 0xFFFFFFFF, path)


def as_flashed(modules, marker=MARKER):
    """True when every module's file is listed in marker with its CRC32: the files the host
    checked, unchanged. False when marker is missing or any module differs."""
    try:
        with open(marker) as f:
            listed = "\n" + f.read()  # each line whole: no path matches inside another
    except OSError:
        return False
    for m in modules:
        path = getattr(m, "__file__", None)
        if path is None:
            return False
        try:
            with open(path, "rb") as f:
                want = line(path, f.read())
        except OSError:
            return False
        if "\n" + want not in listed:
            return False
    return True


def load(board_name, robot_name, marker=MARKER):
    """(the board file's BOARD, the robot file's module, the robot's calibration: a dict of
    REFERENCE, SERVOS, SONARS as hexapod.robotcal.load gives it), unchecked, when
    boards/<board_name>, robots/<robot_name> and its _cal file are as flashed; else None (also
    when one does not import: the board's checks then say why, as without the marker)."""
    names = ("boards." + board_name, "robots." + robot_name, "robots.%s_cal" % robot_name)
    try:
        modules = [__import__(n, None, None, ("NAME",)) for n in names]
    except Exception:  # noqa: BLE001 (a missing, misnamed or broken file: the checks' words for it)
        return None
    if not as_flashed(modules, marker):
        return None
    cal = modules[2]
    return modules[0].BOARD, modules[1], {"REFERENCE": cal.REFERENCE, "SERVOS": cal.SERVOS, "SONARS": cal.SONARS}
