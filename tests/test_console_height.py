"""The console's `height MM` (issue 23: the page's height control speaks it): the body's standing
height, within the robot file's 60.0..100.0 mm. Hand-worked: the leg frame's origin is the coxa
joint, level with the body (docs/design.md), so a foot on the ground of a level body stands at
z = -height; the robot file's 80.0 mm is the height after power-up. Refusals: test_console_refusals."""

from tests.console_rig import clean_stubs  # noqa: F401 (autouse fixture)

S = "scenarios.console_height:"


def test_standing_the_feet_go_to_the_new_height(both_runtimes):
    cp, mp = both_runtimes.call(S + "standing")
    assert cp == mp
    assert cp[0] == ["ok height 70.0"]
    assert cp[1] == ["-70.0"] * 6
    assert cp[2] == "ok height 70.0"
    assert cp[3] == ["ok height 95.5"]
    assert cp[4] == ["-95.5"] * 6
    assert cp[5] == "ok height 95.5"


def test_sitting_the_next_stand_goes_there(both_runtimes):
    cp, mp = both_runtimes.call(S + "sitting")
    assert cp == mp
    replies, sat, stood = cp
    assert replies == ["ok height 90.0"]
    assert sat != ["-90.0"] * 6  # sitting, the feet stay where they are
    assert stood == ["-90.0"] * 6
