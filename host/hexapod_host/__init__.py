"""Host side of hexapod: runs the board's integer core under CPython.

Importing this package puts the firmware, the board files and the CPython shims on
sys.path, so `import hexapod` (the core) and `import drivers.pca9685` resolve to the
very files that go onto a board.
"""

import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
FIRMWARE = os.path.join(ROOT, "firmware")
BOARDS = os.path.join(ROOT, "boards")
VM_DIR = os.path.join(ROOT, "host", "hexapod_host", "vm")  # the scripts run inside the MicroPython VM
# The MicroPython stubs: a folder, not a package, since the firmware imports `machine` by its bare name.
STUBS = os.path.join(ROOT, "host", "hexapod_host", "stubs", "micropython")

# Bare names, as on the board: firmware/ is its root, boards/ and robots/ sit beside hexapod/ there.
for _path in (STUBS, FIRMWARE, ROOT):
    if _path not in sys.path:
        sys.path.insert(0, _path)
