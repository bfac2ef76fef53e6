"""The gamepad's reports (drive_ui.PAD_JS -> Driver.gamepad) as console lines: the sticks and
triggers as a walk, the dead zone, the stop button, the deadman (renewed while off-centre; centred,
disconnected or silent: stop), bad reports refused with nothing changed. The page in Chromium:
tests/test_view_drive_browser.py."""

import re

import pytest
from test_view_virtual import Recorder

from hexapod_host.view.drive import PAD_STALE, Driver, NotOwner


def pad(lx=0.0, ly=0.0, rx=0.0, ry=0.0, lt=0.0, rt=0.0, stop=0.0):
    return {"axes": [lx, ly, rx, ry], "lt": lt, "rt": rt, "stop": stop}


def driving():
    src = Recorder()
    d = Driver(src)
    d.claim("t")
    return src, d


@pytest.mark.parametrize(
    "report, line",
    [
        (pad(ly=-1.0), "walk 80 0 0"),  # left stick up: forward at the rim, 80 mm/s
        (pad(ly=1.0), "walk -80 0 0"),
        (pad(lx=-1.0), "walk 0 80 0"),  # left: strafe left (vy > 0)
        (pad(rx=1.0), "walk 0 0 -20"),  # right stick right: turn right (wz < 0), 20 deg/s
        (pad(lt=1.0), "walk 0 0 20"),  # left trigger: turn left
        (pad(rt=0.5), "walk 0 0 -8.24"),  # (0.5 - 0.15) / 0.85 x 20 = 8.2353 deg/s, 0.01 deg/s
        (pad(ly=-0.575), "walk 40 0 0"),  # (0.575 - 0.15) / 0.85 = 0.5 of 80 mm/s
        (pad(ly=-1.0, rx=1.0, lt=1.0), "walk 80 0 0"),  # right stick right and left trigger cancel
    ],
)
def test_sticks_and_triggers_as_a_walk(report, line):
    src, d = driving()
    d.gamepad("t", report)
    assert src.lines == [line]


def test_the_dead_zone_is_centred_and_sends_nothing():
    src, d = driving()
    d.gamepad("t", pad(lx=0.15, ly=-0.14, rx=-0.15, lt=0.1))  # all within 0.15 of rest
    assert src.lines == [] and not d.held()


def test_renewed_while_off_centre_and_stopped_when_centred():
    src, d = driving()
    d.gamepad("t", pad(ly=-1.0))
    d.renew()
    d.gamepad("t", pad(ly=-1.0))  # the page's report every 0.25 s while held: the same walk, not resent
    d.renew()
    assert src.lines == ["walk 80 0 0"] * 3
    d.gamepad("t", pad())  # centred
    d.renew()
    assert src.lines == ["walk 80 0 0"] * 3 + ["stop"]


def test_a_disconnected_pad_stops():
    src, d = driving()
    d.gamepad("t", pad(ly=-1.0))
    d.gamepad("t", None)
    assert src.lines == ["walk 80 0 0", "stop"] and not d.held()


def test_a_pad_whose_reports_stop_is_let_go():
    src, d = driving()
    d.gamepad("t", pad(ly=-1.0))
    for _ in range(PAD_STALE):  # 12 renewals (3 s) with no report: still renewed
        d.renew()
    assert src.lines == ["walk 80 0 0"] * (1 + PAD_STALE)
    d.renew()  # the 13th: the page went quiet, stop
    assert src.lines[-1] == "stop" and not d.held()
    d.renew()
    assert src.lines[-1] == "stop" and len(src.lines) == PAD_STALE + 2


def test_the_stop_button_stops_once_and_the_pad_waits_for_centre():
    src, d = driving()
    d.gamepad("t", pad(ly=-1.0))
    d.gamepad("t", pad(ly=-1.0, stop=1.0))
    d.gamepad("t", pad(ly=-0.9, stop=1.0))  # held: no second stop
    d.gamepad("t", pad(ly=-1.0))  # let go of the button, the stick still up: still stopped
    d.renew()
    assert src.lines == ["walk 80 0 0", "stop"]
    d.gamepad("t", pad())  # centred: the pad may drive again
    d.gamepad("t", pad(ly=-1.0))
    assert src.lines == ["walk 80 0 0", "stop", "walk 80 0 0"]


def test_space_and_the_keys_add_up_with_the_pad():
    src, d = driving()
    d.gamepad("t", pad(ly=-1.0))
    d.key("t", "a", True)  # A strafes left at 80 mm/s on top of the pad's forward
    d.key("t", " ", True)  # space stops everything; the off-centre pad waits for centre
    d.gamepad("t", pad(ly=-1.0))
    assert src.lines == ["walk 80 0 0", "walk 80 80 0", "stop"]


def test_losing_the_window_lets_go_of_the_pad():
    src, d = driving()
    d.gamepad("t", pad(rx=-1.0))
    d.let_go("t")
    d.gamepad("t", pad(rx=-1.0))
    assert src.lines == ["walk 0 0 20", "stop"]


@pytest.mark.parametrize(
    "report, why",
    [
        ({"axes": [0, 0, 0, 0]}, "gamepad report {'axes': [0, 0, 0, 0]}: allowed None or {axes, lt, rt, stop}"),
        (pad(ly=-1.5), "gamepad axes [0.0, -1.5, 0.0, 0.0]: allowed 4 numbers -1..1"),
        ({**pad(), "axes": [0, 0]}, "gamepad axes [0, 0]: allowed 4 numbers -1..1"),
        (pad(lt=-0.2), "gamepad lt, rt, stop [-0.2, 0.0, 0.0]: allowed numbers 0..1"),
        (pad(stop=True), "gamepad lt, rt, stop [0.0, 0.0, True]: allowed numbers 0..1"),
        ("up", "gamepad report 'up': allowed None or {axes, lt, rt, stop}"),
    ],
)
def test_a_bad_report_is_refused_and_changes_nothing(report, why):
    src, d = driving()
    d.gamepad("t", pad(ly=-1.0))
    with pytest.raises(ValueError, match=re.escape(why)):
        d.gamepad("t", report)
    assert d.pad == (1.0, 0.0, 0.0) and src.lines == ["walk 80 0 0"]


def test_another_tabs_pad_is_refused():
    src, d = driving()
    with pytest.raises(NotOwner, match="another tab drives; this one is view-only"):
        d.gamepad("tab2", pad(ly=-1.0))
    assert src.lines == [] and d.pad is None
