"""The whole loop (main.build's runner.Runner) on the stub machine: the board's PCA9685 models, which a
scenario plugs in itself, its HC-SR04 models at 300..700 mm, the virtual clock."""

import _stub_clock as clock
import main
import stub_board
from scenarios.heap import heap_bytes


def unsafe_outputs(table, bus, chips):
    """[(servo, ns)] of the servos whose output is neither off nor inside min..max (give or take half a
    count); servos on a chip not on the bus are not looked at."""
    bad = []
    for k in range(18):
        address, ch, smap = table[k]
        m = chips[address]
        if m not in bus._devices:
            continue
        ns = m.pulse_ns(ch)
        half = (m.prescale() + 1) * 500000000 // m.clock_hz() + 1
        if ns and not smap.min_us * 1000 - half <= ns <= smap.max_us * 1000 + half:
            bad.append((k, ns))
    return bad


class Loop:
    """The board's stub machine (None: pico, and main.build picks its board itself), its chips
    unplugged until plug(); build() makes the runner."""

    def __init__(self, board=None):
        self.board_name = board
        self.board = stub_board.reset(board or "pico")
        self.table = stub_board.servo_table(self.board)
        self.bus, self.chips = stub_board.pca9685_models(self.board, attach=False)
        self.sonar = stub_board.sonar_models(self.board, [3000 + 1000 * k for k in range(5)])
        self.r = None

    def plug(self, *addresses):
        for a in addresses:
            self.bus.attach(self.chips[a])

    def build(self):
        self.r = main.build(self.board_name, clock=clock) if self.board_name else main.build(clock=clock)
        return self.r

    def unsafe(self):
        return unsafe_outputs(self.table, self.bus, self.chips)

    def frames(self, n):
        """n frames (step, wait); the unsafe outputs seen after each step."""
        worst = []
        for _ in range(n):
            self.r.step()
            worst += self.unsafe()
            self.r.wait()
        return worst

    def widths(self):
        return [self.chips[a].pulse_us(ch) for a, ch, _ in self.table]


def _standing_loop(board=None, frames=0):
    loop = Loop(board)
    loop.plug(0x40, 0x41)
    loop.build().robot.stand_up()
    bad = loop.frames(frames)
    return loop, bad


def healthy():
    """Stand 150 frames, walk 300: the counters, distances, unsafe outputs, width range, mode, clock."""
    loop, bad = _standing_loop(frames=150)
    r = loop.r
    r.robot.walk(1200, 0, 0)
    bad += loop.frames(300)
    widths = loop.widths()
    return (
        r.frames,
        r.held,
        r.robot.overruns,
        r.bank.failed_frames,
        r.sonar_faults,
        r.distances,
        bad,
        min(widths),
        max(widths),
        r.robot.mode,
        clock.ticks_ms(),
    )


def faults_while_running():
    """Chip 0x41 unplugged at boot then plugged, a NACK, a brownout, two sonar faults, then walking."""
    loop = Loop()
    chips = loop.chips
    loop.plug(0x40)  # 0x41 unplugged at boot
    r = loop.build()
    r.robot.stand_up()
    bad = loop.frames(20)
    boot = (r.bank.failed_frames > 0, r.frames)
    loop.plug(0x41)  # plugged back: picked up by the periodic MODE1 check
    bad += loop.frames(60)
    back = (r.bank.reinits > 0, chips[0x41].running())
    loop.bus.fault(0x40, "nack", byte=17)  # a NACK in the middle of a frame burst
    errors_before = r.bank.chips[0].errors
    bad += loop.frames(5)
    nack = (r.bank.chips[0].errors - errors_before, r.bank.chips[0].last_errno)
    chips[0x41].reset()  # brownout between frames
    bad += loop.frames(30)
    brownout = (r.bank.reinits >= 2, chips[0x41].running())
    loop.sonar[0].stuck_high = True  # front echo stuck high
    loop.sonar[2].missing_echo = True  # left-rear echo never comes
    bad += loop.frames(50)
    sonar = (r.sonar_faults > 0, r.distances[0], r.distances[2], r.sonar_status[0], r.sonar_status[2])
    loop.sonar[0].stuck_high = False
    loop.sonar[2].missing_echo = False
    bad += loop.frames(50)
    r.robot.walk(1000, 0, 500)
    bad += loop.frames(100)
    return (boot, back, nack, brownout, sonar, r.distances[0] > 0, r.frames, r.held, bad, r.robot.mode)


def steady_frame_heap():
    """MicroPython only (gc.mem_alloc): (heap bytes 300 walking frames left allocated, frames, held,
    failed frames, mode)."""
    loop, _ = _standing_loop(frames=100)
    r = loop.r
    r.robot.walk(1200, 300, 1500)
    loop.frames(100)

    return (walking_heap(r), r.frames, r.held, r.bank.failed_frames, r.robot.mode)


def walking_heap(r, frames=300):
    """MicroPython only (gc.mem_alloc): heap bytes `frames` frames of the runner r leave allocated,
    after as many that are not counted."""

    def run(n):
        for _ in range(n):
            r.step()
            r.wait()

    return heap_bytes(run, frames)


def board_runs(board, n):
    """(frames, held, failed frames, sonar faults, unsafe outputs, mode) after n frames from stand_up."""
    loop, bad = _standing_loop(board, n)
    r = loop.r
    return (r.frames, r.held, r.bank.failed_frames, r.sonar_faults, bad, r.robot.mode)


def boot_frames(n):
    """The loop as the flashed image runs it: where main and hexapod.leg came from, the board, the
    counters, the unsafe outputs and the 18 widths after n frames from stand_up."""
    from hexapod import leg

    loop, bad = _standing_loop(frames=n)
    r = loop.r
    return (main.__file__, leg.__file__, main.BOARD, r.frames, r.held, r.robot.mode, bad, loop.widths())


def irq_sonar(frames):
    """(sonar split, the longest any step blocked (us), distances): main.build's echo timed by IRQs."""
    loop = Loop()
    loop.plug(0x40, 0x41)
    r = loop.build()
    blocked = 0
    for _ in range(frames):
        t0 = clock.now_us()
        r.step()
        blocked = max(blocked, clock.now_us() - t0)
        r.wait()
    return (r.sonars.ring.split, blocked, r.distances)


def run_frame_starts(idle_ms, frames):
    """Runner.run(frames) idle_ms after main.build (a boot's remaining work): each frame's start
    (us on the virtual clock, from run's call) and each frame's bursts' time, as the chips saw them."""
    loop = Loop()
    loop.plug(0x40, 0x41)
    r = loop.build()
    clock.advance_us(idle_ms * 1000)
    starts = []
    step = r.step

    def timed_step():
        starts.append(clock.now_us())
        return step()

    r.step = timed_step
    t0 = clock.now_us()
    r.run(frames)
    return [t - t0 for t in starts]
