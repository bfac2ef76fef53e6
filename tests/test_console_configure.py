"""The console stays within its frame while a gait is being checked (issue 22, point 3): `gait G`
runs the servo guard in the frames' slack (Robot.set_gait wait=False), its reply comes when the
guard is done, and a `status` sent meanwhile is answered in the very next frame.

The robot here has no guard table (robots/default_guard.py answers a gait at its own cycle
without solving): the worst case, every gait change solved live. Bound per frame, worked by
hand: two solves for the configure (tests/test_tick_configure.py) and none for the line.
"""

from tests.console_rig import clean_stubs  # noqa: F401 (autouse fixture)

SCENARIO = "scenarios.console_gait:"


def test_a_status_during_a_gait_change_is_answered_in_the_next_frame(both_runtimes):
    cp, mp = both_runtimes.call(SCENARIO + "status_during_gait_change")
    assert cp == mp
    rows = cp
    assert rows[0] == "ok mode moving" and rows[1].startswith("ok ")
    solves, replies, configuring = rows[2]
    assert solves <= 2 and replies == 0 and configuring  # taken, no reply yet: it is being checked
    solves, status, configuring, gait = rows[3]
    assert solves <= 2 and status == "ok frames " and configuring and gait == 0  # still the tripod
    worst, n, later = rows[4]
    assert worst <= 2  # every frame of the check
    assert 100 < n < 4000
    assert [line for line in later if "gait" in line] == ["ok gait ripple"]
    assert rows[5] == "ok gait ripple"


def test_a_tagged_gait_change_says_working_then_its_late_reply_carries_the_tag(both_runtimes):
    # The link (docs/console.md, "Request tags") pairs the reply checked over frames with its request.
    cp, mp = both_runtimes.call(SCENARIO + "tagged_gait_change")
    assert cp == mp
    assert cp == ["#5 working", "#5 ok gait ripple"]
