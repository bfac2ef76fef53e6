"""PCA9685.stage's count and register bytes as viper machine code: the same integer steps as
PCA9685.count, about 5x faster on a Pico than the native emitter. Imported by pca9685.py only on
MicroPython ports with viper; CPython and CircuitPython use the plain path (same results: tests)."""

import sys

import micropython

if sys.implementation.name != "micropython":
    raise ImportError("viper code runs on MicroPython only")


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
