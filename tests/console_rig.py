"""The console tests' pytest side. The console bench itself (the pico board's loop on the stub
machine with a console on a BufferReader) is tests/scenarios/console_rig.py, run on CPython and in
the MicroPython VM."""

import pytest


@pytest.fixture(autouse=True)
def clean_stubs():
    """The CPython runs share this process's stub modules: leave no bus, chip or wire behind."""
    yield
    import _stub_clock
    import _stub_i2c
    import _stub_pins

    _stub_i2c.reset()
    _stub_pins.reset()
    _stub_clock.reset(0)
