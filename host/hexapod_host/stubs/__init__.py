"""Stand-ins for the boards' runtimes, on CPython and in the MicroPython VM.

micropython/      MicroPython's `machine` (_stub_clock, _stub_pins, _stub_i2c), the `micropython` shim,
                  the I2C bus, PCA9685 and HC-SR04 models and stub_board: a folder on sys.path and
                  MICROPYPATH, not a package, because the firmware imports `machine` by that bare name
                  and the VM's scripts (vm/, wall/rig.py) import the models beside it so.
circuitpython.py  CircuitPython's board, busio, digitalio, pulseio, supervisor and microcontroller
                  modules, on the same stub pins, bus model and virtual clock (CPython only).
busio.py          busio.I2C on the bus model, so Adafruit's libraries run against the chip models.
"""
