"""Battery awareness (hexapod.battery) on both runtimes: the core state machine fed readings, and
the whole board (main.main with its console) on the stub machine with a pack voltage profile
on the stub ADC (_stub_adc: pack mV through the divider, the rp2 port's read_u16)."""

import _stub_adc
import _stub_clock as clock
import _stub_serial
import console
import main
import stub_board
from scenarios import battery_watch
from scenarios.runner import walking_heap

from hexapod import battery
from hexapod import board as boards

PIN = 28
DIVIDER = 333  # 1:3 (20k over 10k: 10 / 30 = 333 permille)
SETTING = {"pin": PIN, "divider_permille": DIVIDER}  # 2 cells, 3.5 / 3.3 / 3.6 V a cell


def raw_for(mv, divider=DIVIDER):
    """What the stub ADC's read_u16 answers for a pack at mv (the stub's conversion, not the core's)."""
    c = _stub_adc.code12(mv * divider // 1000)
    return c << 4 | c >> 8


def to_mv(raws, cells=2, divider=DIVIDER):
    """The core's mV for each read_u16 value."""
    m = battery.Monitor(cells, divider)
    return [m.to_mv(r) for r in raws]


def trace(samples_mv, cells=2, divider=DIVIDER, warn=3500, cutoff=3300, resume=3600):
    """Feed the monitor one reading per pack mV in samples_mv (200 ms apart); the state after each."""
    m = battery.Monitor(cells, divider, warn, cutoff, resume)
    out = []
    for mv in samples_mv:
        m.update(raw_for(mv, divider))
        out.append(m.state)
    return out


def dip(dip_ms, start_ms, level, low, total_ms, period=200):
    """Pack mV sampled every period ms from t = 0: level, with a dip to low over
    [start_ms, start_ms + dip_ms)."""
    return [low if start_ms <= t < start_ms + dip_ms else level for t in range(0, total_ms, period)]


def dip_states(dip_ms, total_ms=4000):
    """For every phase of the dip against the 200 ms samples (20 ms steps): the states seen while
    a 7600 mV pack dips to 6000 mV (below the 6600 mV cutoff) for dip_ms from 1000 ms + phase."""
    seen = []
    for phase in range(0, 200, 20):
        states = trace(dip(dip_ms, 1000 + phase, 7600, 6000, total_ms))
        for s in states:
            if s not in seen:
                seen.append(s)
    return sorted(seen)


def bad_setting(setting, runtime=None):
    """validate() of the pico board with its "battery" set: the message, or None when accepted."""
    board = boards.load("pico")
    saved = dict(board)
    board["battery"] = setting
    if runtime is not None:
        board["runtime"] = runtime
    try:
        boards.validate(board)
        return None
    except ValueError as e:
        return str(e)
    finally:
        board.clear()
        board.update(saved)


# The pack's voltage over the scenario (from_ms, mV), 2S, thresholds 7000 warn, 6600 cutoff,
# 7200 resume (tests/test_battery.py works the frames out by hand).
PROFILE = [
    (0, 8000),  # full
    (2000, 7600),  # sagging under load ...
    (2400, 6000),  # ... an inrush dip 600 ms long, far below the cutoff
    (3000, 7600),
    (3600, 6000),  # ... and one 900 ms long
    (4500, 7600),
    (5000, 6900),  # below warn (7000)
    (6600, 6000),  # a 600 ms dip while low
    (7200, 6900),
    (8000, 6400),  # below cutoff (6600)
    (12000, 7100),  # rested: above warn but below resume (7200)
    (14000, 7500),  # a 600 ms blip above resume
    (14600, 7100),
    (16000, 7300),  # charged: above resume
]


def walk_lines(first, last, every=25):
    return {f: "walk 100 0 0" for f in range(first, last, every)}


def whole(frames, typed, profile=PROFILE, setting=SETTING, boot="stand"):
    """main.main on the pico board with a battery setting, the pack following profile on the stub
    ADC, `typed` console lines ({frame: line}); returns (log, said)."""
    board = stub_board.reset("pico")
    bus, chips = stub_board.pca9685_models(board)
    stub_board.sonar_models(board, [3000 + 1000 * k for k in range(5)])
    _stub_adc.battery(setting["pin"], setting["divider_permille"], profile)
    board["battery"] = setting
    try:
        return battery_watch.run(frames, typed, clock, lambda: clock.ticks_ms() // 20, boot)
    finally:
        board["battery"] = None  # as shipped


def scenario_typed():
    """The console lines of the battery scenario, {frame: line} (also typed on the emulated Pico)."""
    typed = walk_lines(60, 700)
    typed[640] = "status"
    typed[700] = "stand"
    typed[701] = "wall left 30"
    typed[702] = "status"
    typed[703] = "sit"
    typed[704] = "joint 2 femur 10"
    typed[705] = "relax"  # allowed (the robot is relaxed already)
    typed[825] = "stand"  # the pack is at 7300 mV since 16000 ms, but not yet for a whole window
    typed[900] = "stand"
    typed[1000] = "status"
    typed[1001] = "faults"
    return typed


def scenario(frames=1050):
    return whole(frames, scenario_typed())


def boot_at_cutoff(frames=100):
    """Power-up on a pack below its cutoff with "boot": "stand": (log, said)."""
    return whole(frames, {50: "stand", 60: "status"}, profile=[(0, 6400)])


def no_setting_status():
    """The pico board as shipped (no battery setting): its status line."""
    stub_board.reset("pico")
    board = boards.load("pico")
    bus, chips = stub_board.pca9685_models(board)
    stub_board.sonar_models(board, [3000 + 1000 * k for k in range(5)])
    r = main.build(clock=clock)
    c = console.start(r, _stub_serial.BufferReader(), None, out=lambda line: None)
    return (r.battery, c.do("status"))


def _walking_heap(pack_mv):
    """(heap bytes 300 walking frames leave allocated, the runner): the pico board with a battery
    setting, the pack at pack_mv, standing then walking."""
    board = stub_board.reset("pico")
    stub_board.pca9685_models(board)
    stub_board.sonar_models(board, [3000 + 1000 * k for k in range(5)])
    _stub_adc.battery(PIN, DIVIDER, [(0, pack_mv)])
    board["battery"] = SETTING
    try:
        r = main.build(clock=clock)
    finally:
        board["battery"] = None  # as shipped
    r.robot.stand_up()
    for _ in range(100):
        r.step()
        r.wait()
    r.robot.walk(1200, 300, 1500)
    return walking_heap(r), r


def steady_frame_heap():
    """MicroPython only: heap bytes 300 walking frames (30 battery readings) leave allocated, with
    a battery setting and the pack at 7600 mV; (bytes, frames, held, battery state, mode)."""
    heap, r = _walking_heap(7600)
    return (heap, r.frames, r.held, r.battery.state, r.robot.mode)


def low_heap():
    """MicroPython only: the same in LOW (the speed cap in force, 6900 mV): heap bytes, state, req_vx."""
    heap, r = _walking_heap(6900)
    return (heap, r.battery.state, r.robot.walker.req_vx, r.robot.mode)


def selftest_supply(pack_mv):
    """The selftest's supply line on a board whose pack holds pack_mv from power-up (relaxed; the
    command typed at frame 60, after the monitor's 1 s window has filled)."""
    _, said = whole(120, {60: "selftest"}, profile=[(0, pack_mv)], boot="relaxed")
    return [line for _, line in said if line.split()[1:2] == ["supply"]]
