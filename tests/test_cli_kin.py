"""`hexapod ik` / `hexapod fk`: output format, JSON, batch, both runtimes, and bad input."""

import json
import os
import subprocess
import sys

import pytest

from hexapod.leg import OK, Leg
from hexapod.units import format_fixed
from hexapod_host import cli

HEXAPOD = os.path.join(os.path.dirname(sys.executable), "hexapod")


def run(capsys, *argv, stdin=None, monkeypatch=None):
    if stdin is not None:
        import io

        monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BytesIO(stdin.encode())))
    try:
        status = cli.main(list(argv))
    except SystemExit as exc:
        status = exc.code
    out = capsys.readouterr()
    return status, out.out, out.err


def test_ik_prints_three_angles_with_two_decimals(capsys):
    status, out, _ = run(capsys, "ik", "140", "0", "-80")
    leg = Leg(coxa=300, femur=850, tibia=1250, femur_offset=320)
    angles = [0, 0, 0]
    assert leg.ik(1400, 0, -800, angles) == OK
    assert status == 0
    assert out == " ".join(format_fixed(a, 2) for a in angles) + "\n"


def test_fk_inverts_ik(capsys):
    status, out, _ = run(capsys, "ik", "120", "-35.5", "-60.2")
    t = out.split()
    status, out, _ = run(capsys, "fk", *t)
    assert status == 0
    assert [float(v) for v in out.split()] == pytest.approx([120, -35.5, -60.2], abs=0.11)


def test_json_and_geometry_options(capsys):
    status, out, _ = run(
        capsys, "ik", "0", "137", "0", "--coxa", "30", "--femur", "45", "--tibia", "62", "--femur-offset", "0"
    )
    assert status == 0 and out.split() == ["90.00", "0.00", "0.00"]
    status, out, _ = run(
        capsys, "ik", "0", "137", "0", "--coxa=30", "--femur=45", "--tibia=62", "--femur-offset=0", "--json"
    )
    assert json.loads(out) == {"reachable": True, "theta1_deg": 90.0, "theta2_deg": 0.0, "theta3_deg": 0.0}
    status, out, _ = run(capsys, "fk", "10", "20", "-30", "--json")
    assert set(json.loads(out)) == {"x_mm", "y_mm", "z_mm"}


def test_unreachable_is_status_1_with_the_reason(capsys):
    status, out, _ = run(capsys, "ik", "400", "0", "0")
    assert status == 1 and out.startswith("unreachable: too far: ") and "mm beyond the reach" in out
    status, out, _ = run(capsys, "ik", "34", "0", "32")
    assert status == 1 and "too close" in out
    status, out, _ = run(capsys, "ik", "-100", "10", "-50")
    assert status == 1 and out == "unreachable: coxa above its limit by 84.29 deg\n"
    status, out, _ = run(capsys, "ik", "150", "0", "-100", "--limits", "-90", "90", "-5", "90", "-180", "0")
    assert status == 1 and out == "unreachable: femur below its limit by 3.30 deg\n"
    status, out, _ = run(capsys, "fk", "0", "95", "-10")
    assert status == 1 and out == "unreachable: femur above its limit by 5.00 deg\n"
    status, out, _ = run(capsys, "ik", "400", "0", "0", "--json")
    assert json.loads(out)["reachable"] is False


BAD = [
    (("ik", "ten", "0", "0"), "x: 'ten' is not a number"),
    (("ik", "1", "2"), "need 3 numbers, got 2"),
    (("ik", "1", "2", "3", "4"), "need 3 numbers, got 4"),
    (("ik",), "need 3 numbers, got 0"),
    (("ik", "1", "NaN", "3"), "y: 'NaN' is not a number"),
    (("ik", "1", "2", "inf"), "z: 'inf' is not a number"),
    (("ik", "1", "2", "1e3"), "z: '1e3' is not a number"),
    (("ik", "1", "2", "3", "--femur", "-85"), "--femur: -85 mm is outside the allowed 10..250 mm"),
    (("ik", "1", "2", "3", "--tibia", "0"), "--tibia: 0 mm is outside"),
    (("ik", "1", "2", "3", "--coxa", "-1"), "--coxa: -1 mm is outside"),
    (("ik", "1", "2", "3", "--coxa", "x"), "--coxa: 'x' is not a number"),
    (("ik", "1", "2", "3", "--femur-offset", "999"), "--femur-offset: 999 mm is outside"),
    (("ik", "1", "2", "3", "--limits", "10", "-10", "-90", "90", "-180", "0"), "coxa min 1000 cdeg is above its max"),
    (("ik", "1", "2", "3", "--limits", "-90", "90", "-90", "90", "-190", "0"), "--limits: -190 deg is outside"),
    (("ik", "1", "2", "3", "--limits", "a", "90", "-90", "90", "-180", "0"), "--limits: 'a' is not a number"),
    (("fk", "1", "x", "3"), "theta2: 'x' is not a number"),
    (("fk", "1", "2"), "need 3 numbers, got 2"),
    (("ik", "--batch", "1", "2", "3"), "--batch reads stdin"),
    (("ik", "1", "2", "3", "--runtime", "pypy"), "invalid choice: 'pypy'"),
]


@pytest.mark.parametrize("argv,message", BAD, ids=[" ".join(a) for a, _ in BAD])
def test_bad_input_exits_2_naming_the_value(capsys, argv, message):
    status, out, err = run(capsys, *argv)
    assert status == 2
    assert message in err, err
    assert out == ""


def test_batch_reports_bad_lines_and_carries_on(capsys, monkeypatch):
    stdin = "140 0 -80\nfoo 1 2\n400 0 0\n1 2\n\n120 10 -70\n"
    status, out, err = run(capsys, "ik", "--batch", stdin=stdin, monkeypatch=monkeypatch)
    rows = out.splitlines()
    assert status == 2 and len(rows) == 6
    assert rows[1] == "error: line 2: x: 'foo' is not a number"
    assert rows[2].startswith("unreachable: too far")
    assert rows[3] == "error: line 4: need 3 numbers (x y z), got 2"
    assert rows[4] == "error: line 5: need 3 numbers (x y z), got 0"
    assert len(rows[5].split()) == 3 and "line 2" in err and "line 4" in err


def batch_input(n):
    lines = []
    for k in range(n):
        lines.append("%d.%d %d -%d.%d" % (60 + k % 130, k % 10, (k * 7) % 160 - 80, 20 + k % 100, k % 7))
    return "".join(line + "\n" for line in lines)


def hexapod(*argv, stdin=""):
    return subprocess.run([HEXAPOD, *argv], input=stdin, capture_output=True, text=True, timeout=120)


@pytest.mark.parametrize(
    "argv",
    [
        ("ik", "140", "0", "-80"),
        ("ik", "140", "0", "-80", "--json"),
        ("ik", "500", "0", "0"),
        ("fk", "12.5", "-30", "-100.25"),
        ("ik", "1", "zz", "3"),
    ],
)
def test_micropython_runtime_prints_byte_identical_output(argv, mp):
    a = hexapod(*argv)
    b = hexapod(*argv, "--runtime", "micropython")
    assert (a.returncode, a.stdout, a.stderr) == (b.returncode, b.stdout, b.stderr)
    assert a.stdout or a.stderr


def test_ten_thousand_line_batch_identical_in_both_runtimes(mp):
    stdin = batch_input(10000)
    a = hexapod("ik", "--batch", stdin=stdin)
    b = hexapod("ik", "--batch", "--runtime", "micropython", stdin=stdin)
    assert a.returncode == b.returncode and a.stdout == b.stdout
    rows = a.stdout.splitlines()
    assert len(rows) == 10000
    solved = [r for r in rows if not r.startswith("unreachable")]
    assert len(solved) > 5000 and all(len(r.split()) == 3 for r in solved)
