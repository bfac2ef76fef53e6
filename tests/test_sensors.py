"""The sensor contract (firmware/hexapod/sensors.py): the sonar order, names and status codes the
drivers, the follower, the board checks and the console share; the mounts check against many bad
inputs (messages written out by hand, identical on both runtimes); the sonar ring as a frame
sensor; and a new kind of frame sensor plugged into the Runner beside the sonars, asked once a
frame without a change to the loop, allocating nothing."""

import pytest

from tests.console_rig import clean_stubs  # noqa: F401 (autouse fixture)

SCENARIO = "scenarios.sensors:"

GOOD = ((1300, 0, 0), (1000, 2100, 9000), (-1000, 2100, 9000), (1000, -2100, -9000), (-1000, -2100, -9000))


def with_mount(k, m):
    return GOOD[:k] + (m,) + GOOD[k + 1 :]


ORDER = "front, left_front, left_rear, right_front, right_rear"
# (mounts, the whole message; None: accepted)
CASES = [
    (GOOD, None),
    (list(GOOD), None),
    (tuple(list(m) for m in GOOD), None),
    (with_mount(0, (1300, 0, 1000)), None),  # +-10 degrees of its heading: the edges are inside
    (with_mount(1, (1000, 2100, 8000)), None),
    (with_mount(4, (-1000, -2100, -10000)), None),
    (with_mount(2, (500, 2100, 9000)), None),  # left pair exactly 50 mm apart
    (None, "sensor mounts: need 5 (x, y, heading) in the order " + ORDER),
    ("front", "sensor mounts: need 5 (x, y, heading) in the order " + ORDER),
    ({0: (1300, 0, 0)}, "sensor mounts: need 5 (x, y, heading) in the order " + ORDER),
    (GOOD[:4], "sensor mounts: need 5 (x, y, heading) in the order " + ORDER),
    (GOOD + ((0, 0, 0),), "sensor mounts: need 5 (x, y, heading) in the order " + ORDER),
    ((), "sensor mounts: need 5 (x, y, heading) in the order " + ORDER),
    (with_mount(0, None), "sensor mounts: front: None, allowed (x, y, heading) integers"),
    (with_mount(0, (1300, 0)), "sensor mounts: front: (1300, 0), allowed (x, y, heading) integers"),
    (
        with_mount(1, (1000, 2100, 9000, 0)),
        "sensor mounts: left_front: (1000, 2100, 9000, 0), allowed (x, y, heading) integers",
    ),
    (
        with_mount(2, (-1000.0, 2100, 9000)),
        "sensor mounts: left_rear: (-1000.0, 2100, 9000), allowed (x, y, heading) integers",
    ),
    (
        with_mount(3, (1000, True, -9000)),
        "sensor mounts: right_front: (1000, True, -9000), allowed (x, y, heading) integers",
    ),
    (
        with_mount(4, (-1000, -2100, "-9000")),
        "sensor mounts: right_rear: (-1000, -2100, '-9000'), allowed (x, y, heading) integers",
    ),
    (with_mount(0, (1300, 0, 1001)), "sensor mounts: front heading 1001 cdeg, allowed -1000..1000"),
    (with_mount(0, (1300, 0, -1001)), "sensor mounts: front heading -1001 cdeg, allowed -1000..1000"),
    (with_mount(0, (1300, 0, 18000)), "sensor mounts: front heading 18000 cdeg, allowed -1000..1000"),
    (with_mount(1, (1000, 2100, 7999)), "sensor mounts: left_front heading 7999 cdeg, allowed 8000..10000"),
    (with_mount(2, (-1000, 2100, 10001)), "sensor mounts: left_rear heading 10001 cdeg, allowed 8000..10000"),
    (with_mount(3, (1000, -2100, 9000)), "sensor mounts: right_front heading 9000 cdeg, allowed -10000..-8000"),
    (with_mount(4, (-1000, -2100, 0)), "sensor mounts: right_rear heading 0 cdeg, allowed -10000..-8000"),
    (with_mount(1, (1000, 0, 9000)), "sensor mounts: left_front y 0 must be > 0 (left)"),
    (with_mount(2, (-1000, -2100, 9000)), "sensor mounts: left_rear y -2100 must be > 0 (left)"),
    (with_mount(3, (1000, 2100, -9000)), "sensor mounts: right_front y 2100 must be < 0 (right)"),
    (with_mount(4, (-1000, 0, -9000)), "sensor mounts: right_rear y 0 must be < 0 (right)"),
    (
        with_mount(2, (501, 2100, 9000)),
        "sensor mounts: left_front x 1000 must be at least 500 (50 mm) ahead of left_rear x 501",
    ),
    (
        with_mount(3, (-1000, -2100, -9000)),
        "sensor mounts: right_front x -1000 must be at least 500 (50 mm) ahead of right_rear x -1000",
    ),
    (
        with_mount(4, (2000, -2100, -9000)),
        "sensor mounts: right_front x 1000 must be at least 500 (50 mm) ahead of right_rear x 2000",
    ),
]


def test_the_contract_is_seed_000s_ring_and_the_datasheets_codes(rt):
    names, order, words, codes, none, min_range = rt.call(SCENARIO + "contract")
    assert names == tuple(ORDER.split(", ")) and order == (0, 1, 2, 3, 4)
    assert words[: len(codes) - 1] == ("ok", "out_of_range", "no_echo", "stuck", "too_close", "wait")  # docs/console.md
    assert codes == (0, 1, 2, 3, 4, 5, 6) and none == -1
    assert min_range == 200  # the HC-SR04's 2 cm, in 0.1 mm


def test_mounts_check_accepts_and_refuses_with_clear_messages(rt):
    got = rt.call(SCENARIO + "mounts_checked", [m for m, _ in CASES])
    assert got == [want for _, want in CASES]


def test_mounts_check_says_the_same_on_both_runtimes(both_runtimes):
    cp, mp = both_runtimes.call(SCENARIO + "mounts_checked", [m for m, _ in CASES])
    assert cp == mp


def test_the_robot_file_and_the_default_mounts_agree(rt):
    assert rt.call(SCENARIO + "robot_mounts_are_the_default") is True
    assert GOOD == ((1300, 0, 0), (1000, 2100, 9000), (-1000, 2100, 9000), (1000, -2100, -9000), (-1000, -2100, -9000))


def test_the_sonar_ring_is_a_frame_sensor(rt):
    # ok, wait, nothing, out of range, no echo, stuck, too close: four faults
    script = [(0, 0, 3000), (1, 5, 0), (-1, 0, 0), (2, 1, 0), (3, 2, 0), (4, 3, 0), (0, 4, 0)]
    out, dist, status = rt.call(SCENARIO + "ring_frames", script, 7)
    assert out == [(0, 0), (1, 0), (-1, 0), (2, 1), (3, 2), (4, 3), (0, 4)]
    assert dist == [-1, -1, -1, -1, -1] and status == [4, 5, 1, 2, 3]


def test_a_new_kind_of_sensor_plugs_in_beside_the_sonars(both_runtimes):
    cp, mp = both_runtimes.call(SCENARIO + "extra_sensor", 200)
    assert cp == mp
    n, frames_run, first, sonar_calls, faults, runner_faults, same, standing, order = cp
    assert n == frames_run == sonar_calls == 200 and standing and same and order
    t = first[0][1]  # the first frame's start (building took a moment of the virtual clock)
    assert first == [("sonar", t), ("battery", t), ("sonar", t + 20), ("battery", t + 20)]  # sonars first, each frame
    assert faults == runner_faults == 0


def test_a_frame_with_an_extra_sensor_allocates_nothing(mp):
    heap, n = mp.call(SCENARIO + "extra_sensor_heap", 150, 50)
    assert heap == 0 and n == 250


@pytest.mark.parametrize("name", ["front", "left_rear"])
def test_the_console_names_the_sonars_by_the_contract(rt, name):
    reply = rt.call(SCENARIO + "console_sonar", 30)
    words = reply.split()
    assert words[0] == "ok" and words[1::3] == ORDER.split(", ")
    k = ORDER.split(", ").index(name)
    assert words[2 + 3 * k] == "%.1f" % ((3000 + 1000 * k) / 10) and words[3 + 3 * k] == "ok"
