"""Decimal text <-> fixed point (both runtimes), and the servo pulse map."""

import pytest

from hexapod.servo import ABOVE_MAX, BELOW_MIN, OK, ServoMap
from hexapod.units import format_fixed, parse_fixed

CASES = [
    ("12.34", 2),
    ("-0.005", 2),
    ("0.004", 2),
    ("+7", 1),
    (".5", 1),
    ("5.", 1),
    ("-12.35", 1),
    ("999999999", 0),
    ("1234567890", 0),
    ("abc", 2),
    ("1e5", 2),
    ("nan", 2),
    ("-inf", 2),
    ("", 1),
    ("-", 1),
    ("1.2.3", 1),
    ("--1", 1),
    ("0x10", 1),
    ("1_000", 1),
    (" 3.25 ", 2),
]


def test_parse_and_format_identical_in_both_runtimes(rt):
    out = rt.call("scenarios.units:parse_and_format", CASES)
    assert out[:9] == [
        "1234 12.34",
        "-1 -0.01",
        "0 0.00",
        "70 7.0",
        "5 0.5",
        "50 5.0",
        "-124 -12.4",
        "999999999 999999999",
        "error '1234567890' is too large",
    ]
    assert all(line.startswith("error ") and "is not a number" in line for line in out[9:19]), out[9:19]
    assert out[19] == "325 3.25"


def test_one_pass_parse_and_format_equal_the_general_forms(rt):
    # The console's numbers take parse_fixed's one-pass form (issue 22: a `walk` line's three
    # numbers and its reply's three took ~2.6 ms on the emulated Pico); everything else, errors
    # included, the general form. Both give the same value or the same message, on both runtimes.
    count, bad = rt.call("scenarios.units:fast_equals_general", 12345, 3000)
    assert count == 3000 and bad == [], bad[:5]


def test_format_fixed_round_trips():
    for v in range(-30000, 30001, 7):
        for places in (0, 1, 2, 3):
            assert parse_fixed(format_fixed(v, places), places) == v


def test_seed001_pulse_map():
    s = ServoMap()
    out = [0]
    for cdeg, us in ((-9000, 600), (0, 1500), (9000, 2400), (4550, 1955), (-1, 1500), (5, 1501)):
        assert s.pulse(cdeg, out, 0) == OK and out[0] == us, cdeg
    r = ServoMap(direction=-1, centre_us=1450, min_us=700, max_us=2300)
    assert r.raw(4000) == 1050 and r.angle(1050) == 4000
    out[0] = 1234
    assert r.pulse(9000, out, 0) == BELOW_MIN and r.excess == 150 and out[0] == 1234  # out untouched
    assert r.pulse(-9000, out, 0) == ABOVE_MAX and r.excess == 50
    assert r.clamp(3000) == 2300 and r.clamp(10) == 700 and r.clamp(1500) == 1500
    # at exactly the limits, on CPython alone too (the VM may be missing): one us either side
    assert [r.clamp(us) for us in (699, 700, 701, 2299, 2300, 2301)] == [700, 700, 701, 2299, 2300, 2300]


def test_a_reference_angle_changes_the_reference_not_the_mapping():
    # seed 001's tibia: 2400 us at 0 deg, 10 us per degree (1500 us at -90): the same pulse for every
    # angle whether the calibration point is 0 or -90 deg, on both mounting directions.
    for old, new in (
        (ServoMap(centre_us=2400), ServoMap(centre_us=1500, ref_cdeg=-9000)),
        (ServoMap(centre_us=600, direction=-1), ServoMap(centre_us=1500, direction=-1, ref_cdeg=-9000)),
    ):
        assert [new.raw(a) for a in range(-18000, 1)] == [old.raw(a) for a in range(-18000, 1)]
        assert new.raw(-9000) == 1500 and new.centre_us == 1500 and old.centre_us in (600, 2400)
    s = ServoMap(centre_us=1500, ref_cdeg=-9000)
    s.centre_us = 1510  # a trim of +10 us at the reference: every angle 10 us more
    assert (s.raw(-9000), s.raw(0), s.raw(-18000)) == (1510, 2410, 610)
    s.direction = -1  # mirrored about the reference: -90 deg keeps its pulse
    assert (s.raw(-9000), s.raw(0), s.raw(-18000), s.centre_us) == (1510, 610, 2410, 1510)
    assert s.raw_at(-8000, 1500, 1) == 1600 and s.raw_at(-8000, 1500, -1) == 1400  # another calibration's pulse
    assert s.angle(s.raw(-4500)) == -4500


@pytest.mark.parametrize(
    "kwargs,message",
    [
        ({"centre_us": 400}, "centre_us: 400 is outside 500..2500 us"),
        ({"min_us": 2600}, "min_us: 2600 is outside"),
        ({"max_us": 499}, "max_us: 499 is outside"),
        ({"min_us": 1600}, "need min_us <= centre_us <= max_us"),
        ({"max_us": 1400}, "need min_us <= centre_us <= max_us"),
        ({"direction": 0}, "direction: 0, allowed 1 or -1"),
        ({"direction": 2}, "direction: 2, allowed 1 or -1"),
        ({"us_per_degree": 0}, "us_per_degree: 0 is outside 100..5000"),
        ({"us_per_degree": 10.0}, "us_per_degree: 10.0 is outside"),
        ({"centre_us": 1500.5}, "centre_us: 1500.5 is outside"),
        ({"min_us": "600"}, "min_us: '600' is outside"),
        ({"ref_cdeg": 18001}, "ref_cdeg: 18001 is outside -18000..18000"),
        ({"ref_cdeg": -18001}, "ref_cdeg: -18001 is outside"),
        ({"ref_cdeg": "-90"}, "ref_cdeg: '-90' is outside"),
        ({"ref_cdeg": True}, "ref_cdeg: True is outside"),
        ({"ref_cdeg": -9000.0}, "ref_cdeg: -9000.0 is outside"),
        ({"ref_cdeg": -9005}, "ref_cdeg: -9005 at 1000"),
        ({"ref_cdeg": 3, "us_per_degree": 1000}, "ref_cdeg: 3 at 1000"),
        ({"ref_cdeg": 9000, "centre_us": 2450}, "need min_us <= centre_us <= max_us"),
    ],
)
def test_bad_servo_calibration_is_refused(kwargs, message):
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(".", r"\.")):
        ServoMap(**kwargs)


@pytest.mark.parametrize(
    "kwargs,message",
    [
        ({"coxa": -1}, "coxa: -1 is outside the allowed 0..1500"),
        ({"femur": 99}, "femur: 99 is outside the allowed 100..2500"),
        ({"tibia": 2501}, "tibia: 2501 is outside"),
        ({"tibia": 12.5}, "tibia: need a whole number, got 12.5"),
        ({"femur": True}, "femur: need a whole number, got True"),
        ({"femur_offset": 1501}, "femur_offset: 1501 is outside"),
        ({"limits": (0, 1, 2)}, "limits: need 6 values"),
        ({"limits": (100, -100, 0, 0, -100, 0)}, "coxa min 100 cdeg is above its max -100 cdeg"),
        ({"limits": (0, 0, 0, 0, 0, 18001)}, "tibia max limit: 18001 is outside"),
        ({"limits": (0, 0, "a", 0, 0, 0)}, "femur min limit: need a whole number"),
    ],
)
def test_bad_leg_geometry_is_refused(kwargs, message):
    from hexapod.leg import Leg

    args = {"coxa": 300, "femur": 850, "tibia": 1250, **kwargs}
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(".", r"\.")):
        Leg(**args)


def test_parse_fixed_edges_identical_in_both_runtimes(rt):
    cases = [
        ("\uff11\uff14\uff10", 1, None),  # full-width digits: CPython's isdigit() says yes, MicroPython's no
        ("\u0661", 1, None),  # an Arabic-Indic one
        ("\u22125", 1, None),  # a Unicode minus sign
        ("1e6", 1, None),
        ("-2.5E+03", 1, None),
        ("1e", 1, None),
        ("\u00a012\u3000", 1, None),  # Unicode spaces are not stripped (MicroPython's strip() keeps them)
        ("3000", 1, 30000),  # exactly at the limit
        ("-3000.04", 1, 30000),  # rounds onto it
        ("3000.05", 1, 30000),  # rounds past it
        ("0" * 50 + "12.5", 1, 30000),  # leading zeros are no digits
        ("9" * 60, 1, 30000),
        ("9" * 60, 1, None),
        ("360.005", 2, 36000),
    ]
    shown = ["a'b\\c\x00\u00e9\u20ac\U0001f600", "x" * 25, "x" * 20]
    out = rt.call("scenarios.units:parse_edges", cases, shown)
    only = "is not a number: only ASCII digits 0-9, '-' and '.' are accepted"
    assert out == [
        "error '\\uff11\\uff14\\uff10' " + only,
        "error '\\u0661' " + only,
        "error '\\u22125' " + only,
        "error '1e6' is not a number: exponents are not accepted, write it out in full",
        "error '-2.5E+03' is not a number: exponents are not accepted, write it out in full",
        "error '1e' is not a number",
        "error '\\xa012\\u3000' " + only,
        "30000",
        "-30000",
        "error '3000.05' is outside the accepted -3000..3000 mm",
        "125",
        "error '99999999999999999999...' is outside the accepted -3000..3000 mm",
        "error '99999999999999999999...' is too large",
        "error '360.005' is outside the accepted -360..360 mm",
        "'a\\'b\\\\c\\x00\\xe9\\u20ac\\U0001f600' 'xxxxxxxxxxxxxxxxxxxx...' 'xxxxxxxxxxxxxxxxxxxx'",
    ]
