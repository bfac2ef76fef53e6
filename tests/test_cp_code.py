"""firmware/code.py, the CircuitPython entry, on fake CircuitPython modules (CPython only).

busio.I2C drives the bus model with two PCA9685 models, digitalio/pulseio drive five HC-SR04
models through the stub pins, supervisor.ticks_ms runs on the virtual clock and wraps at
2**29 during the run. As tests/test_runner.py does for main.py: the loop stands and walks
with correct distances, faults keep it running and are reported, and no channel ever
outputs a pulse outside its servo's calibrated range.
"""

import importlib.util
import os

import _stub_clock as vclock
import _stub_pins as pins
import hcsr04_model
import pytest
import runner
from i2c_bus import I2CBus
from pca9685_model import PCA9685Model
from scenarios.runner import unsafe_outputs

from drivers import cp_clock, hcsr04
from hexapod import board as boards
from hexapod import robotcal
from hexapod_host import FIRMWARE
from hexapod_host.stubs import circuitpython as fakes_cp

BOARD = boards.load("feather_rp2040")
TABLE = boards.servo_table(BOARD, robotcal.servo_maps(robotcal.load("default")))
RANGER = "drivers.cp_hcsr04_pulsein"


def load_code():
    """firmware/code.py under another name: `code` is also a CPython standard module."""
    spec = importlib.util.spec_from_file_location("cp_code", os.path.join(FIRMWARE, "code.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


class Rig:
    def __init__(self, monkeypatch, plugged=(0x40, 0x41), wrap_after_ms=3000):
        vclock.reset(0)
        pins.reset()
        self.bus = I2CBus(clock_us=vclock.now_us)
        self.chips = {c["address"]: PCA9685Model(c["address"], osc_hz=c["osc_hz"]) for c in BOARD["pca9685"]["chips"]}
        for a in plugged:
            self.bus.attach(self.chips[a])
        start = fakes_cp.SUPERVISOR_PERIOD_MS - wrap_after_ms  # supervisor.ticks_ms wraps during the run
        self.cp = fakes_cp.CircuitPython(self.bus, ticks_start_ms=start).install(monkeypatch)
        self.sonar = [
            hcsr04_model.HCSR04(t, e, distance=3000 + 1000 * k) for k, (t, e) in enumerate(boards.sonar_pins(BOARD))
        ]
        fakes_cp.forget(RANGER)
        self.code = load_code()
        self.clock = self.cp.clock()

    def unsafe(self):
        return unsafe_outputs(TABLE, self.bus, self.chips)

    def frames(self, r, n):
        bad = []
        for _ in range(n):
            r.step()
            bad += self.unsafe()
            r.wait()
        return bad


@pytest.fixture
def rig(monkeypatch):
    yield lambda **kw: Rig(monkeypatch, **kw)
    fakes_cp.forget(RANGER)


def test_stands_walks_and_measures(rig):
    g = rig()
    r = g.code.build(clock=g.clock)
    t0 = vclock.now_us()
    sup0 = g.cp.ticks_ms()
    r.robot.stand_up()
    bad = g.frames(r, 5)
    # one cycle in, every sensor has fired once and none has a reading yet: a reading is a cycle old
    assert r.sonar_status == [hcsr04.WAIT] * 5 and r.distances == [hcsr04.NO_DISTANCE] * 5
    bad += g.frames(r, 5)
    assert r.sonar_status == [hcsr04.OK] * 5
    bad += g.frames(r, 140)
    r.robot.walk(1200, 0, 0)
    bad += g.frames(r, 300)
    assert g.cp.ticks_ms() < sup0  # the supervisor's 2**29 wrap happened mid-run
    assert (r.frames, r.held, r.robot.overruns, r.bank.failed_frames, r.sonar_faults) == (450, 0, 0, 0, 0)
    assert r.sonar_status == [hcsr04.OK] * 5
    assert [abs(d - (3000 + 1000 * k)) <= 2 for k, d in enumerate(r.distances)] == [True] * 5, r.distances
    assert bad == []
    widths = [g.chips[a].pulse_us(ch) for a, ch, _ in TABLE]
    assert 600 <= min(widths) <= max(widths) <= 2400 and len(set(widths)) > 3
    assert r.robot.mode == 4  # walking
    assert 450 * 20000 <= vclock.now_us() - t0 <= 450 * 20000 + 40000  # every frame on its 20 ms boundary
    assert sum(sum(m.flags.values()) for m in g.sonar) == 0  # no short trigger, crosstalk or ping within 60 ms
    assert r.sonars.ring.max_block_us == 10


def test_main_prints_a_status_line_every_5_s(rig, capsys):
    g = rig()
    r = g.code.main(frames=500, clock=g.clock, boot="stand", calibrated=True)
    notice, *lines = capsys.readouterr().out.splitlines()
    assert notice == "boot: standing up (the board file's boot setting is stand, the servos are calibrated)"
    assert [line.split()[:2] for line in lines] == [["frames", "250"], ["frames", "500"]]
    assert lines[-1] == runner.status_line(r) and "sonar_faults 0" in lines[-1] and "held 0" in lines[-1]
    assert "dist [%d, " % r.distances[0] in lines[-1]


def test_main_starts_following_from_the_board_setting(rig, monkeypatch):
    monkeypatch.setitem(BOARD, "follow", {"side": "right", "setpoint": 900})
    g = rig()
    for k, d in enumerate((9000, 9000, 9000, 900, 900)):
        g.sonar[k].set_distance(d)
    r = g.code.main(frames=300, clock=g.clock, boot="stand", calibrated=True)
    f = r.follower
    assert (f.mode_name, f.side, f.setpoint, f.used, f.distance, f.yaw) == (
        "following",
        "right",
        900,
        "right_front+right_rear",
        900,
        0,
    )
    assert r.robot.mode == 4 and f.updates > 10


def test_faults_while_running(rig):
    g = rig(plugged=(0x40,))  # 0x41 unplugged at boot
    r = g.code.build(clock=g.clock)
    r.robot.stand_up()
    bad = g.frames(r, 20)
    assert r.bank.failed_frames == 20 and r.bank.chips[1].offline
    g.bus.attach(g.chips[0x41])  # plugged back: found by the periodic MODE1 check
    bad += g.frames(r, 60)
    assert r.bank.reinits > 0 and g.chips[0x41].running()
    g.bus.fault(0x40, "nack", byte=17)  # a NACK in the middle of a frame burst
    errors = r.bank.chips[0].errors
    bad += g.frames(r, 5)
    assert r.bank.chips[0].errors > errors and r.bank.chips[0].last_errno == 5
    reinits = r.bank.reinits
    g.chips[0x41].reset()  # brownout between frames
    bad += g.frames(r, 30)
    assert r.bank.reinits > reinits and g.chips[0x41].running()
    faults = r.sonar_faults
    g.sonar[0].stuck_high = True  # front echo stuck high
    g.sonar[2].missing_echo = True  # left-rear echo never comes
    bad += g.frames(r, 50)
    assert r.sonar_faults > faults
    assert (r.distances[0], r.distances[2]) == (-1, -1)  # never a fake distance
    assert (r.sonar_status[0], r.sonar_status[2]) == (hcsr04.NO_ECHO, hcsr04.NO_ECHO)  # PulseIn: no STUCK
    assert r.sonar_status[1] == hcsr04.OK and abs(r.distances[1] - 4000) <= 2
    g.sonar[0].stuck_high = False
    g.sonar[2].missing_echo = False
    bad += g.frames(r, 50)
    assert r.sonar_status == [hcsr04.OK] * 5 and abs(r.distances[0] - 3000) <= 2
    r.robot.walk(1000, 0, 500)
    bad += g.frames(r, 100)
    assert (r.frames, r.held, r.robot.mode) == (315, 0, 4)
    assert bad == []


def test_default_clock_is_cp_clock_on_supervisor(rig):
    g = rig()
    r = g.code.build()
    assert isinstance(r.clock, cp_clock.Clock)
    t = r.clock.ticks_ms()
    vclock.advance_us(1234000)
    assert r.clock.ticks_diff(r.clock.ticks_ms(), t) == 1234


def remove_pin(g, name):
    delattr(g.cp.modules["board"], name)


BAD = [
    ({"board_name": "pico"}, None, "board 'pico': runtime 'micropython'"),
    ({"board_name": "nope"}, None, "board 'nope': no boards/nope.py"),
    ({"board_name": 7}, None, "board name 7"),
    ({"robot_name": "nope"}, None, "robot 'nope': no robots/nope.py"),
    ({"robot_name": ""}, None, "robot name ''"),
    ({"robot_name": None}, None, "robot name None"),
    ({}, "D13", "right_front sensor trigger: pin 'D13' is not in this CircuitPython board"),
    ({}, "A1", "right_rear sensor echo: pin 'A1'"),
    ({}, "SCL", "i2c scl: pin 'SCL'"),
    ({"max_range": 100}, None, "max_range: 100, allowed 200..40000"),
    ({"max_range": 50000}, None, "max_range: 50000"),
    ({"max_range": "1000"}, None, "max_range: '1000'"),
]


@pytest.mark.parametrize("kw,missing,message", BAD)
def test_bad_setup_is_one_clear_error_and_touches_nothing(rig, kw, missing, message):
    g = rig()
    if missing:
        remove_pin(g, missing)
    with pytest.raises(ValueError) as e:
        g.code.build(clock=g.clock, **kw)
    assert message in str(e.value), str(e.value)
    assert g.cp.claimed == {}  # no pin taken
    assert g.bus.stats()["transactions"] == 0  # no chip touched
    assert sum(m.pings for m in g.sonar) == 0
