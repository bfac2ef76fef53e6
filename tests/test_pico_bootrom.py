"""Our own RP2040 bootrom (host/pico/bootrom.mjs) against the RP2040 datasheet's section 2.8:
the header's fields, rom_table_lookup run on the emulated core for every code the image uses, an
unknown code reported by the runner, and a boot through boot2 into the image's reset handler."""

import json
import os
import struct
import subprocess

import pytest

from hexapod_host.pico import emulator as pico

NODE_MISSING = None
try:
    pico.node()
except pico.PicoError as err:
    NODE_MISSING = str(err)
pytestmark = pytest.mark.skipif(NODE_MISSING is not None, reason=NODE_MISSING or "")

# Datasheet 2.8.3.1.2 (flash access functions): each function's two-character code.
DATASHEET_CODES = {
    "connect_internal_flash": "IF",
    "flash_exit_xip": "EX",
    "flash_range_erase": "RE",
    "flash_range_program": "RP",
    "flash_flush_cache": "FC",
    "flash_enter_cmd_xip": "CX",
}
BX_LR = 0x4770  # Thumb BX LR: a served function returns at once unless the runner traps it


def node_run(script):
    """Run an ES module next to run.mjs (rp2040js installed); its stdout as JSON."""
    pico.rp2040js()
    proc = subprocess.run(
        [pico.node(), "--input-type=module", "-e", script],
        cwd=pico.HERE,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)


PRELUDE = """
import path from 'path';
const pkg = path.join(process.cwd(), 'node_modules', 'rp2040js', 'dist', 'esm');
const { RP2040 } = await import(path.join(pkg, 'index.js'));
const { SimulationClock } = await import(path.join(pkg, 'clock', 'simulation-clock.js'));
const ROM = await import(path.join(process.cwd(), 'bootrom.mjs'));
const mcu = new RP2040(new SimulationClock(125e6));
mcu.loadBootrom(ROM.bootrom);
"""


@pytest.fixture(scope="module")
def rom():
    """The ROM's first 256 bytes, and each datasheet code looked up by the ROM's own routine."""
    script = (
        PRELUDE
        + """
const codes = %s;
const out = { bytes: Array.from(new Uint8Array(ROM.bootrom.buffer).subarray(0, 256)), lookups: {} };
const RETURN = 0x20001000;                 // a 'b .' in SRAM: where the lookup returns to
mcu.writeUint16(RETURN, 0xe7fe);
for (const tag of [...codes, 'ZZ', 'SF']) {
  const r = mcu.core.registers;
  r[0] = mcu.readUint16(0x14); r[1] = tag.charCodeAt(0) | (tag.charCodeAt(1) << 8);
  mcu.core.LR = RETURN | 1; mcu.core.PC = mcu.readUint16(0x18) & ~1; mcu.core.SP = 0x20041f00;
  let n = 0;
  while (mcu.core.PC !== RETURN && n++ < 1000) mcu.core.executeInstruction();
  out.lookups[tag] = { result: r[0], steps: n, target: r[0] ? mcu.readUint16(r[0] & ~1) : null };
}
process.stdout.write(JSON.stringify(out));
"""
        % json.dumps(sorted(DATASHEET_CODES.values()))
    )
    res = node_run(script)
    res["bytes"] = bytes(res["bytes"])
    return res


def test_the_header_is_the_datasheets():
    """2.8.2: initial SP and reset vector at 0x0/0x4, 'Mu' 0x01 and the version at 0x10, the three
    16-bit pointers at 0x14/0x16/0x18 (the lookup a Thumb function address), all inside the ROM."""
    r = node_run(PRELUDE + "process.stdout.write(JSON.stringify(Array.from(new Uint8Array(ROM.bootrom.buffer))));")
    data = bytes(r)
    assert len(data) == 16 * 1024
    sp, reset = struct.unpack_from("<II", data, 0)
    assert sp == 0x20041F00 and reset & 1 and 0x1C < reset < 0x4000
    assert data[0x10:0x13] == b"Mu\x01"
    func, dat, lookup = struct.unpack_from("<HHH", data, 0x14)
    assert lookup & 1 and func % 2 == 0 and dat % 2 == 0
    assert all(0x1C <= p < 0x400 for p in (func, dat, lookup & ~1))


def test_every_flash_function_the_image_uses_is_served(rom):
    """Each datasheet code resolves (Thumb bit set) to its own address holding a BX LR: the runner
    traps RE/RP there, the others return at once; the addresses are distinct."""
    found = {}
    for name, tag in DATASHEET_CODES.items():
        got = rom["lookups"][tag]
        assert got["result"] & 1, (name, got)
        assert got["target"] == BX_LR, (name, got)
        found[tag] = got["result"]
    assert len(set(found.values())) == len(found)


def test_an_unknown_code_is_not_found(rom):
    """2.8.3.1: a code not in the table gives 0 (here: the runner traps that exit and names it)."""
    for tag in ("ZZ", "SF"):
        assert rom["lookups"][tag]["result"] == 0


def test_the_runner_names_a_rom_function_it_does_not_serve(tmp_path):
    """A tiny image whose boot2 asks the ROM for 'SF' (the float table a stock release uses): the
    runner stops with exit 3 and says which code was asked for, instead of jumping to address 0."""
    # Thumb: movs r0,#0x14; ldrh r0,[r0]; movs r1,#0x18; ldrh r2,[r1]; movs r1,#'F'; lsls r1,#8;
    # adds r1,#'S'; blx r2; b .
    code = [0x2014, 0x8800, 0x2118, 0x880A, 0x2146, 0x0209, 0x3153, 0x4790, 0xE7FE]
    image = struct.pack("<%dH" % len(code), *code).ljust(4096, b"\xff")
    fw = tmp_path / "asks_sf.bin"
    fw.write_bytes(image)
    pico.rp2040js()
    proc = subprocess.run(
        [pico.node(), pico.RUNNER, "--firmware", str(fw), "--max-emu-s", "1", os.devnull],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert proc.returncode == 3, (proc.returncode, proc.stderr)
    assert "'SF'" in proc.stderr and "code 0x4653" in proc.stderr, proc.stderr


@pytest.mark.skipif(pico.missing() is not None, reason=pico.missing() or "")
def test_boot_goes_through_boot2_into_the_images_reset_handler():
    """From the ROM's reset vector: boot2 copied to 0x20041f00 byte for byte and run from there,
    then the image's own reset handler (the vector at 0x10000104) is reached."""
    fw = pico.firmware()
    with open(fw, "rb") as f:
        image = f.read()
    if fw.endswith(".uf2"):
        pytest.skip("the boot trace reads a flat .bin image")
    reset = struct.unpack_from("<I", image, 0x104)[0] & ~1
    script = (
        PRELUDE
        + """
import fs from 'fs';
mcu.flash.set(fs.readFileSync(%s), 0);
mcu.core.reset();
const start = mcu.core.PC;
let inBoot2 = 0, n = 0;
while (mcu.core.PC !== %d && n++ < 200000) {
  if (mcu.core.PC >= 0x20041f00 && mcu.core.PC < 0x20042000) inBoot2++;
  mcu.core.executeInstruction();
}
const copy = Array.from({ length: 256 }, (_, i) => mcu.readUint8(0x20041f00 + i));
process.stdout.write(JSON.stringify({ start, reached: mcu.core.PC, steps: n, inBoot2, copy }));
"""
        % (json.dumps(fw), reset)
    )
    r = node_run(script)
    assert r["start"] < 0x4000  # the ROM's reset handler, not the flash
    assert r["reached"] == reset, r
    assert r["inBoot2"] > 20  # boot2 ran from its SRAM copy
    assert bytes(r["copy"]) == image[:256]
