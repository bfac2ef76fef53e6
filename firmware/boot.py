"""CircuitPython boot.py: make the flash writable for code.py, so `save` can store the servo
calibration (docs/console.md).

Trade-off: while code can write, the PC sees the CIRCUITPY drive read-only (one writer at a
time, or the FAT gets corrupted). To edit files over USB again, hold the BOOT_PIN low (button
to GND) while resetting: the drive is then writable from the PC and `save` answers
`err save: the filesystem is read-only`, losing nothing. Without this file the same holds.
"""

import board
import digitalio
import storage

BOOT_PIN = "A2"  # a free pin on the Feather RP2040 (boards/feather_rp2040.py leaves it unused)

pin = digitalio.DigitalInOut(getattr(board, BOOT_PIN))
pin.switch_to_input(pull=digitalio.Pull.UP)
if pin.value:  # not held low: code gets the filesystem
    storage.remount("/", readonly=False)
pin.deinit()
