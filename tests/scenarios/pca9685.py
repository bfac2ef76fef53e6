"""drivers.pca9685 on two chip models as on the robot: 16 servos on 0x40 (3 % fast oscillator,
trimmed), 2 on 0x41; start-up, frames, counts, bad input, and faults on the PCA9685 side."""

import machine
from i2c_bus import I2CBus
from pca9685_model import PCA9685Model

from drivers.pca9685 import PCA9685, ServoBank, describe, servo_bank
from hexapod.servo import ServoMap

CMAP = [(0, k) for k in range(16)] + [(1, 0), (1, 1)]
MAPS = [ServoMap(min_us=900 + 10 * k, max_us=2100 - 10 * k) for k in range(18)]
LOW = [m.min_us for m in MAPS]
HIGH = [m.max_us for m in MAPS]


class Rig:
    """The bus, the models m0 (0x40) and m1 (0x41), and machine.I2C on the bus."""

    def __init__(self):
        self.bus = I2CBus()
        self.m0 = self.bus.attach(PCA9685Model(0x40, osc_hz=25750000))
        self.m1 = self.bus.attach(PCA9685Model(0x41))
        self.i2c = machine.I2C(0, bus=self.bus)

    def chips(self, **kw):
        c0 = PCA9685(self.i2c, 0x40, osc_hz=25750000, sleep_us=self.bus.sleep_us, **kw)
        c1 = PCA9685(self.i2c, 0x41, channels=2, sleep_us=self.bus.sleep_us, **kw)
        return c0, c1

    def bank(self, **kw):
        return ServoBank(list(self.chips(**kw)), CMAP, MAPS)

    def outputs(self):
        """The 18 servos' pulse widths (us) at the models' outputs."""
        return self.m0.pulses_us() + self.m1.pulses_us()[:2]

    def unsafe(self):
        """(servo, pulse ns) of every output neither off nor inside its map's min..max, give or take
        half a count (the chip's resolution: 4.9 us per count at 50 Hz)."""
        bad = []
        for k in range(18):
            m, ch = (self.m0, k) if k < 16 else (self.m1, k - 16)
            ns = m.pulse_ns(ch)
            half = (m.prescale() + 1) * 500000000 // m.clock_hz() + 1
            if ns and not MAPS[k].min_us * 1000 - half <= ns <= MAPS[k].max_us * 1000 + half:
                bad.append((k, ns))
        return bad

    def near(self, lo, hi, want):
        """Every output lo..hi-1 within 3 us of want's."""
        got = self.outputs()
        return all(abs(got[k] - want[k]) <= 3 for k in range(lo, hi))


def err(fn, *a, **kw):
    try:
        fn(*a, **kw)
        return ("ok", None)
    except ValueError as e:
        return ("ValueError", str(e))


# -- the driver ------------------------------------------------------------------------------


def start_up():
    """[offline, the driver's prescale, MODE1, MODE2, the chip's prescale, running, violations,
    0x41's prescale, bus transactions] of starting both chips."""
    r = Rig()
    r.bus.reset_stats()
    c0, _ = r.chips()
    m0 = r.m0
    return [
        c0.offline,
        c0.prescale,
        m0.regs[0],
        m0.regs[1],
        m0.prescale(),
        m0.running(),
        m0.violation_codes(),
        r.m1.prescale(),
        r.bus.transactions,
    ]


def one_frame(pulses):
    """[status, transactions, bytes, outputs, violations of each chip] of one frame of pulses."""
    r = Rig()
    b = r.bank(check_every=0)
    r.bus.reset_stats()
    st = b.write(pulses)
    return [st, r.bus.transactions, r.bus.bytes, r.outputs(), r.m0.violation_codes(), r.m1.violation_codes()]


def counts(oscs, widths):
    """[[osc Hz, prescale, [count of each width]]] of a driver at each oscillator (over 30 MHz: external)."""
    r = Rig()
    out = []
    for osc in oscs:
        c = PCA9685(r.i2c, 0x40, osc_hz=osc, sleep_us=r.bus.sleep_us, check_every=0, ext_clock=osc > 30000000)
        out.append([osc, c.prescale, [c.count(us) for us in widths]])
    return out


def stagger():
    """[[counts of each channel], widths us] of 16 servos at 1500 us staggered 200 us."""
    r = Rig()
    c0 = PCA9685(r.i2c, 0x40, osc_hz=25750000, sleep_us=r.bus.sleep_us, stagger_us=200, check_every=0)
    c0.write([1500] * 16)
    return [[list(r.m0.counts(ch)) for ch in range(16)], r.m0.pulses_us()]


def clamp(pulses):
    """[status, outputs, servos clamped] of a frame of pulses outside the maps."""
    r = Rig()
    b = r.bank(check_every=0)
    st = b.write(pulses)
    return [st, r.outputs(), b.clamped]


def relax_and_off():
    """[status of off(3), outputs, status of relax(), outputs, outputs after a new frame]."""
    r = Rig()
    b = r.bank(check_every=0)
    b.write([1500] * 18)
    st = b.off(3)
    a = r.outputs()
    st2 = b.relax()
    c = r.outputs()
    b.write([1500] * 18)
    return [st, a, st2, c, r.outputs()]


def _bad_calls(r, C, B):
    i2c = r.i2c
    s = r.bus.sleep_us
    return [
        lambda: PCA9685(i2c, 0x80, sleep_us=s),
        lambda: PCA9685(i2c, 0x70, sleep_us=s),
        lambda: PCA9685(i2c, "0x40", sleep_us=s),
        lambda: PCA9685(i2c, 0x40, osc_hz=25000000.0, sleep_us=s),
        lambda: PCA9685(i2c, 0x40, osc_hz=2500000, sleep_us=s),
        lambda: PCA9685(i2c, 0x40, osc_hz=40000000, sleep_us=s),
        lambda: PCA9685(i2c, 0x40, freq_hz=10, sleep_us=s),
        lambda: PCA9685(i2c, 0x40, freq_hz=50.0, sleep_us=s),
        lambda: PCA9685(i2c, 0x40, freq_hz=2000, sleep_us=s),
        lambda: PCA9685(i2c, 0x40, freq_hz=400, sleep_us=s),
        lambda: PCA9685(i2c, 0x40, freq_hz=1526, channels=1, sleep_us=s),
        lambda: PCA9685(i2c, 0x40, channels=0, sleep_us=s),
        lambda: PCA9685(i2c, 0x40, channels=17, sleep_us=s),
        lambda: PCA9685(i2c, 0x40, retries=-1, sleep_us=s),
        lambda: PCA9685(i2c, 0x40, retries=11, sleep_us=s),
        lambda: PCA9685(i2c, 0x40, check_every=-1, sleep_us=s),
        lambda: PCA9685(i2c, 0x40, stagger_us=-5, sleep_us=s),
        lambda: PCA9685(i2c, 0x40, stagger_us=1500, sleep_us=s),
        lambda: PCA9685(i2c, 0x40, stagger_us=10**9, sleep_us=s),
        lambda: C.stage(16, 1500),
        lambda: C.stage(-1, 1500),
        lambda: C.stage(0, 499),
        lambda: C.stage(0, 2501),
        lambda: C.stage(0, 1500.0),
        lambda: C.stage(0, None),
        lambda: C.stage_off(20),
        lambda: ServoBank([C], [(0, 0), (0, 0)], [ServoMap(), ServoMap()]),
        lambda: ServoBank([C], [(0, 0), (1, 0)], [ServoMap(), ServoMap()]),
        lambda: ServoBank([C], [(0, 0), (0, 16)], [ServoMap(), ServoMap()]),
        lambda: ServoBank([C], [(0, 0)], [ServoMap(), ServoMap()]),
        lambda: B.write([1500] * 17),
        lambda: B.write([1500, 1500.0]),
        lambda: B.write([1500, "1500"]),
        lambda: B.write([None, 1500]),
    ]


def bad_input():
    """[err() of each bad call, the staged frame unchanged, the chip's registers unchanged, the two
    outputs] after a good frame of 1200 and 1800 us."""
    r = Rig()
    C = PCA9685(r.i2c, 0x40, osc_hz=25750000, sleep_us=r.bus.sleep_us, check_every=0)
    B = ServoBank([C], [(0, 0), (0, 1)], [ServoMap(), ServoMap()])
    B.write([1200, 1800])
    frame = bytes(C._frame)
    regs = bytes(r.m0.regs)
    out = [err(call) for call in _bad_calls(r, C, B)]
    return [out, bytes(C._frame) == frame, bytes(r.m0.regs) == regs, r.m0.pulses_us()[:2]]


def frames_heap():
    """MicroPython only (gc.mem_alloc): [heap bytes of 30 frames (10 reading MODE1 back), violations]."""
    import gc

    r = Rig()
    b = r.bank(check_every=3, stagger_us=100)
    pulses = [1000 + 50 * k for k in range(18)]
    for _ in range(10):
        b.write(pulses)
    gc.collect()
    gc.disable()
    a = gc.mem_alloc()
    for _ in range(30):
        b.write(pulses)
    heap = gc.mem_alloc() - a
    gc.enable()
    return [heap, r.m0.violation_codes()]


def describe_all(statuses):
    return [describe(s) for s in statuses]


def external_clock():
    """[offline, MODE1, the chip's clock, prescale, three frames' statuses, channel 5's us, violations]
    of a driver on a 40 MHz external clock."""
    r = Rig()
    m0 = r.m0
    m0.ext_clock_hz = 40000000
    c = PCA9685(r.i2c, 0x40, osc_hz=40000000, ext_clock=True, sleep_us=r.bus.sleep_us, check_every=1)
    sts = [c.write([1500] * 16) for _ in range(3)]
    return [c.offline, m0.regs[0], m0.clock_hz(), c.prescale, sts, m0.pulse_us(5), m0.violation_codes()]


def nack_on(flavour):
    """[status of a frame with byte 20 NACKed, errors, last errno, the next frame's status] on
    machine.SoftI2C ("soft") or the rp2's machine.I2C ("rp2")."""
    r = Rig()
    if flavour == "soft":
        i2c = machine.SoftI2C(bus=r.bus)
    else:
        i2c = machine.I2C(0, bus=r.bus, port=flavour)
    c = PCA9685(i2c, 0x40, osc_hz=25750000, sleep_us=r.bus.sleep_us, check_every=0, retries=0)
    c.write([1500] * 16)
    r.bus.fault(0x40, "nack", byte=20)
    st = c.write([1000] * 16)
    return [st, c.errors, c.last_errno, c.write([1000] * 16)]


def board_layout():
    """servo_bank from a board's layout (servos 0-8 on 0x40, 9-17 on 0x41): [status, transactions,
    bytes, [channels per chip], the 18 outputs, err() kind of a table naming 0x42, 0x40's unused outputs]."""
    r = Rig()
    pca = {"pwm_hz": 50, "chips": ({"address": 0x40, "osc_hz": 25750000}, {"address": 0x41, "osc_hz": 25000000})}
    table = tuple((0x40 if k < 9 else 0x41, k % 9, ServoMap(min_us=600, max_us=2400)) for k in range(18))
    b = servo_bank(r.i2c, pca, table, sleep_us=r.bus.sleep_us, check_every=0)
    r.bus.reset_stats()
    st = b.write([1000 + 50 * k for k in range(18)])
    got = r.m0.pulses_us()[:9] + r.m1.pulses_us()[:9]
    wire = [r.bus.transactions, r.bus.bytes]
    bad = err(servo_bank, r.i2c, pca, table[:17] + ((0x42, 0, ServoMap()),), sleep_us=r.bus.sleep_us)
    return [st] + wire + [[c.channels for c in b.chips], got, bad[0], r.m0.pulses_us()[9:]]


# -- faults ----------------------------------------------------------------------------------


def nack_mid_frame():
    """[status, unsafe outputs, channels 0-2 new, 3-15 old, 0x41's new, the next status, all new,
    errors, errno] of a frame whose channel 3 OFF_H is NACKed (no retries)."""
    r = Rig()
    b = r.bank(check_every=0, retries=0)
    b.write(HIGH)
    # Channel 3's OFF_H is data byte 5 + 4*3 (the pointer is byte 1): its OFF_L arrives, OFF_H does not.
    r.bus.fault(0x40, "nack", byte=17)
    st = b.write(LOW)
    first = r.near(0, 3, LOW)
    rest = r.near(3, 16, HIGH)
    chip1 = r.near(16, 18, LOW)
    bad = r.unsafe()
    st2 = b.write(LOW)
    c0 = b.chips[0]
    return [st, bad, first, rest, chip1, st2, r.near(0, 18, LOW), c0.errors, c0.last_errno]


def nack_retried():
    """[status, outputs new, unsafe outputs, bus NACKs] of a frame NACKed twice with two retries."""
    r = Rig()
    b = r.bank(check_every=0, retries=2)
    b.write(HIGH)
    r.bus.fault(0x40, "nack", byte=17, count=2)
    st = b.write(LOW)
    return [st, r.near(0, 18, LOW), r.unsafe(), r.bus.nacks]


def timeouts():
    """[four frames' statuses with five timeouts on 0x41, its last errno, unsafe outputs, last frame out]."""
    r = Rig()
    b = r.bank(check_every=0, retries=1)
    r.bus.fault(0x41, "timeout", byte=4, count=5)
    sts = [b.write(LOW if i % 2 else HIGH) for i in range(4)]
    return [sts, b.chips[1].last_errno, r.unsafe(), r.near(0, 18, LOW)]


def brownout():
    """[20 frames' statuses with 0x40 reset before frame 7, unsafe outputs seen, resets seen, last frame
    out, MODE1, prescale]."""
    r = Rig()
    b = r.bank(check_every=5)
    sts = []
    bad = []
    for i in range(20):
        if i == 7:
            r.m0.reset()  # brownout: registers at defaults, SLEEP set, AI clear
        sts.append(b.write(HIGH if i % 2 else LOW))
        bad += r.unsafe()
    return [sts, bad, b.chips[0].resets_seen, r.near(0, 18, HIGH), r.m0.regs[0], r.m0.prescale()]


def reset_on_the_wire():
    """[status, unsafe outputs, frame out, resets seen] of a frame after a 'reset' fault on 0x41."""
    r = Rig()
    b = r.bank(check_every=1)
    b.write(LOW)
    r.bus.fault(0x41, "reset")
    st = b.write(HIGH)
    return [st, r.unsafe(), r.near(0, 18, HIGH), b.chips[1].resets_seen]


def unplugged_at_boot():
    """0x41 unplugged at boot, plugged back after six frames: [the twelve statuses, [offline, its two
    outputs, 0x40's out] between, unsafe outputs, all out, offline, the new chip's violations]."""
    r = Rig()
    r.bus.detach(0x41)
    b = r.bank(check_every=4)
    sts = []
    for _ in range(6):
        sts.append(b.write(HIGH))
    mid = [b.chips[1].offline, r.outputs()[16:], r.near(0, 16, HIGH)]
    r.bus.attach(PCA9685Model(0x41))
    r.m1 = r.bus.device(0x41)
    for _ in range(6):
        sts.append(b.write(LOW))
    return [sts, mid, r.unsafe(), r.near(0, 18, LOW), b.chips[1].offline, r.m1.violation_codes()]


def soak(frames=150, seed=12345):
    """Random NACKs, timeouts, resets and brownouts on either chip, random pulses: [unsafe outputs
    seen, statuses, the status after the faults stop, its outputs right, errors, clamped]."""
    r = Rig()
    state = [seed]

    def rnd(n):
        state[0] = (state[0] * 1103515245 + 12345) & 0x7FFFFFFF
        return (state[0] >> 8) % n

    b = r.bank(check_every=3, retries=1)
    sts = []
    bad = []
    for _ in range(frames):
        f = rnd(12)
        addr = 0x40 if rnd(3) else 0x41
        if f == 0:
            r.bus.fault(addr, "nack", byte=rnd(70), count=1 + rnd(3))
        elif f == 1:
            r.bus.fault(addr, "timeout", byte=rnd(70))
        elif f == 2:
            r.bus.fault(addr, "reset")
        elif f == 3:
            (r.m0 if addr == 0x40 else r.m1).reset()
        pulses = [300 + rnd(2500) for _ in range(18)]  # some far outside every calibrated range
        sts.append(b.write(pulses))
        bad += r.unsafe()
    r.bus.clear_faults()
    for _ in range(4):
        last = b.write(LOW)
    errors = b.chips[0].errors + b.chips[1].errors
    return [bad, sts, last, r.near(0, 18, LOW), errors, b.clamped]


def sleep_wake_without_restart():
    """[[running, channel 0's us] after someone else's sleep and wake, three statuses, running, out, unsafe]."""
    r = Rig()
    b = r.bank(check_every=2)
    b.write(LOW)
    r.i2c.writeto_mem(0x40, 0, b"\x30")
    r.i2c.writeto_mem(0x40, 0, b"\x20")
    stopped = [r.m0.running(), r.m0.pulse_us(0)]
    sts = [b.write(LOW) for _ in range(3)]
    return [stopped, sts, r.m0.running(), r.near(0, 18, LOW), r.unsafe()]
