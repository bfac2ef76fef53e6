# Runs on a MicroPython board (the emulated Pico) or in the VM: imports the modules named in MODULES
# one by one, leaves first, and prints one line per module: name, bytes allocated while it imported
# with the collector off (-1: that ran out of heap, then imported with the collector on), bytes that
# stay after a collection. The host replaces the MODULES line before running it.
import gc

MODULES = []

for name in MODULES:
    gc.collect()
    a0 = gc.mem_alloc()
    gc.disable()
    try:
        __import__(name)
        a1 = gc.mem_alloc() - a0
    except MemoryError:
        a1 = -1
    gc.enable()
    if a1 < 0:
        gc.collect()
        __import__(name)
    gc.collect()
    print("heap", name, a1, gc.mem_alloc() - a0)
