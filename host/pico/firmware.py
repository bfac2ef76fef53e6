#!/usr/bin/env python3
"""Build the MicroPython RPI_PICO image the emulated Pico runs, from Debian's packages only.

    python3 host/pico/firmware.py [--out build/pico-firmware] [--jobs N]

Sources (Debian 13 "trixie", fetched through apt with a private sources list, so the system's apt
set-up is untouched): the source packages `micropython` (orig tarball: ports/rp2, its lib/ submodule
folders empty), `pico-sdk` and `mbedtls`, and the binary package `tinyusb-source` (its
/usr/src/tinyusb). Every archive's SHA-256 is checked against the signed Debian index apt read
(and against the .dsc where Debian serves one). Toolchain: this machine's Debian
`gcc-arm-none-eabi` with newlib and `cmake` (installed through apt-get when missing and we are root).

The port is built with pico-sdk's float, double, memory and bit operations taken from the compiler
(`pico_set_*_implementation(firmware compiler)`) instead of the RP2040's ROM, so that the image looks
up only the boot and flash functions our own bootrom (bootrom.mjs) serves. The frozen manifest keeps
the port's `modules` and `asyncio` (no micropython-lib in Debian: onewire, ds18x20, dht and neopixel
are not frozen). Its linker script keeps libgcc and libm in flash (patch_linker: they would take ~33 KB
of the heap in RAM).

Writes OUT/firmware.bin (flat, for 0x10000000), OUT/firmware.elf and OUT/provenance.json (package
names, versions, sha256 of each archive, compiler, options). Nothing here is committed: OUT is
git-ignored. Exit 0 when the image exists afterwards; 1 with one line naming what is missing.
"""

import argparse
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import tarfile
import time
import urllib.parse
import urllib.request

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
DEFAULT_OUT = os.path.join(ROOT, "build", "pico-firmware")
SUITE = "trixie"
MIRROR = "http://deb.debian.org/debian"
KEYRING = "/usr/share/keyrings/debian-archive-keyring.gpg"
SOURCES = ("micropython", "pico-sdk", "mbedtls")
BINARIES = ("tinyusb-source",)
TOOLS = {"arm-none-eabi-gcc": "gcc-arm-none-eabi libnewlib-arm-none-eabi", "cmake": "cmake", "make": "make"}
# What the port's CMakeLists gets instead of its ROM-backed float: the SDK's implementations from the
# compiler (libgcc / newlib), so the bootrom needs no float, double, memory or bit functions.
IMPLEMENTATIONS = ("float", "double", "mem_ops", "bit_ops")
# Fixed build time and hash seed: two builds of the same sources give the same image.
EPOCH = "1735689600"


class BuildError(RuntimeError):
    """What is missing, in one line."""


def log(msg):
    print("pico-firmware: " + msg, file=sys.stderr, flush=True)


def run(cmd, **kw):
    """Run cmd; BuildError with its last output lines when it fails."""
    res = subprocess.run(cmd, capture_output=True, text=True, **kw)
    if res.returncode:
        tail = "\n".join((res.stdout + res.stderr).strip().splitlines()[-15:])
        raise BuildError("%s failed (exit %d):\n%s" % (" ".join(cmd[:3]), res.returncode, tail))
    return res.stdout


def apt(out):
    """apt-get with a private sources list and state under out/apt (the system's apt is not touched)."""
    base = os.path.join(out, "apt")
    for d in ("lists/partial", "cache/archives/partial"):
        os.makedirs(os.path.join(base, d), exist_ok=True)
    src = os.path.join(base, "sources.list")
    with open(src, "w") as f:
        for kind in ("deb-src", "deb"):
            f.write("%s [signed-by=%s] %s %s main\n" % (kind, KEYRING, MIRROR, SUITE))
    return [
        "apt-get",
        "-q",
        "-o",
        "Dir::Etc::SourceList=" + src,
        "-o",
        "Dir::Etc::SourceParts=/dev/null",
        "-o",
        "Dir::State::Lists=" + os.path.join(base, "lists"),
        "-o",
        "Dir::Cache=" + os.path.join(base, "cache"),
        "-o",
        "APT::Sandbox::User=root",
    ]


def uris(text):
    """apt-get --print-uris lines -> [(url, filename, size, sha256)]."""
    found = []
    for m in re.finditer(r"^'(\S+)' (\S+) (\d+) SHA256:([0-9a-f]{64})$", text, re.M):
        found.append((m.group(1), m.group(2), int(m.group(3)), m.group(4)))
    return found


def sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def fetch(url, name, size, digest, into):
    """Download url to into/name unless a file with that SHA-256 is there; check size and hash."""
    path = os.path.join(into, name)
    if os.path.isfile(path) and sha256(path) == digest:
        return path
    tmp = path + ".part"
    try:
        with urllib.request.urlopen(url, timeout=120) as r, open(tmp, "wb") as f:
            shutil.copyfileobj(r, f)
    except OSError as err:
        raise BuildError("cannot download %s: %s" % (name, err)) from None
    got = sha256(tmp)
    if os.path.getsize(tmp) != size or got != digest:
        os.unlink(tmp)
        raise BuildError("%s: sha256 %s, Debian's index says %s" % (name, got, digest))
    os.replace(tmp, path)
    return path


def dsc_checksums(path):
    """A .dsc's Checksums-Sha256 field -> {filename: sha256}."""
    with open(path) as f:
        text = f.read()
    m = re.search(r"^Checksums-Sha256:\n((?: .*\n)+)", text, re.M)
    rows = (line.split() for line in m.group(1).splitlines()) if m else ()
    return {name: digest for digest, _size, name in rows}


def download(out):
    """The orig tarballs and tinyusb-source's .deb, checked -> {package: {version, file, sha256, ...}}."""
    cmd = apt(out)
    log("reading Debian %s's package index (private apt lists in %s)" % (SUITE, os.path.join(out, "apt")))
    run(cmd + ["update"])
    into = os.path.join(out, "archives")
    os.makedirs(into, exist_ok=True)
    got = {}
    for pkg in SOURCES:
        files = uris(run(cmd + ["source", "--print-uris", pkg]))
        if not files:
            raise BuildError("Debian %s has no source package %s" % (SUITE, pkg))
        orig = [f for f in files if ".orig.tar." in f[1]]
        dsc = [f for f in files if f[1].endswith(".dsc")]
        if len(orig) != 1:
            raise BuildError("%s: expected one orig tarball, found %s" % (pkg, [f[1] for f in files]))
        url, name, size, digest = orig[0]
        log("%s: %s (%d bytes)" % (pkg, name, size))
        path = fetch(url, name, size, digest, into)
        entry = {"kind": "source", "file": name, "sha256": digest, "size": size}
        entry["version"] = re.search(r"_([^_]+)\.dsc$", dsc[0][1]).group(1) if dsc else name.split("_")[1]
        entry["dsc"] = None
        if dsc:
            try:
                dpath = fetch(*dsc[0], into)
            except BuildError as err:  # pico-sdk's .dsc is listed in the index but not served
                entry["dsc_note"] = str(err)
            else:
                if dsc_checksums(dpath).get(name) != digest:
                    raise BuildError("%s: %s does not match its .dsc" % (pkg, name))
                entry["dsc"] = {"file": dsc[0][1], "sha256": dsc[0][3]}
        entry["path"] = path
        got[pkg] = entry
    for pkg in BINARIES:
        # Run where the .deb is not: apt-get download prints no URI for a file already in its folder.
        files = uris(run(cmd + ["download", "--print-uris", pkg], cwd=os.path.join(out, "apt")))
        if len(files) != 1:
            raise BuildError("Debian %s has no binary package %s" % (SUITE, pkg))
        url, name, size, digest = files[0]
        log("%s: %s (%d bytes)" % (pkg, name, size))
        path = fetch(url, name, size, digest, into)
        version = urllib.parse.unquote(name).split("_")[1]
        got[pkg] = {"kind": "binary", "file": name, "sha256": digest, "size": size, "version": version, "path": path}
    return got


def extract(archive, dest, strip=1, member_prefix=""):
    """Unpack a tarball into dest, dropping `strip` leading path parts (and keeping only member_prefix)."""
    os.makedirs(dest, exist_ok=True)
    with tarfile.open(archive) as tar:
        members = []
        for m in tar.getmembers():
            name = m.name[2:] if m.name.startswith("./") else m.name
            if not name.startswith(member_prefix):
                continue
            parts = name[len(member_prefix) :].split("/")[strip:]
            if not parts or not parts[0]:
                continue
            m.name = "/".join(parts)
            members.append(m)
        tar.extractall(dest, members=members, filter="tar")


def deb_data(deb, into):
    """The data.tar.* member of a .deb (an ar archive) written to into/, its path."""
    with open(deb, "rb") as f:
        if f.read(8) != b"!<arch>\n":
            raise BuildError("%s is not a Debian package" % deb)
        while True:
            head = f.read(60)
            if len(head) < 60:
                raise BuildError("%s has no data.tar member" % deb)
            name = head[:16].decode().strip().rstrip("/")
            size = int(head[48:58])
            body = f.read(size)
            f.read(size & 1)
            if name.startswith("data.tar"):
                path = os.path.join(into, name)
                with open(path, "wb") as g:
                    g.write(body)
                return path


def lay_out(src, work):
    """The micropython tree with pico-sdk, tinyusb and mbedtls where the rp2 port expects them."""
    tree = os.path.join(work, "micropython")
    shutil.rmtree(work, ignore_errors=True)
    log("unpacking into %s" % work)
    extract(src["micropython"]["path"], tree)
    lib = os.path.join(tree, "lib")
    for pkg, sub in (("pico-sdk", "pico-sdk"), ("mbedtls", "mbedtls")):
        shutil.rmtree(os.path.join(lib, sub), ignore_errors=True)
        extract(src[pkg]["path"], os.path.join(lib, sub))
    shutil.rmtree(os.path.join(lib, "tinyusb"), ignore_errors=True)
    data = deb_data(src["tinyusb-source"]["path"], work)
    extract(data, os.path.join(lib, "tinyusb"), strip=0, member_prefix="usr/src/tinyusb/")
    # No Debian package carries micropython-lib; the port only needs the folder to exist.
    mplib = os.path.join(work, "micropython-lib")
    os.makedirs(mplib, exist_ok=True)
    with open(os.path.join(mplib, "README.md"), "w") as f:
        f.write("Empty: micropython-lib is not packaged in Debian; nothing of it is frozen.\n")
    return tree, mplib


def patch_port(tree):
    """The rp2 port's CMakeLists: float (and double, memory, bit operations) from the compiler."""
    path = os.path.join(tree, "ports", "rp2", "CMakeLists.txt")
    with open(path) as f:
        text = f.read()
    old = "pico_set_float_implementation(${MICROPY_TARGET} micropython)"
    if old not in text:
        raise BuildError("ports/rp2/CMakeLists.txt has no line %r to replace" % old)
    new = "\n".join("pico_set_%s_implementation(${MICROPY_TARGET} compiler)" % i for i in IMPLEMENTATIONS)
    with open(path, "w") as f:
        f.write(text.replace(old, new))
    return new.splitlines()


# The port's linker script runs libgcc, libc and libm from RAM: with the ROM's float functions that is
# little code, but with the compiler's soft float it is ~33 KB of the heap. Ours keeps them in flash
# (libc's mem* functions stay in RAM, as the port has them; gc, vm and parse too).
LINKER = (
    "memmap_mp_rp2040.ld",
    (
        (
            "*(EXCLUDE_FILE(*libgcc.a: *libc.a: *lib_a-mem*.o *libm.a: *gc.c.obj",
            "*(EXCLUDE_FILE(*libc.a:*lib_a-mem*.o *gc.c.obj",
        ),
        (
            "*(EXCLUDE_FILE(*libgcc.a: *libc.a:*lib_a-mem*.o *libm.a:) .rodata*)",
            "*(EXCLUDE_FILE(*libc.a:*lib_a-mem*.o) .rodata*)",
        ),
    ),
)


def patch_linker(tree):
    """The rp2040 linker script: the compiler's float and math library in flash, not in RAM."""
    name, edits = LINKER
    path = os.path.join(tree, "ports", "rp2", name)
    with open(path) as f:
        text = f.read()
    for old, new in edits:
        if text.count(old) != 1:
            raise BuildError("ports/rp2/%s has no line %r to change" % (name, old))
        text = text.replace(old, new)
    with open(path, "w") as f:
        f.write(text)
    return [{"file": name, "from": old, "to": new} for old, new in edits]


def toolchain():
    """Install the Debian toolchain when missing (root only); its gcc version line."""
    lacking = [pkg for tool, pkg in TOOLS.items() if shutil.which(tool) is None]
    if lacking:
        if os.geteuid() != 0:
            raise BuildError("missing %s: apt-get install %s" % (", ".join(lacking), " ".join(lacking)))
        log("installing %s with apt-get" % " ".join(lacking))
        env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
        run(["apt-get", "update", "-qq"], env=env)
        run(["apt-get", "install", "-y", "-qq"] + " ".join(lacking).split(), env=env)
    return run(["arm-none-eabi-gcc", "--version"]).splitlines()[0]


def build(out, jobs):
    t0 = time.monotonic()
    gcc = toolchain()
    src = download(out)
    t_fetch = time.monotonic() - t0
    work = os.path.join(out, "src")
    tree, mplib = lay_out(src, work)
    cmake_lines = patch_port(tree)
    linker_edits = patch_linker(tree)
    manifest = os.path.join(HERE, "frozen_manifest.py")
    # CMAKE_ARGS goes in the environment: on make's command line it would replace the port's own.
    cmake_args = "-DPICO_NO_PICOTOOL=1 -DMICROPY_LIB_DIR=" + mplib
    env = dict(os.environ, SOURCE_DATE_EPOCH=EPOCH, PYTHONHASHSEED="0", CMAKE_ARGS=cmake_args)
    log("building mpy-cross")
    run(["make", "-j%d" % jobs, "-C", os.path.join(tree, "mpy-cross")], env=env)
    port = os.path.join(tree, "ports", "rp2")
    make = ["make", "-j%d" % jobs, "-C", port, "BOARD=RPI_PICO", "FROZEN_MANIFEST=" + manifest]
    log("building the RPI_PICO firmware (%d jobs)" % jobs)
    run(make, env=env)
    built = os.path.join(port, "build-RPI_PICO")
    for name in ("firmware.bin", "firmware.elf"):
        shutil.copyfile(os.path.join(built, name), os.path.join(out, name + ".part"))
        os.replace(os.path.join(out, name + ".part"), os.path.join(out, name))
    seconds = time.monotonic() - t0
    with open(manifest) as f:
        manifest_text = f.read()
    provenance = {
        "image": "MicroPython %s, board RPI_PICO" % src["micropython"]["version"],
        "firmware.bin": {
            "sha256": sha256(os.path.join(out, "firmware.bin")),
            "size": os.path.getsize(os.path.join(out, "firmware.bin")),
        },
        "packages": {k: {f: v[f] for f in v if f != "path"} for k, v in src.items()},
        "debian_suite": SUITE,
        "compiler": gcc,
        "cmake": run(["cmake", "--version"]).splitlines()[0],
        "cmake_changes": cmake_lines,
        "linker_changes": linker_edits,
        "cmake_args": env["CMAKE_ARGS"],
        "make": make[3:],
        "frozen_manifest": manifest_text,
        "micropython_lib": "empty folder (not packaged in Debian)",
        "SOURCE_DATE_EPOCH": EPOCH,
        "PYTHONHASHSEED": "0",
        "built": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
        "build_seconds": round(seconds, 1),
        "fetch_seconds": round(t_fetch, 1),
        "jobs": jobs,
    }
    with open(os.path.join(out, "provenance.json.part"), "w") as f:
        json.dump(provenance, f, indent=2)
        f.write("\n")
    os.replace(os.path.join(out, "provenance.json.part"), os.path.join(out, "provenance.json"))
    shutil.rmtree(work, ignore_errors=True)
    log("done in %.0f s: %s" % (seconds, os.path.join(out, "firmware.bin")))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=DEFAULT_OUT, help="cache folder (default build/pico-firmware)")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    ap.add_argument("--force", action="store_true", help="build even when the image is there")
    args = ap.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    if not args.force and os.path.isfile(os.path.join(args.out, "firmware.bin")):
        log("%s is there (--force rebuilds)" % os.path.join(args.out, "firmware.bin"))
        return 0
    try:
        build(args.out, args.jobs)
    except BuildError as err:
        log("no image: %s" % err)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
