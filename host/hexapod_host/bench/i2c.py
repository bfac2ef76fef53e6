"""`hexapod bench i2c`: wire cost of one 18-servo frame (two PCA9685) at 400 kHz, in one run.

  ours              drivers.pca9685 in the MicroPython VM (and its heap bytes per frame)
  adafruit_servokit two ServoKit(channels=16) on CPython through the fake busio.I2C
  physical_minimum  one transaction per chip starting at LED0_OFF_L (the first ON bytes are the
                    only ones a frame can skip: the registers are ON_L ON_H OFF_L OFF_H per
                    channel and auto-increment cannot jump), counted on the same bus model
All three are counted by i2c_bus.I2CBus: bits = START + 9 per byte + STOP, plus tBUF per STOP.
"""

import json
import os

from hexapod_host import VM_DIR, mpvm
from hexapod_host.stubs import busio as fakes_busio

VM_SCRIPT = os.path.join(VM_DIR, "bench_i2c.py")
FREQ = 400000
OSC = {0x40: 25_750_000, 0x41: 25_000_000}  # chip 0x40 runs 3 % fast; both trimmed
CMAP = [(0, k) for k in range(16)] + [(1, 0), (1, 1)]
PULSES = [1000 + 50 * k for k in range(18)]


def _figures(stats, frames=1):
    return {
        "transactions": stats["transactions"] / frames,
        "bytes": stats["bytes"] / frames,
        "bits": stats["bits"] / frames,
        "bus_us": stats["time_ns"] / frames / 1000,
    }


def new_bus():
    """A bus model with the two PCA9685 models of OSC: (bus, {address: model})."""
    # Bare names: the models sit with the MicroPython stubs, where the VM (vm/bench_i2c.py) imports them so.
    from i2c_bus import I2CBus
    from pca9685_model import PCA9685Model

    bus = I2CBus()
    return bus, {a: bus.attach(PCA9685Model(a, osc_hz=osc)) for a, osc in OSC.items()}


def servokit_servos(bus, i2c):
    """The 18 servos, CMAP order, of two adafruit_servokit.ServoKit(channels=16) on i2c (a fake
    busio.I2C on bus), each set so that angle = pulse_us - 500 (500..2500 us over 2000 degrees)."""
    fakes_busio.ensure_board()
    import adafruit_servokit

    with fakes_busio.model_time(bus):
        kits = [adafruit_servokit.ServoKit(channels=16, i2c=i2c, address=a, reference_clock_speed=OSC[a]) for a in OSC]
    servos = []
    for c, ch in CMAP:
        s = kits[c].servo[ch]
        s.set_pulse_width_range(500, 2500)
        s.actuation_range = 2000
        servos.append(s)
    return servos


def servokit_frame():
    """Wire figures of one steady-state 18-servo frame written through adafruit_servokit."""
    bus, _ = new_bus()
    servos = servokit_servos(bus, fakes_busio.I2C(bus, frequency=FREQ))
    for s, p in zip(servos, PULSES, strict=True):  # first frame: warm-up
        s.angle = p - 500
    bus.reset_stats()
    for s, p in zip(servos, PULSES, strict=True):
        s.angle = p - 500
    return _figures(bus.stats())


def physical_minimum():
    """One burst per chip from LED0_OFF_L through the last servo channel's OFF_H."""
    import machine  # the stub machine, by the name the firmware imports it

    bus, _ = new_bus()
    i2c = machine.I2C(0, FREQ, bus=bus)
    bus.reset_stats()
    for addr, n in ((0x40, 16), (0x41, 2)):
        i2c.writeto(addr, bytearray([0x08]) + bytearray(4 * n - 2))
    return _figures(bus.stats())


def bench_i2c(args):
    """Per 18-servo frame: ours (VM), adafruit_servokit (CPython), the physical minimum."""
    out = mpvm.run(script=VM_SCRIPT, heapsize="256k")
    vm = json.loads(out.strip().splitlines()[-1])
    return {
        "bench": "i2c",
        "freq_hz": FREQ,
        "servos": 18,
        "chips": 2,
        "ours": vm["frame"],
        "ours_with_mode1_readback": dict(vm["frame_with_readback"], check_every=vm["check_every"]),
        "ours_heap_bytes_per_frame": vm["heap_bytes_per_frame"],
        "ours_vm_us_per_frame": vm["vm_us_per_frame"],
        "adafruit_servokit": servokit_frame(),
        "physical_minimum": physical_minimum(),
    }
