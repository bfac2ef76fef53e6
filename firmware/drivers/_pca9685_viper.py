"""PCA9685.stage's count and register bytes as viper machine code: the same integer steps as
PCA9685.count, about 5x faster on a Pico than the native emitter (docs/viper.md lists every viper
twin). Imported by pca9685.py only on MicroPython ports with viper; CPython and CircuitPython use
the plain path (same results: tests/test_pca9685_viper.py)."""

import micropython


@micropython.viper
def put(frame, params, channel: int, pulse_us: int):
    """frame[1 + 4 channel:] = ON and OFF counts of pulse_us (us) on channel; params: array("i")
    khz, rem, den, den1000, den2000 (PCA9685._set_prescale), then each channel's ON count."""
    f = ptr8(frame)  # noqa: F821 (a viper built-in)
    p = ptr32(params)  # noqa: F821 (a viper built-in)
    den = p[2]
    a = pulse_us * p[0]  # <= 2500 * 50000: every step below stays under 2**31
    q = a // den
    on = p[5 + channel]
    off = on + q + (2 * (1000 * (a - q * den) + pulse_us * p[1]) + p[3]) // p[4]
    i = 1 + 4 * channel
    f[i] = on & 0xFF
    f[i + 1] = on >> 8
    f[i + 2] = off & 0xFF
    f[i + 3] = off >> 8


_TRUE = True  # inside viper code True and False are native values, not the objects
_FALSE = False


@micropython.viper
def stage_all(pulses, maps, tab, bufs) -> int:
    """ServoBank.write's staging in one call: pulses[k] (us; 0 full OFF) into maps[k]'s
    min_us..max_us, then put()'s bytes. tab: array("i"): 3 words of scratch per servo, then per
    chip its servo count and (servo, channel) pairs; bufs: each chip's frame and params. Returns
    how many pulses the limits caught, or -1 with nothing staged when the plain path must run (a
    pulse that is a bool or whose limit lies outside 500..2500 us); a pulse that is not an int
    raises TypeError (or OverflowError) before anything is staged."""
    t = ptr32(tab)  # noqa: F821
    n = int(len(pulses))
    k = 0
    while k < n:  # read and check everything before staging any of it
        p = int(pulses[k])
        if 0 <= p <= 1:
            x = pulses[k]
            if x is _TRUE or x is _FALSE:  # int() took them as 1 or 0
                return -1
        cal = ptr32(maps[k].cal)  # noqa: F821 (hexapod.servo.ServoMap's words: one lookup, not two properties)
        lo = cal[3]
        hi = cal[4]
        if lo < 500 or hi > 2500:
            return -1
        t[3 * k] = p
        t[3 * k + 1] = lo
        t[3 * k + 2] = hi
        k += 1
    clamped = 0
    j = 3 * n
    c = 0
    nchips = int(len(bufs)) >> 1
    while c < nchips:
        f = ptr8(bufs[2 * c])  # noqa: F821
        pp = ptr32(bufs[2 * c + 1])  # noqa: F821
        count = t[j]
        j += 1
        while count > 0:
            k = t[j]
            channel = t[j + 1]
            j += 2
            count -= 1
            i = 1 + 4 * channel
            p = t[3 * k]
            if p == 0:
                f[i] = 0
                f[i + 1] = 0
                f[i + 2] = 0
                f[i + 3] = 0x10  # full OFF
                continue
            q = p
            if q < t[3 * k + 1]:
                q = t[3 * k + 1]
            elif q > t[3 * k + 2]:
                q = t[3 * k + 2]
            if q != p:
                clamped += 1
            # put()'s steps written out: a viper call per servo would cost more than all of this
            den = pp[2]
            a = q * pp[0]
            d = a // den
            on = pp[5 + channel]
            off = on + d + (2 * (1000 * (a - d * den) + q * pp[1]) + pp[3]) // pp[4]
            f[i] = on & 0xFF
            f[i + 1] = on >> 8
            f[i + 2] = off & 0xFF
            f[i + 3] = off >> 8
        c += 1
    return clamped
