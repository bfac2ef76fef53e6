"""Files as flashed (hexapod.wiring): a board file and the robot's two files that `hexapod
flash` checked on the host and listed with their CRC32 build, unchecked, exactly what the board's
checks build (every shipped board, CPython and the MicroPython VM); any change to a listed file,
a file not listed or no marker sends the board back to its checks."""

import pytest

from hexapod_host.serial import flash

BOARDS = flash.boards()


def test_the_shipped_boards_are_the_ones_compared():
    assert BOARDS == ["esp32_devkit", "feather_rp2040", "feather_rp2040_micropython", "pico"]


@pytest.mark.parametrize("board", BOARDS)
def test_unchecked_builds_what_the_checks_build(rt, board, tmp_path):
    checked, unchecked = rt.call("scenarios.wiring:both", str(tmp_path / "marker"), board)
    assert unchecked is not None, "the marker lists the board's and robot's three files: wiring.load must trust them"
    assert unchecked == checked
    board_items, robot, cal, table, pins, mounts, battery = checked
    assert dict(board_items)["name"] == board and battery is None  # no shipped board has a battery
    assert len(table) == 18 and len(pins) == 5 and len(mounts) == 5
    # robots/default.py's build and boards/pico.py's wiring, read by hand
    assert dict(robot[1:])["body_height"] == 800 and dict(robot[1:])["neutral_reach"] == 1300
    if board == "pico":
        assert pins[0] == [6, 7] and table[0][:2] == [0x40, 0] and table[17][:2] == [0x41, 8]


def test_unchecked_builds_the_same_battery_monitor(rt, tmp_path):
    setting = {"pin": 28, "divider_permille": 250, "cells": 3}
    checked, unchecked = rt.call("scenarios.wiring:both", str(tmp_path / "marker"), "pico", battery=setting)
    assert unchecked == checked
    # the per-cell defaults (docs/wiring.md "Battery": warn 3.5 V, cutoff 3.3 V, resume 3.6 V), 3 cells given
    assert checked[6] == [3, 250, 3500, 3300, 3600]


def test_the_marker_line_is_the_standard_crc32(rt):
    # The CRC catalogue's check value: CRC-32 (ISO-HDLC, zlib's and binascii's) of "123456789"
    # is 0xcbf43926; flash (CPython) writes and the board (MicroPython) compares this line.
    line = rt.value("from hexapod import wiring\nprint(repr(wiring.line('robots/x.mpy', b'123456789')))")
    assert line == "cbf43926 robots/x.mpy\n"


@pytest.mark.parametrize(
    "how",
    [
        {"changed": "boards.pico"},
        {"changed": "robots.default"},
        {"changed": "robots.default_cal"},
        {"left_out": "robots.default_cal"},
        {"write": False},  # no marker
    ],
)
def test_anything_but_the_flashed_files_is_checked(rt, how, tmp_path):
    marker = str(tmp_path / "marker")
    assert rt.call("scenarios.wiring:trusted", marker, "pico") is True
    if how.get("write") is False:
        marker = str(tmp_path / "none")
    assert rt.call("scenarios.wiring:trusted", marker, "pico", **how) is False
