"""The whole loop on the stub machine: board file, robot file, PCA9685 and HC-SR04 models, the
virtual clock. Faults from issue 3 are injected while it runs: the loop keeps running, reports
them, and no channel ever outputs a pulse outside its servo's calibrated range."""

SETUP = """
import _stub_clock as clock
import _stub_i2c
import _stub_pins
import hcsr04_model
import stub_board
from hexapod import board as boards
from hexapod import robotcal
import main

BOARD = stub_board.reset("pico")
TABLE = boards.servo_table(BOARD, robotcal.servo_maps(robotcal.load("default")))
bus, chips = stub_board.pca9685_models(BOARD, attach=False)
SONAR = stub_board.sonar_models(BOARD, [3000 + 1000 * k for k in range(5)])


def plug(address):
    bus.attach(chips[address])


def unsafe():
    # Servos whose output is neither off nor inside min..max (give or take half a count).
    bad = []
    for k in range(18):
        address, ch, smap = TABLE[k]
        m = chips[address]
        if m not in bus._devices:
            continue
        ns = m.pulse_ns(ch)
        half = (m.prescale() + 1) * 500000000 // m.clock_hz() + 1
        if ns and not smap.min_us * 1000 - half <= ns <= smap.max_us * 1000 + half:
            bad.append((k, ns))
    return bad


def frames(r, n):
    worst = []
    for _ in range(n):
        r.step()
        worst += unsafe()
        r.wait()
    return worst
"""


def run_both(both_runtimes, body):
    cp, mp = both_runtimes(SETUP + body, heapsize="4m")
    assert cp == mp
    return __import__("ast").literal_eval(cp.strip().splitlines()[-1])


def test_healthy_loop_stands_walks_and_measures(both_runtimes):
    out = run_both(
        both_runtimes,
        """
plug(0x40)
plug(0x41)
r = main.build(clock=clock)
r.robot.stand_up()
bad = frames(r, 150)
r.robot.walk(1200, 0, 0)
bad += frames(r, 300)
widths = [chips[a].pulse_us(ch) for a, ch, _ in TABLE]
print((r.frames, r.held, r.robot.overruns, r.bank.failed_frames, r.sonar_faults, r.distances, bad,
       min(widths), max(widths), r.robot.mode, clock.ticks_ms()))
""",
    )
    n, held, overruns, failed, sonar_faults, dist, bad, lo, hi, mode, now = out
    assert n == 450 and held == 0 and overruns == 0 and failed == 0 and sonar_faults == 0
    assert [abs(d - (3000 + 1000 * k)) <= 2 for k, d in enumerate(dist)] == [True] * 5, dist
    assert bad == [] and 600 <= lo <= hi <= 2400
    assert mode == 4  # walking
    assert 450 * 20 <= now <= 450 * 20 + 40  # frames on their 20 ms boundaries


def test_faults_while_running(both_runtimes):
    out = run_both(
        both_runtimes,
        """
plug(0x40)          # 0x41 unplugged at boot
r = main.build(clock=clock)
r.robot.stand_up()
bad = frames(r, 20)
boot = (r.bank.failed_frames > 0, r.frames)
plug(0x41)          # plugged back: picked up by the periodic MODE1 check
bad += frames(r, 60)
back = (r.bank.reinits > 0, chips[0x41].running())
bus.fault(0x40, 'nack', byte=17)   # a NACK in the middle of a frame burst
errors_before = r.bank.chips[0].errors
bad += frames(r, 5)
nack = (r.bank.chips[0].errors - errors_before, r.bank.chips[0].last_errno)
chips[0x41].reset()                # brownout between frames
bad += frames(r, 30)
brownout = (r.bank.reinits >= 2, chips[0x41].running())
SONAR[0].stuck_high = True         # front echo stuck high
SONAR[2].missing_echo = True       # left-rear echo never comes
bad += frames(r, 50)
sonar = (r.sonar_faults > 0, r.distances[0], r.distances[2], r.sonar_status[0], r.sonar_status[2])
SONAR[0].stuck_high = False
SONAR[2].missing_echo = False
bad += frames(r, 50)
r.robot.walk(1000, 0, 500)
bad += frames(r, 100)
print((boot, back, nack, brownout, sonar, r.distances[0] > 0, r.frames, r.held, bad, r.robot.mode))
""",
    )
    boot, back, nack, brownout, sonar, front_again, n, held, bad, mode = out
    assert nack[0] >= 1 and nack[1] in (5, 19)  # seen, retried within the frame, counted
    assert boot == [True, 20] or boot == (True, 20)
    assert tuple(back) == (True, True)
    assert tuple(brownout) == (True, True)
    faults, d_front, d_left_rear, st_front, st_left_rear = sonar
    assert faults and d_front == -1 and d_left_rear == -1
    assert st_front == 3 and st_left_rear == 2  # STUCK, NO_ECHO: never a fake distance
    assert front_again and n == 315 and mode == 4 and held == 0
    assert bad == []


def test_a_steady_frame_allocates_nothing(mp):
    """Ping + tick + two bursts, through the stub machine and the chip models, in the VM."""
    from hexapod_host.testing.runtimes import HEAP_PROBE

    src = (
        SETUP
        + HEAP_PROBE
        + """
plug(0x40)
plug(0x41)
r = main.build(clock=clock)
r.robot.stand_up()
frames(r, 100)
r.robot.walk(1200, 300, 1500)
frames(r, 100)


def run(n):
    for _ in range(n):
        r.step()
        r.wait()


print((heap_bytes(run, 300), r.frames, r.held, r.bank.failed_frames, r.robot.mode))
"""
    )
    heap, n, held, failed, mode = mp.value(src, heapsize="4m")
    assert (held, failed, mode) == (0, 0, 4) and n == 800
    assert heap == 0


def test_esp32_board_builds_and_runs(rt):
    src = (
        SETUP.replace('stub_board.reset("pico")', 'stub_board.reset("esp32_devkit")')
        + """
plug(0x40)
plug(0x41)
r = main.build("esp32_devkit", clock=clock)
r.robot.stand_up()
bad = frames(r, 120)
print((r.frames, r.held, r.bank.failed_frames, r.sonar_faults, bad, r.robot.mode))
"""
    )
    assert rt.value(src, heapsize="4m") == (120, 0, 0, 0, [], 3)  # standing after the stand-up move
