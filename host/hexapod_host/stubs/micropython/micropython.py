"""CPython stand-in for MicroPython's built-in `micropython` module.

The one home of every CPython shim the firmware needs. Inside the MicroPython VM the
built-in module wins over this file, so it is never used there.
"""


def const(value):
    """Return value unchanged; MicroPython folds it at compile time."""
    return value


def native(func):
    """Emitter decorator: a no-op on CPython."""
    return func


def viper(func):
    """Emitter decorator: a no-op on CPython (viper code needs its own equivalence test)."""
    return func


def schedule(func, arg):
    """Run func(arg) at once; CPython has no hard interrupts to defer from."""
    func(arg)


def alloc_emergency_exception_buf(size):
    """Nothing to reserve on CPython."""


def mem_info(*_args):
    """Nothing to report on CPython."""


def opt_level(*_args):
    return 0
