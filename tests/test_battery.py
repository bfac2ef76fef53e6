"""Battery awareness (issue 20, point 5): hexapod.battery's filter and states, the board file's
"battery" setting, the stub ADC, and the whole board through main.main on both runtimes.

Every expected frame below is worked out by hand from the thresholds and the filter, never
from the code under test:
- 2S defaults: warn 2 x 3500 = 7000 mV, cutoff 2 x 3300 = 6600 mV, resume 2 x 3600 = 7200 mV.
- Readings: one at build (t = 0), then every 10th frame: frame k runs at t = 20k ms, so the
  readings fall on frames 9, 19, 29, ... (t = 180 + 200 j ms).
- The filter: the last 6 readings. Down across a threshold when all 6 are below it, up across
  resume when all 6 are at or above it. A level that starts between two readings is seen from
  the next reading on, and acted on at the 6th: 1000 ms after that first reading.
"""

import pytest

from hexapod import battery
from hexapod import board as boards

OK, LOW, CUTOFF = 0, 1, 2
RELAXED, MOVING, STANDING, WALKING = 0, 2, 3, 4


# -- the stub ADC -------------------------------------------------------------------------------


def test_stub_adc_reads_as_the_rp2_port(rt):
    # 12-bit code = mV * 4096 / 3300 rounded, then code << 4 | code >> 8 (ports/rp2/machine_adc.c).
    src = """
import _stub_adc, _stub_clock
from machine import ADC, Pin
_stub_clock.reset(0)
_stub_adc.reset()
_stub_adc.volts(26, [(0, 0), (10, 1650), (20, 3300), (30, 5000), (40, 1)])
a = ADC(Pin(26))
out = []
for t in (0, 10, 20, 30, 40):
    _stub_clock.advance_to(t * 1000)
    out.append(a.read_u16())
_stub_adc.battery(27, 333, [(0, 8400)])
out.append(ADC(1).read_u16())   # channel 1 is GPIO 27: 8400 * 333 // 1000 = 2797 mV
for bad in ("Pin(5)", "5", "30"):
    try:
        ADC(eval(bad))
        out.append("accepted " + bad)
    except ValueError as e:
        out.append(str(e))
print(out)
"""
    # 1650 mV: 2048 -> 32768 | 8; 2797 mV: (2797 * 4096 + 1650) // 3300 = 3472 -> 55552 | 13
    assert rt.value(src) == [
        0,
        32776,
        65535,
        65535,
        16 | 0,  # 1 mV is code 1: 16 | 1 >> 8
        55565,
        "Pin doesn't have ADC capabilities",
        "invalid channel",
        "invalid channel",
    ]


# -- the core: conversion and filter ------------------------------------------------------------


def test_readings_convert_to_pack_millivolts(rt):
    # One 12-bit step is 3300 / 4096 / 0.333 = 2.42 mV of pack; the divider and rounding add < 3 mV more.
    raws = [rt.call("scenarios.battery:raw_for", mv) for mv in (6000, 6600, 7000, 7200, 8400)]
    got = rt.call("scenarios.battery:to_mv", raws)
    assert [abs(g - mv) <= 5 for g, mv in zip(got, (6000, 6600, 7000, 7200, 8400), strict=True)] == [True] * 5, got


@pytest.mark.parametrize("dip_ms", [200, 400, 600, 800, 900])
def test_a_dip_shorter_than_a_second_never_trips(rt, dip_ms):
    # A dip to 6000 mV (600 below the cutoff) at every phase against the readings: shorter than
    # 1000 ms it covers at most 5 of the 6 readings, so the window's maximum stays 7600: OK.
    assert rt.call("scenarios.battery:dip_states", dip_ms) == [OK]


@pytest.mark.parametrize("dip_ms", [1200, 1400, 2000])
def test_a_dip_of_1_2_s_or_longer_always_trips(rt, dip_ms):
    # 1200 ms or longer covers 6 readings at every phase: CUTOFF (and it stays: 7600 < resume 7200? no,
    # 7600 >= 7200, so it comes back to OK once 6 readings are above resume again).
    states = rt.call("scenarios.battery:dip_states", dip_ms)
    assert states == [OK, CUTOFF]


def test_the_1_4_s_dip_frame_by_frame(rt):
    # Readings every 200 ms from t = 0; 7600 mV, 6000 mV over [1000, 2400) ms: readings 5..11
    # (t = 1000 .. 2200) are low. Reading 10 (t = 2000) is the 6th low one: CUTOFF there. Readings
    # 12.. are 7600 again (>= resume 7200): the 6th of them, reading 17 (t = 3400), brings OK.
    samples = [6000 if 1000 <= t < 2400 else 7600 for t in range(0, 4000, 200)]
    states = rt.call("scenarios.battery:trace", samples)
    assert states == [OK] * 10 + [CUTOFF] * 7 + [OK] * 3
    # The 600 ms one: readings 5, 6, 7 low; never anything but OK.
    samples = [6000 if 1000 <= t < 1600 else 7600 for t in range(0, 4000, 200)]
    assert rt.call("scenarios.battery:trace", samples) == [OK] * 20


def test_low_then_cutoff_then_resume_with_hysteresis(rt):
    # 2S: warn 7000, cutoff 6600, resume 7200. 6 readings at 6900 -> LOW at the 6th; 6 at 6500 ->
    # CUTOFF at the 6th; 7100 (above warn, below resume) keeps CUTOFF; 7300 x 6 -> OK at the 6th.
    samples = [7500] * 3 + [6900] * 8 + [6500] * 8 + [7100] * 8 + [7300] * 8
    states = rt.call("scenarios.battery:trace", samples)
    low, cut = [LOW] * 3 + [LOW] * 5, [CUTOFF] * 3 + [CUTOFF] * 8 + [CUTOFF] * 5
    assert states == [OK] * 3 + [OK] * 5 + low + cut + [OK] * 3
    # Back above warn but below resume: LOW stays LOW (the notice is not repeated).
    samples = [6900] * 6 + [7100] * 10
    assert rt.call("scenarios.battery:trace", samples) == [LOW] * 16
    # The first reading fills the window: a flat pack is CUTOFF at once, a low one LOW.
    assert rt.call("scenarios.battery:trace", [6400]) == [CUTOFF]
    assert rt.call("scenarios.battery:trace", [6900]) == [LOW]


# -- the board file ----------------------------------------------------------------------------

BAD = [
    ("x", "board 'pico': battery: expected a dict, got str"),
    ({"divider_permille": 333}, "board 'pico': battery: missing key 'pin'"),
    ({"pin": 28}, "board 'pico': battery: missing key 'divider_permille'"),
    (
        {"pin": 28, "divider_permille": 333, "warn_mv": 7000},
        "board 'pico': battery: unknown key 'warn_mv' (allowed: pin, divider_permille, cells, cell_warn_mv,"
        " cell_cutoff_mv, cell_resume_mv)",
    ),
    ({"pin": 4, "divider_permille": 333}, "board 'pico': battery.pin: pin 4 is already used as i2c.sda"),
    ({"pin": 64, "divider_permille": 333}, "board 'pico': battery.pin: 64, allowed a GPIO number 0..63 or a pin name"),
    ({"pin": None, "divider_permille": 333}, "board 'pico': battery.pin: no pin given"),
    (
        {"pin": 28, "divider_permille": 333.3},
        "board 'pico': battery.divider_permille: 333.3, allowed 100..1000 (the ADC pin's voltage per pack volt)",
    ),
    (
        {"pin": 28, "divider_permille": 50},
        "board 'pico': battery.divider_permille: 50, allowed 100..1000 (the ADC pin's voltage per pack volt)",
    ),
    (
        {"pin": 28, "divider_permille": 500},
        "board 'pico': battery.divider_permille: 500 puts 4200 mV on the ADC pin for a full 2-cell pack"
        " (8400 mV), above the ADC's 3300 mV reference; allowed at most 392 (e.g. 1:3, 333, for 2 cells)",
    ),
    (
        {"pin": 28, "divider_permille": 333, "cells": 3},
        "board 'pico': battery.divider_permille: 333 puts 4195 mV on the ADC pin for a full 3-cell pack"
        " (12600 mV), above the ADC's 3300 mV reference; allowed at most 261 (e.g. 1:3, 333, for 2 cells)",
    ),
    (
        {"pin": 28, "divider_permille": 333, "cells": 0},
        "board 'pico': battery.cells: 0, allowed 1..6 (LiPo cells in series)",
    ),
    (
        {"pin": 28, "divider_permille": 333, "cells": True},
        "board 'pico': battery.cells: True, allowed 1..6 (LiPo cells in series)",
    ),
    (
        {"pin": 28, "divider_permille": 333, "cell_cutoff_mv": 3.3},
        "board 'pico': battery.cell_cutoff_mv: 3.3, allowed 2500..4200 mV a cell",
    ),
    (
        {"pin": 28, "divider_permille": 333, "cell_warn_mv": 4300},
        "board 'pico': battery.cell_warn_mv: 4300, allowed 2500..4200 mV a cell",
    ),
    (
        {"pin": 28, "divider_permille": 333, "cell_resume_mv": 2400},
        "board 'pico': battery.cell_resume_mv: 2400, allowed 2500..4200 mV a cell",
    ),
    (
        {"pin": 28, "divider_permille": 333, "cell_warn_mv": 3300},
        "board 'pico': battery.cell_warn_mv: 3300 must be above cell_cutoff_mv 3300 (warn before cutting)",
    ),
    (
        {"pin": 28, "divider_permille": 333, "cell_cutoff_mv": 3600},
        "board 'pico': battery.cell_warn_mv: 3500 must be above cell_cutoff_mv 3600 (warn before cutting)",
    ),
    (
        {"pin": 28, "divider_permille": 333, "cell_warn_mv": 3400, "cell_resume_mv": 3300},
        "board 'pico': battery.cell_resume_mv: 3300 must be above cell_cutoff_mv 3300 (a recharged pack,"
        " not the one that was cut)",
    ),
    (
        {"pin": 28, "divider_permille": 333, "cell_resume_mv": 3500},
        "board 'pico': battery.cell_resume_mv: 3500 must be above cell_warn_mv 3500 (a resumed pack must not"
        " warn at once)",
    ),
]


@pytest.mark.parametrize("setting, message", BAD)
def test_bad_battery_settings_are_refused(rt, setting, message):
    assert rt.call("scenarios.battery:bad_setting", setting) == message


def test_good_battery_settings_are_accepted(rt):
    for setting in (
        None,
        {"pin": 28, "divider_permille": 333},
        {"pin": 26, "divider_permille": 392},  # 8400 * 392 / 1000 = 3292 mV: just under 3300
        {"pin": 28, "divider_permille": 130, "cells": 6},
        {"pin": 28, "divider_permille": 700, "cells": 1, "cell_warn_mv": 3550, "cell_cutoff_mv": 3400},
        {"pin": 28, "divider_permille": 333, "cell_warn_mv": 3400, "cell_cutoff_mv": 3000, "cell_resume_mv": 3700},
    ):
        assert rt.call("scenarios.battery:bad_setting", setting) is None, setting


def test_circuitpython_boards_refuse_a_battery_setting():
    from hexapod import board as hb

    board = dict(hb.load("feather_rp2040"), battery={"pin": "A2", "divider_permille": 333})
    with pytest.raises(ValueError) as err:
        hb.validate(board)
    assert str(err.value) == (
        "board 'feather_rp2040': battery: a battery monitor runs on MicroPython boards only (code.py has no"
        " ADC driver); remove it"
    )


def test_a_refused_setting_changes_nothing():
    board = boards.load("pico")
    before = repr(board)
    with pytest.raises(ValueError):
        boards.validate(dict(board, battery={"pin": 28, "divider_permille": 999}))
    assert repr(boards.load("pico")) == before and board["battery"] is None  # as shipped


def test_monitor_defaults_are_a_2s_lipo():
    m = battery.Monitor()
    assert (m.cells, m.warn_mv, m.cutoff_mv, m.resume_mv) == (2, 7000, 6600, 7200)
    with pytest.raises(ValueError, match="cells: 7, allowed 1..6"):
        battery.Monitor(7)


# -- the speed cap in the core ------------------------------------------------------------------


def test_speed_cap_scales_the_walk_by_one_factor():
    from scenarios.rig import unguarded_geometry

    from hexapod import tick

    g = unguarded_geometry()
    r = tick.Robot(g, tick.default_servos(g), tick.FrameBuffer())
    r.stand_up()
    for _ in range(100):
        r.tick(0)
    assert r.mode == tick.STANDING
    r.cap_speed(600, 1500)
    got = []
    for cmd in ((1000, 0, 0), (1000, 1000, 0), (0, 0, 9000), (-3000, 0, 0), (500, 0, 1000)):
        assert r.walk(*cmd) == 0
        w = r.walker
        got.append((w.req_vx, w.req_vy, w.req_yaw))
    # 600 / 1000; 600 / isqrt(2e6) = 600 / 1414 -> 424 permille; 1500 / 9000 -> 166 permille;
    # 600 / 3000 -> 200 permille; (500, 1000) is under both caps: unchanged.
    assert got == [(600, 0, 0), (424, 424, 0), (0, 0, 1494), (-600, 0, 0), (500, 0, 1000)]
    r.cap_speed()  # lifted: the walk under way gets its asked speed back at once
    assert (r.walker.req_vx, r.walker.req_yaw) == (500, 1000)
    r.cap_speed(600, 1500)
    r.walk(2000, 0, 0)
    assert r.walker.req_vx == 600
    r.cap_speed(0, 0)
    assert r.walker.req_vx == 2000
    for bad in ((-1, 1500), (600, 0), (3001, 1500), (600, True), (600.0, 1500)):
        with pytest.raises(ValueError):
            r.cap_speed(*bad)
    assert (r.speed_cap, r.yaw_cap, r.walker.req_vx) == (0, 0, 2000)


# -- the whole board ----------------------------------------------------------------------------


def _mv(status):
    return int(status.split(" battery_mv ")[1].split()[0])


def test_the_battery_scenario(rt):
    assert_the_battery_scenario(*rt.call("scenarios.battery:scenario", 1050))


def assert_the_battery_scenario(log, said):
    """scenarios.battery's scenario (1050 frames) against the frames worked out by hand; the
    emulated Pico's run of it too (tests/test_pico_battery.py)."""
    events = [(f, what, v) for f, what, v in log if what in ("battery", "req_vx")]
    # Frame 0: 8000 mV, OK. 2000 ms: 7600 (sagging) with dips to 6000 over [2400, 3000) (readings
    # at 2580, 2780, 2980: 3 of 6) and [3600, 4500) (3780 .. 4380: 4 of 6): ignored, no event.
    # 5000 ms: 6900 < 7000: readings 5180 (frame 259) .. the 6th, 6180 ms = frame 309: LOW, and the
    # walk asked at 100 mm/s is capped to 60 at once. The 600 ms dip at [6600, 7200) while low
    # (readings 6780, 6980, 7180: 3 of 6) does not cut off. 8000 ms: 6400 < 6600: readings 8180
    # (frame 409) .. 9180 ms = frame 459: CUTOFF (the walk command goes to 0: stop).
    # 12000 ms: 7100 (rested) and a blip to 7500 over [14000, 14600): below resume for part of
    # every window: still CUTOFF. 16000 ms: 7300 >= 7200: readings 16180 (frame 809) .. 17180 ms
    # = frame 859: OK.
    assert events == [
        (0, "battery", OK),
        (0, "req_vx", 0),
        (61, "req_vx", 1000),  # the first `walk 100 0 0` (frame 60) accepted once standing
        (309, "battery", LOW),
        (309, "req_vx", 600),
        (459, "battery", CUTOFF),
        (459, "req_vx", 0),
        (859, "battery", OK),
    ]
    # Modes: moving (the boot stand: 56 frames, the soft start's 24 included), standing, walking;
    # at the cutoff the walk stops (its steps end within a 1 s cycle), then relax: a sit (2 mm a
    # frame) and limp. Relaxed within 3 s of the cutoff; nothing moves until the stand at 900.
    modes = [(f, v) for f, what, v in log if what == "mode"]
    assert [v for f, v in modes] == [MOVING, STANDING, WALKING, STANDING, MOVING, RELAXED, MOVING, STANDING]
    f_walk, f_stood, f_sit, f_relaxed, f_stand = modes[2][0], modes[3][0], modes[4][0], modes[5][0], modes[6][0]
    assert f_walk == 61 and 459 < f_stood <= 459 + 75 and f_sit == f_stood + 1 and f_relaxed <= 459 + 150
    assert f_stand == 901  # `stand` typed at 900, accepted, moving from the next frame's log
    # What the console printed: one notice per change, the refusals naming the battery.
    notices = [(f, line) for f, line in said if line.startswith("battery:")]
    assert [f for f, _ in notices] == [309, 459, 859]
    assert notices[0][1] == (
        "battery: low, 6.89 V (below 7.00 V for 1 s): walking capped at 60 mm/s and 15 deg/s; charge soon"
    )
    assert notices[1][1].startswith("battery: cutoff, 6.39 V (below 6.60 V for 1 s): sitting down, then relaxed;")
    assert notices[2][1] == "battery: ok, 7.29 V (above 7.20 V for 1 s): stand, walk and wall allowed, no speed cap"
    replies = dict(said)
    why = "cut off below 6.60 V (2 cells); charge it: allowed again after 1 s above 7.20 V"
    assert replies[460] == "err walk: battery 6.39 V, " + why  # the next walk renewal is refused
    assert replies[700] == "err stand: battery 7.09 V, " + why
    assert replies[701] == "err wall: battery 7.09 V, " + why
    assert replies[703] == "err sit: battery 7.09 V, " + why  # nothing that drives a servo
    assert replies[704] == "err joint: battery 7.09 V, " + why
    assert replies[705] == "ok mode relaxed"
    assert replies[825] == "err stand: battery 7.29 V, " + why  # 7300 since 16000 ms, not yet 1 s
    assert replies[900] == "ok mode moving"
    # status: the window's maximum, within 5 mV (2.42 mV ADC steps, the divider's rounding)
    assert " boot stood battery cutoff battery_mv " in replies[640] and abs(_mv(replies[640]) - 7100) <= 5
    assert " battery ok battery_mv " in replies[1000] and abs(_mv(replies[1000]) - 7300) <= 5
    assert replies[1001] == "ok faults 1 logged (oldest first) battery frame 459"  # the cutoff, in the fault log
    assert [line for f, line in said if line.startswith("err") and f not in (460, 700, 701, 703, 704, 825)] == [
        "err walk: battery %s V, %s" % (v, why) for v in ["6.39"] * 5 + ["7.09"] * 4
    ]


def test_power_up_below_the_cutoff_stays_relaxed(rt):
    log, said = rt.call("scenarios.battery:boot_at_cutoff", 100)
    assert [v for f, what, v in log if what == "mode"] == [RELAXED]
    lines = [line for f, line in said if not line.startswith("cal:")]
    assert lines[0].startswith("battery: cutoff, 6.39 V")
    assert lines[1] == (
        "err stand: battery 6.39 V, cut off below 6.60 V (2 cells); charge it: allowed again after 1 s above 7.20 V"
    )
    assert " boot relaxed_battery battery cutoff battery_mv " in lines[2]
    assert abs(_mv(lines[2]) - 6400) <= 5


def test_boards_without_the_setting_show_n_a(rt):
    monitor, status = rt.call("scenarios.battery:no_setting_status")
    assert monitor is None and status.endswith(" boot none battery n/a battery_mv n/a")


def test_a_battery_frame_allocates_nothing(mp):
    heap, frames, held, state, mode = mp.call("scenarios.battery:steady_frame_heap")
    assert (frames, held, state, mode) == (700, 0, OK, WALKING)
    assert heap == 0


def test_a_capped_frame_allocates_nothing(mp):
    heap, state, req_vx, mode = mp.call("scenarios.battery:low_heap")
    # 1200, 300 under a 600 cap: isqrt(1200^2 + 300^2) = 1236 -> 485 permille -> 582, 145; the yaw
    # 1500 * 485 // 1000 = 727 is under its cap.
    assert (state, req_vx, mode) == (LOW, 582, WALKING)
    assert heap == 0


@pytest.mark.parametrize(
    "pack_mv, state, ok",
    [
        (8000, "ok", True),
        (6900, "low: charge the pack (cut off below 6.60 V)", False),
        (6400, "cutoff: charge the pack (cut off below 6.60 V)", False),
    ],
)
def test_selftest_reports_the_pack(rt, pack_mv, state, ok):
    # 2S thresholds by hand: warn 2 x 3.5 = 7.0 V, cutoff 2 x 3.3 = 6.6 V.
    [line] = rt.call("scenarios.battery:selftest_supply", pack_mv)
    word, check, volts, unit, rest = line.split(" ", 4)
    assert (word, check, unit, rest) == ("ok" if ok else "err", "supply", "V,", "2 cells, " + state)
    # Shown to 10 mV (cut, not rounded) of a reading one 12-bit ADC count wide: 3.3 V / 4096 at the
    # pin, x 3 through the divider = 2.4 mV of pack.
    assert abs(pack_mv - 1000 * float(volts)) < 10 + 2.5, line
