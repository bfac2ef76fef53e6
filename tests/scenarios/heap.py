"""Heap use in the MicroPython VM (gc.mem_alloc): what a piece of code leaves allocated."""

import gc


def heap_bytes(fn, arg):
    """fn(arg) once to warm up, then again with the collector off: the heap bytes that second
    run left allocated. Locals only: a new global would grow a module dict inside the measurement."""
    fn(arg)
    gc.collect()
    gc.disable()
    before = gc.mem_alloc()
    fn(arg)
    after = gc.mem_alloc()
    gc.enable()
    return after - before
