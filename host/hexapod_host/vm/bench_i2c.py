# Runs inside the MicroPython VM: our PCA9685 driver sending 18-servo frames to two chip models
# over the stub machine.I2C. Prints one JSON line: wire figures per frame (burst only, and with
# the MODE1 read-back every check_every frames averaged in), heap bytes per frame, VM time.
import gc
import json
import time

import machine
from i2c_bus import I2CBus
from pca9685_model import PCA9685Model

from drivers.pca9685 import PCA9685, ServoBank
from hexapod.servo import ServoMap

FREQ = 400000
CHECK_EVERY = 10
CMAP = [(0, k) for k in range(16)] + [(1, 0), (1, 1)]


def rig(check_every):
    bus = I2CBus()
    bus.attach(PCA9685Model(0x40, osc_hz=25750000))
    bus.attach(PCA9685Model(0x41))
    i2c = machine.I2C(0, FREQ, bus=bus)
    chips = [
        PCA9685(i2c, 0x40, osc_hz=25750000, sleep_us=bus.sleep_us, check_every=check_every),
        PCA9685(i2c, 0x41, channels=2, sleep_us=bus.sleep_us, check_every=check_every),
    ]
    return bus, ServoBank(chips, CMAP, [ServoMap() for _ in range(18)])


def per_frame(bus, bank, pulses, frames):
    for _ in range(frames):  # settle the read-back phase
        bank.write(pulses)
    bus.reset_stats()
    for _ in range(frames):
        bank.write(pulses)
    s = bus.stats()
    return {
        "transactions": s["transactions"] / frames,
        "bytes": s["bytes"] / frames,
        "bits": s["bits"] / frames,
        "bus_us": s["time_ns"] / frames / 1000,
    }


def main(frames=100):
    pulses = [1000 + 50 * k for k in range(18)]
    bus, bank = rig(0)
    burst = per_frame(bus, bank, pulses, 1)
    bus, bank = rig(CHECK_EVERY)
    with_check = per_frame(bus, bank, pulses, CHECK_EVERY * 10)
    for _ in range(CHECK_EVERY * 2):
        bank.write(pulses)
    gc.collect()
    gc.disable()
    before = gc.mem_alloc()
    for _ in range(frames):
        bank.write(pulses)
    heap = gc.mem_alloc() - before
    gc.enable()
    gc.collect()
    t0 = time.ticks_us()
    for _ in range(frames):
        bank.write(pulses)
    vm_us = time.ticks_diff(time.ticks_us(), t0) / frames
    print(
        json.dumps(
            {
                "runtime": "micropython",
                "freq_hz": FREQ,
                "frame": burst,
                "frame_with_readback": with_check,
                "check_every": CHECK_EVERY,
                "heap_bytes_per_frame": heap / frames,
                "vm_us_per_frame": round(vm_us, 1),
            }
        )
    )


main()
