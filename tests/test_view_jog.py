"""The page's jog and calibrate panel without a browser (view/jog.py's Jogger): the exact console
lines each step sends through the page's tagged path (Driver -> BoardSource -> BoardLink, a fake
serial line as in tests/test_view_virtual.py) to the real board console on the pico board's loop
on the stub machine (tests/console_link.py, standing), and what the panel shows. Expected pulses
are the default robot's calibration rows worked by hand: centre_us + trim + direction x (angle -
ref_deg) x 10 us. The page in a real browser: tests/test_view_jog_browser.py."""

import re

import pytest

from hexapod_host.view.board import BoardSource
from hexapod_host.view.board_link import BoardLink
from hexapod_host.view.drive import Driver, NotOwner
from hexapod_host.view.jog import Jogger
from tests.console_link import ConsoleLink
from tests.console_rig import clean_stubs  # noqa: F401 (autouse fixture)
from tests.test_view_virtual import FakePort

ME, OTHER = "tab-1", "tab-2"


class ConsolePort(FakePort):
    """A serial line to the console rig: each tagged line is answered by the real console (its own
    tag on the reply); `stream on 25` is answered here (the rig's console would then write
    telemetry into its replies)."""

    def __init__(self, rig):
        super().__init__()
        self.rig = rig
        self.sent = []  # the commands, untagged, in order

    def write(self, data):
        tagged = data.decode().strip()
        tag, _, line = tagged.partition(" ")
        self.sent.append(line)
        self.put("%s ok stream 25" % tag if line == "stream on 25" else self.rig.request(tagged))


@pytest.fixture
def jogged():
    """(jogger, port, rig): the panel's logic for tab ME, which drives."""
    rig = ConsoleLink()
    port = ConsolePort(rig)
    source = BoardSource(BoardLink(port, "rig").start(), "pico")
    driver = Driver(source)
    assert driver.claim(ME)
    jogger = Jogger(driver, pause=lambda s: None)
    port.sent.clear()
    try:
        yield jogger, port, rig
    finally:
        source.close()


def cal_line(rig, leg, joint):
    return rig.request("cal %d %s" % (leg, joint))


def test_pick_then_reference_trim_nudge_and_pulse_send_these_lines(jogged):
    j, port, rig = jogged
    j.pick(ME, 2, "tibia")
    assert port.sent == ["get 2", "cal 2 tibia"]
    port.sent.clear()
    j.reference(ME)
    assert port.sent == ["joint 2 tibia -90.00", "cal 2 tibia", "get 2"]
    assert j.view.pulses[2] == 1500  # at its reference: centre_us, no trim yet
    port.sent.clear()
    j.trim(ME, +1, 10)
    assert port.sent == ["trim 2 tibia 10", "get 2", "cal 2 tibia"]
    assert j.view.pulses[2] == 1510 and j.view.cal["trim"] == 10
    assert "cal    tibia: centre 1500 at -90.00 deg trim +10 dir +1 range 600..2400 us" in j.lines()
    port.sent.clear()
    j.nudge(ME, +1, "2")
    assert port.sent == ["joint 2 tibia -88.00", "get 2", "cal 2 tibia"]
    assert j.view.pulses[2] == 1530  # 1500 + 10 + (+1) x 2 deg x 10 us
    port.sent.clear()
    j.nudge(ME, -1, "0.5")
    assert port.sent == ["joint 2 tibia -88.50", "get 2", "cal 2 tibia"]
    assert j.view.pulses[2] == 1525
    port.sent.clear()
    j.pulse(ME, -1, 5)
    assert port.sent == ["pulse 2 tibia 1520", "get 2", "cal 2 tibia"]
    assert j.view.pulses[2] == 1520
    # the other legs' pulses and every other servo's calibration untouched
    assert re.search(r"trim 0 dir 1 ", cal_line(rig, 3, "tibia"))
    assert re.search(r"trim 10 dir 1 ", cal_line(rig, 2, "tibia"))


def test_flip_and_save_on_a_mirrored_leg(jogged):
    j, port, rig = jogged
    j.pick(ME, 5, "femur")
    j.reference(ME)
    assert j.view.pulses[1] == 1500 and j.view.cal["dir"] == -1  # robots/default_cal.py: leg 5 femur -1
    port.sent.clear()
    j.nudge(ME, +1, "5")
    assert port.sent == ["joint 5 femur 5.00", "get 5", "cal 5 femur"]
    assert j.view.pulses[1] == 1450  # 1500 + (-1) x 5 deg x 10 us
    port.sent.clear()
    j.flip(ME)
    assert port.sent == ["dir 5 femur 1", "get 5", "cal 5 femur"]
    assert j.view.pulses[1] == 1550 and j.view.cal["dir"] == 1  # mirrored about its reference
    port.sent.clear()
    j.save(ME)
    assert port.sent == ["save", "get 5", "cal 5 femur"]
    assert j.view.message.startswith("save: ok saved hexapod_cal.txt crc ")
    rows = rig.saved_rows()
    assert rows[3 * 4 + 1] == (0, 1, 600, 2400)  # leg 5 femur: trim 0, direction now +1


def test_a_refused_trim_shows_the_err_sends_nothing_after_it_and_changes_nothing(jogged):
    j, port, rig = jogged
    assert rig.request("trim 2 tibia 300").startswith("ok leg 2 joint tibia")  # at the console's limit
    j.pick(ME, 2, "tibia")
    j.reference(ME)
    before = cal_line(rig, 2, "tibia")
    port.sent.clear()
    j.trim(ME, +1, 10)
    assert port.sent == ["trim 2 tibia 310"]  # no get, no cal after the err
    assert j.view.error and j.view.message.startswith("trim 2 tibia 310: ")
    assert j.view.cal["trim"] == 300
    assert cal_line(rig, 2, "tibia") == before
    assert any(line.startswith("ERROR trim 2 tibia 310: ") for line in j.lines())


def test_a_limp_joint_is_not_nudged_and_a_step_is_checked_before_it_goes(jogged):
    j, port, rig = jogged
    rig.limp(2, 2)
    j.pick(ME, 2, "tibia")
    port.sent.clear()
    j.nudge(ME, +1, "1")
    assert port.sent == [] and "limp" in j.view.message
    with pytest.raises(ValueError, match="allowed 0.5, 1, 2, 5"):
        j.nudge(ME, +1, "3")
    with pytest.raises(ValueError, match="leg 7: allowed 1-6"):
        j.pick(ME, 7, "tibia")
    with pytest.raises(ValueError, match="allowed coxa, femur, tibia"):
        j.pick(ME, 2, "knee")
    assert port.sent == []


def test_only_the_driving_tab_jogs(jogged):
    j, port, rig = jogged
    j.pick(ME, 2, "tibia")
    port.sent.clear()
    for step in (
        lambda: j.pick(OTHER, 3, "coxa"),
        lambda: j.trim(OTHER, +1, 10),
        lambda: j.nudge(OTHER, +1, "1"),
        lambda: j.save(OTHER),
        lambda: j.guided(OTHER, "G"),
    ):
        with pytest.raises(NotOwner, match="another tab drives"):
            step()
    assert port.sent == []
    assert (j.view.leg, j.view.joint) == (2, 2)  # the other tab's pick changed nothing either
    # the drive freed (its tab closed): the next tab to claim it jogs
    j.driver.release(ME)
    assert j.driver.claim(OTHER)
    port.sent.clear()
    j.trim(OTHER, -1, 5)
    assert port.sent[0] == "trim 2 tibia -5"


def test_the_guided_calibration_from_the_page(jogged):
    """The terminal's procedure (serial/guided.py) driven by the page's buttons: the keys of
    guided.ACTIONS; the lines are the console's, worked out from docs/calibration.md."""
    j, port, rig = jogged
    j.guided(ME, "G")
    assert port.sent[0] == "relax" and set(port.sent[1:-2]) == {"status"}
    assert port.sent[-2:] == ["cal 1 coxa", "pulse 1 coxa 1500"]  # fit: the reference pulse
    assert j.guide.phase == "fit"
    assert any("servo 1 of 18: leg 1 coxa  step: fit" in x for x in j.lines())
    with pytest.raises(ValueError, match="the guided calibration runs"):
        j.trim(ME, +1, 10)  # the jog buttons wait while the guide holds the servos
    port.sent.clear()
    j.guided(ME, "ENTER")  # the horn is on
    sweep = [2, 4, 6, 8, 10, 8, 6, 4, 2, 0, -2, -4, -6, -8, -10, -8, -6, -4, -2, 0]
    assert port.sent == ["joint 1 coxa %d.00" % d if d >= 0 else "joint 1 coxa -%d.00" % -d for d in sweep]
    port.sent.clear()
    j.guided(ME, "y")  # it went the right way first
    assert port.sent == ["joint 1 coxa 0.00"]
    port.sent.clear()
    j.guided(ME, "+")
    j.guided(ME, "+")
    j.guided(ME, "-")
    assert port.sent == ["trim 1 coxa 10", "trim 1 coxa 20", "trim 1 coxa 10"]
    port.sent.clear()
    j.guided(ME, "ENTER")  # servo done: the next one's fit
    assert port.sent == ["cal 1 femur", "pulse 1 femur 1500"]
    assert re.search(r"trim 10 dir 1 ", cal_line(rig, 1, "coxa"))
    port.sent.clear()
    j.guided(ME, "ESC")  # quit: nothing saved; back to jogging, the view read again
    assert j.guide is None
    assert "save" not in port.sent and port.sent == ["get 1", "cal 1 coxa"]
    assert "quit, nothing saved" in j.view.message
    with pytest.raises(ValueError, match="not running"):
        j.guided(ME, "y")
