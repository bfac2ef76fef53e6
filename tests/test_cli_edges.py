"""Rough edges a new user met first (issue 21): each refusal is exit 2 with a message naming what was
wrong and what is allowed, printed before anything starts."""

import os
import subprocess
import sys

import pytest

from hexapod_host.commands import cli

HEXAPOD = os.path.join(os.path.dirname(sys.executable), "hexapod")


def hexapod(*args):
    return subprocess.run([HEXAPOD, *args], capture_output=True, text=True, timeout=120)


def test_virtual_board_names_an_unknown_robot_before_printing_a_pty():
    # main: a pty path on stdout, then "the virtual board's VM exited with status 1" and no reason
    proc = hexapod("virtual-board", "--robot", "nope")
    assert (proc.returncode, proc.stdout) == (2, "")
    assert proc.stderr == "hexapod: error: no robot 'nope'; allowed: default\n"  # robots/ holds default.py


def test_pico_usage_lists_serial():
    proc = hexapod("pico")
    assert proc.returncode == 2
    assert proc.stderr.splitlines()[0] == "usage: hexapod pico [-h] run|bench|serial ..."


@pytest.mark.parametrize("command", [["send", "--port", "/dev/ttyNOPE7", "status"], ["jog", "--port", "/dev/ttyNOPE7"]])
def test_send_and_jog_refuse_a_missing_port_alike(capsys, command):
    # main: send exited 1, jog 2
    with pytest.raises(SystemExit) as stop:
        cli.main(command)
    assert stop.value.code == 2
    assert capsys.readouterr().err == "hexapod: error: no such port '/dev/ttyNOPE7' (hexapod ports lists them)\n"
