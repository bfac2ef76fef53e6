"""`hexapod bench i2c --json`: one run gives ours, adafruit_servokit and the physical minimum."""

import json

import pytest

from hexapod_host.commands import cli
from hexapod_host.testing.runtimes import micropython_missing


@pytest.fixture(scope="module")
def figures():
    if micropython_missing():
        pytest.skip(micropython_missing())
    import contextlib
    import io

    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert cli.main(["bench", "i2c", "--json"]) == 0
    return json.loads(out.getvalue())


def test_bench_reports_all_three_in_one_run(figures):
    assert figures["bench"] == "i2c" and figures["freq_hz"] == 400000 and figures["servos"] == 18
    for key in ("ours", "adafruit_servokit", "physical_minimum", "ours_with_mode1_readback"):
        assert set(figures[key]) >= {"transactions", "bytes", "bits", "bus_us"}


def test_our_frame_is_two_bursts_and_allocates_nothing(figures):
    ours = figures["ours"]
    assert (ours["transactions"], ours["bytes"]) == (2, 76)
    assert ours["bits"] == 2 * 2 + 9 * 76  # START + STOP per transaction, 9 SCL periods a byte
    assert ours["bus_us"] == pytest.approx(ours["bits"] * 2.5 + 2 * 1.3)
    assert figures["ours_heap_bytes_per_frame"] == 0


def test_ordering_minimum_ours_servokit(figures):
    low, ours, kit = figures["physical_minimum"], figures["ours"], figures["adafruit_servokit"]
    assert (low["transactions"], low["bytes"]) == (2, 72)
    assert (kit["transactions"], kit["bytes"]) == (18, 108)
    assert low["bus_us"] < ours["bus_us"] < kit["bus_us"]
    # The read-back adds one 4-byte transaction per chip every check_every frames.
    rb = figures["ours_with_mode1_readback"]
    assert rb["transactions"] == pytest.approx(2 + 2 / rb["check_every"])
    assert rb["bytes"] == pytest.approx(76 + 2 * 4 / rb["check_every"])
