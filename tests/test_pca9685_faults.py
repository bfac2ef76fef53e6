"""Faults on the PCA9685 side: the loop keeps running, the fault is reported, and no channel ever
outputs a pulse outside its servo's calibrated range (read from the chip model's outputs)."""

try:  # tests/ is a package on main, a plain directory before
    from .test_pca9685_driver import PRE as DRIVER_PRE
except ImportError:
    from test_pca9685_driver import PRE as DRIVER_PRE

PRE = (
    DRIVER_PRE
    + """
def unsafe():
    # (servo, pulse_ns) of every output that is neither off nor inside min..max, give or take
    # half a count (the chip's resolution: 4.9 us per count at 50 Hz).
    bad = []
    for k in range(18):
        m, ch = (m0, k) if k < 16 else (m1, k - 16)
        ns = m.pulse_ns(ch)
        half = (m.prescale() + 1) * 500000000 // m.clock_hz() + 1
        if ns and not MAPS[k].min_us * 1000 - half <= ns <= MAPS[k].max_us * 1000 + half:
            bad.append((k, ns))
    return bad
LOW = [MAPS[k].min_us for k in range(18)]
HIGH = [MAPS[k].max_us for k in range(18)]
def near(got, want):
    return all(abs(g - w) <= 3 for g, w in zip(got, want))
"""
)


def test_nack_mid_frame_never_outputs_half_a_channel(rt):
    src = (
        PRE
        + """
b = bank(check_every=0, retries=0)
b.write(HIGH)
# Channel 3's OFF_H is data byte 5 + 4*3 (the pointer is byte 1): its OFF_L arrives, OFF_H does not.
bus.fault(0x40, 'nack', byte=17)
st = b.write(LOW)
after = outputs()
bad = unsafe()
st2 = b.write(LOW)
print([st, bad, near(after[:3], LOW[:3]), near(after[3:16], HIGH[3:16]), near(after[16:], LOW[16:]),
       st2, near(outputs(), LOW), b.chips[0].errors, b.chips[0].last_errno])
"""
    )
    st, bad, first_new, rest_old, chip1_new, st2, healed, errors, errno = rt.value(src)
    assert st == 2  # FAILED: no retries allowed
    assert bad == []
    assert first_new and rest_old and chip1_new  # channels 0-2 complete, 3-15 kept the old frame
    assert st2 == 0 and healed
    assert (errors, errno) == (1, 19)


def test_nack_is_retried_within_the_frame(rt):
    src = (
        PRE
        + """
b = bank(check_every=0, retries=2)
b.write(HIGH)
bus.fault(0x40, 'nack', byte=17, count=2)
st = b.write(LOW)
print([st, near(outputs(), LOW), unsafe(), bus.nacks])
"""
    )
    assert rt.value(src) == [1, True, [], 2]  # RETRIED, the third attempt went through


def test_timeout_reported_as_etimedout(rt):
    src = (
        PRE
        + """
b = bank(check_every=0, retries=1)
bus.fault(0x41, 'timeout', byte=4, count=5)
sts = [b.write(LOW if i % 2 else HIGH) for i in range(4)]
print([sts, b.chips[1].last_errno, unsafe(), near(outputs(), LOW)])
"""
    )
    sts, errno, bad, final = rt.value(src)
    assert sts == [2, 2, 1, 0]  # 2 + 2 attempts fail, the 5th hangs too, the 6th gets through
    assert errno == 110
    assert bad == []
    assert final


def test_brownout_between_frames_is_found_and_healed(rt):
    src = (
        PRE
        + """
b = bank(check_every=5)
sts = []
bad = []
for i in range(20):
    if i == 7:
        m0.reset()  # brownout: registers at defaults, SLEEP set, AI clear
    sts.append(b.write(HIGH if i % 2 else LOW))
    bad += unsafe()
print([sts, bad, b.chips[0].resets_seen, near(outputs(), HIGH), m0.regs[0], m0.prescale()])
"""
    )
    sts, bad, seen, final, mode1, prescale = rt.value(src)
    assert bad == []
    assert seen == 1
    assert 4 in sts[7:12]  # REINIT within check_every frames of the reset
    assert all(s in (0, 4) for s in sts)
    assert final and mode1 == 0x20 and prescale == 125


def test_reset_fault_on_the_wire_mid_run(rt):
    src = (
        PRE
        + """
b = bank(check_every=1)
b.write(LOW)
bus.fault(0x41, 'reset')
st = b.write(HIGH)
print([st, unsafe(), near(outputs(), HIGH), b.chips[1].resets_seen])
"""
    )
    # The chip resets just before its MODE1 read-back: found at once, re-initialised, frame sent.
    assert rt.value(src) == [4, [], True, 1]


def test_unplugged_chip_at_boot_loop_runs_and_it_comes_back(rt):
    src = (
        PRE
        + """
spare = bus.detach(0x41)
b = bank(check_every=4)
sts = []
for i in range(6):
    sts.append(b.write(HIGH))
mid = [b.chips[1].offline, outputs()[16:], near(outputs()[:16], HIGH[:16])]
bus.attach(PCA9685Model(0x41))
m1 = bus.device(0x41)
for i in range(6):
    sts.append(b.write(LOW))
print([sts, mid, unsafe(), near(outputs(), LOW), b.chips[1].offline, m1.violation_codes()])
"""
    )
    sts, mid, bad, final, offline, codes = rt.value(src)
    assert mid == [True, [0, 0], True]  # chip 0 drives its servos; chip 1's are simply not driven
    assert all(s & 8 for s in sts[:6])  # OFFLINE reported every frame while unplugged
    assert 4 in sts[6:]  # REINIT once plugged in
    assert sts[-1] == 0
    assert bad == [] and final and offline is False and codes == []


SOAK = (
    PRE
    + """
seed = 12345
def rnd(n):
    global seed
    seed = (seed * 1103515245 + 12345) & 0x7FFFFFFF
    return (seed >> 8) % n
b = bank(check_every=3, retries=1)
sts = []
bad = []
for i in range(150):
    f = rnd(12)
    addr = 0x40 if rnd(3) else 0x41
    if f == 0:
        bus.fault(addr, 'nack', byte=rnd(70), count=1 + rnd(3))
    elif f == 1:
        bus.fault(addr, 'timeout', byte=rnd(70))
    elif f == 2:
        bus.fault(addr, 'reset')
    elif f == 3:
        (m0 if addr == 0x40 else m1).reset()
    pulses = [300 + rnd(2500) for _ in range(18)]  # some far outside every calibrated range
    sts.append(b.write(pulses))
    bad += unsafe()
bus.clear_faults()
for _ in range(4):
    last = b.write(LOW)
print([bad, sts, last, near(outputs(), LOW), b.chips[0].errors + b.chips[1].errors, b.clamped])
"""
)


def test_random_fault_soak_is_safe_and_identical_in_both_runtimes(both_runtimes):
    import ast

    cp, mp = both_runtimes(SOAK)
    assert cp == mp  # same statuses, errors and outputs, frame by frame
    bad, sts, last, final, errors, clamped = ast.literal_eval(cp.strip().splitlines()[-1])
    assert bad == []
    assert last == 0 and final
    assert errors > 10 and clamped > 100
    assert any(s & 1 for s in sts) and any(s & 2 for s in sts) and any(s & 4 for s in sts)


def test_chip_put_to_sleep_and_woken_without_restart_is_recovered(rt):
    """Someone else's sleep/wake leaves RESTART pending and the outputs stopped: the read-back sees it."""
    src = (
        PRE
        + """
b = bank(check_every=2)
b.write(LOW)
i2c.writeto_mem(0x40, 0, b'\\x30')
i2c.writeto_mem(0x40, 0, b'\\x20')
stopped = [m0.running(), m0.pulse_us(0)]
sts = [b.write(LOW) for _ in range(3)]
print([stopped, sts, m0.running(), near(outputs(), LOW), unsafe()])
"""
    )
    stopped, sts, running, final, bad = rt.value(src)
    assert stopped == [False, 0]
    assert 4 in sts and running and final and bad == []
