"""A pretend MicroPython board on a pseudo-terminal, for `hexapod flash` tests with the real mpremote.

Run as a script: `python fake_raw_repl.py ROOT [--quota BYTES] [--impl NAME] [--silent]`; prints the pty
path, then serves MicroPython's raw REPL (Ctrl-A, Ctrl-D soft reboot, code ended by Ctrl-D answered
`OK`, output, Ctrl-D, error text, Ctrl-D, `>`; raw paste with flow control).
The code mpremote sends runs here under CPython in a namespace whose `open`, `os`, `sys` and `machine`
stand in for the board's: files live under ROOT, a write past the quota raises ENOSPC like a full
flash, `sys.implementation.name` is --impl, `sys.implementation._mpy` is --mpy, `machine.reset()` is
logged to ROOT/../resets.
--silent answers nothing (a board that is not running MicroPython's REPL).
"""

import argparse
import builtins
import contextlib
import errno
import io
import os
import sys
import traceback
import tty
import types

BLOCK = 4096


def used_bytes(root):
    total = 0
    for d, _, files in os.walk(root):
        for f in files:
            total += (os.path.getsize(os.path.join(d, f)) + BLOCK - 1) // BLOCK * BLOCK
    return total


class QuotaFile(io.FileIO):
    """A file whose writes fail with ENOSPC once the board's flash would be full."""

    quota = None
    root = "."

    def write(self, data):
        if self.quota is not None and used_bytes(self.root) + len(data) + BLOCK > self.quota:
            raise OSError(errno.ENOSPC, "ENOSPC")
        return super().write(data)


def namespace(root, quota, impl, resets, mpy=4870):
    fake_os = types.ModuleType("os")
    for name in ("stat", "remove", "rename", "mkdir", "rmdir", "listdir", "getcwd", "chdir"):
        setattr(fake_os, name, getattr(os, name))

    def statvfs(path):
        free = (quota - used_bytes(root)) // BLOCK if quota is not None else 1 << 20
        return (BLOCK, BLOCK, (quota or 1 << 32) // BLOCK, max(free, 0), max(free, 0), 0, 0, 0, 0, 255)

    def ilistdir(path="."):
        for n in os.listdir(path or "."):
            st = os.stat(os.path.join(path or ".", n))
            yield (n, 0x4000 if os.path.isdir(os.path.join(path or ".", n)) else 0x8000, 0, st.st_size)

    fake_os.statvfs = statvfs
    fake_os.ilistdir = ilistdir
    fake_sys = types.SimpleNamespace(implementation=types.SimpleNamespace(name=impl, _mpy=mpy), platform="rp2")
    machine = types.SimpleNamespace(reset=lambda: resets.append(1))
    time_mod = types.SimpleNamespace(sleep_ms=lambda ms: None)
    modules = {"os": fake_os, "sys": fake_sys, "machine": machine, "time": time_mod}
    real_import = builtins.__import__

    def board_import(name, *args, **kw):
        return modules[name] if name in modules else real_import(name, *args, **kw)

    def board_open(path, mode="r", *args, **kw):
        if "w" in mode or "a" in mode:
            f = QuotaFile(path, mode.replace("b", "").replace("t", "")[0])
            return f if "b" in mode else io.TextIOWrapper(f)
        return open(path, mode, *args, **kw)

    fake_builtins = dict(vars(builtins), __import__=board_import, open=board_open)
    return {"__builtins__": fake_builtins, "__name__": "__main__"}


WINDOW = 4096  # raw-paste flow control: the host may send this many bytes per \x01 it receives


def serve(fd, root, quota, impl, silent, resets, mpy):
    raw, code, ns, esc = False, b"", namespace(root, quota, impl, resets, mpy), b""
    paste = None  # bytes received in the current raw-paste window, None outside raw paste

    def out(b):
        os.write(fd, b)

    while True:
        try:
            data = os.read(fd, 4096)
        except OSError:
            return
        if not data:
            return
        if silent:
            continue
        for byte in data:
            c = bytes([byte])
            if esc:
                esc += c
                if len(esc) == 3:  # \x05 A \x01: raw paste, window WINDOW bytes
                    out(b"R\x01" + WINDOW.to_bytes(2, "little"))
                    esc, paste = b"", 0
                continue
            if paste is not None:
                if c != b"\x04":
                    code += c
                    paste += 1
                    if paste == WINDOW:
                        out(b"\x01")
                        paste = 0
                    continue
                paste = None
                out(b"\x04")
                ns = run(code, ns, root, resets, out, b"")
                code = b""
                continue
            if not raw:
                if c == b"\x01":
                    raw, code = True, b""
                    out(b"raw REPL; CTRL-B to exit\r\n>")
                elif c == b"\x03":
                    out(b"\r\n>>> ")
                continue
            if c == b"\x05" and not code:
                esc = c
            elif c == b"\x02":
                raw = False
                out(b"\r\nMicroPython (fake)\r\n>>> ")
            elif c == b"\x03":
                code = b""
            elif c == b"\x01":
                code = b""
                out(b"raw REPL; CTRL-B to exit\r\n>")
            elif c == b"\x04" and not code:  # soft reboot
                ns = namespace(root, quota, impl, resets, mpy)
                out(b"OK\r\nMPY: soft reboot\r\nraw REPL; CTRL-B to exit\r\n>")
            elif c == b"\x04":
                ns = run(code, ns, root, resets, out, b"OK")
                code = b""
            else:
                code += c


def run(code, ns, root, resets, out, ack):
    """Execute one raw-REPL command and answer as the board does; returns the namespace."""
    out(ack)
    stdout, err = io.StringIO(), ""
    try:
        with contextlib.redirect_stdout(stdout):
            exec(compile(code.decode(), "<stdin>", "exec"), ns)
    except BaseException as e:  # noqa: BLE001  (the board prints any exception)
        tb = traceback.format_exception_only(type(e), e)[-1].strip()
        if isinstance(e, OSError) and e.errno:
            tb = "OSError: [Errno %d] %s" % (e.errno, errno.errorcode.get(e.errno, ""))
        err = 'Traceback (most recent call last):\r\n  File "<stdin>", line 1, in <module>\r\n%s\r\n' % tb
    if resets:
        with open(os.path.join(root, "..", "resets"), "a") as f:
            f.write("reset\n")
        resets.clear()
    out(stdout.getvalue().replace("\n", "\r\n").encode() + b"\x04" + err.encode() + b"\x04>")
    return ns


def main():
    p = argparse.ArgumentParser()
    p.add_argument("root")
    p.add_argument("--quota", type=int)
    p.add_argument("--impl", default="micropython")
    p.add_argument("--silent", action="store_true")
    # sys.implementation._mpy: version 6 | (arch << 2 | sub-version 3) << 8; default armv6m (a Pico)
    p.add_argument("--mpy", type=int, default=6 | (4 << 2 | 3) << 8)
    a = p.parse_args()
    os.makedirs(a.root, exist_ok=True)
    os.chdir(a.root)
    QuotaFile.quota, QuotaFile.root = a.quota, os.path.abspath(a.root)
    master, slave = os.openpty()
    tty.setraw(slave)
    tty.setraw(master)
    print(os.ttyname(slave), flush=True)
    serve(master, os.path.abspath("."), a.quota, a.impl, a.silent, [], a.mpy)


if __name__ == "__main__":
    sys.exit(main())
