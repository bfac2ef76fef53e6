"""An RP2040 image is checked before the emulator boots it (hexapod_host.pico.image): the expectations
come from the UF2 spec's block layout and magic numbers and the RP2040 datasheet's boot2 checksum,
written out here by hand, not from the checker."""

import os
import pathlib
import struct

import pytest

from hexapod_host.pico import emulator as pico
from hexapod_host.pico import image

REAL = pico.DEFAULT_FIRMWARE
HAVE_REAL = os.path.isfile(REAL)


def test_boot2_crc_is_the_catalogued_crc32_mpeg2():
    # The catalogue's check value of CRC-32/MPEG-2 (poly 04c11db7, init ffffffff, refin/refout false,
    # xorout 0) over "123456789": the CRC the RP2040 bootrom applies to boot2.
    assert image.crc32_boot2(b"123456789") == 0x0376E6E7


def uf2(flash, family=0xE48BFF56, flags=0x2000, base=0x10000000):
    """flash as UF2 blocks of 256 bytes, as the UF2 spec lays them out (and the Pico SDK's elf2uf2 does)."""
    n = (len(flash) + 255) // 256
    out = b""
    for k in range(n):
        payload = flash[256 * k : 256 * k + 256].ljust(256, b"\0")
        head = struct.pack("<8I", 0x0A324655, 0x9E5D5157, flags, base + 256 * k, 256, k, n, family)
        out += head + payload.ljust(476, b"\0") + struct.pack("<I", 0x0AB16F30)
    return out


@pytest.mark.skipif(not HAVE_REAL, reason="no build/pico-firmware/firmware.bin (make pico-firmware)")
def test_the_built_image_passes_as_bin_and_as_uf2(tmp_path):
    data = pathlib.Path(REAL).read_bytes()
    image.check(REAL)
    f = tmp_path / "fw.uf2"
    f.write_bytes(uf2(data))
    image.check(str(f))
    assert image.uf2_flash(f.read_bytes())[: len(data)] == data


def refused(tmp_path, name, data):
    f = tmp_path / name
    f.write_bytes(data)
    with pytest.raises(image.ImageError) as err:
        image.check(str(f))
    return str(err.value)


@pytest.mark.skipif(not HAVE_REAL, reason="no build/pico-firmware/firmware.bin (make pico-firmware)")
def test_broken_images_are_named(tmp_path):
    data = bytearray(pathlib.Path(REAL).read_bytes())
    bad = bytearray(data)
    bad[100] ^= 1  # one bit of boot2
    assert "no RP2040 boot2 at its start" in refused(tmp_path, "a.bin", bytes(bad))
    assert "no RP2040 boot2" in refused(tmp_path, "a.uf2", uf2(bytes(bad)))
    assert "family 0xe48bff59, not the RP2040's 0xe48bff56" in refused(
        tmp_path,
        "b.uf2",
        uf2(bytes(data), family=0xE48BFF59),  # an RP2350 (ARM) image's family
    )
    assert "not named .uf2" in refused(tmp_path, "c.bin", uf2(bytes(data)))
    torn = bytearray(uf2(bytes(data)))
    torn[512 * 3 + 508] ^= 0xFF  # block 3's end magic
    assert refused(tmp_path, "d.uf2", bytes(torn)) == "block 3 lacks the UF2 magic numbers"
    sp = bytearray(data)
    sp[256:260] = struct.pack("<I", 0x10000000)  # a stack pointer in flash
    assert "initial stack pointer 0x10000000 is not in SRAM" in refused(tmp_path, "e.bin", bytes(sp))


def test_files_that_are_no_image(tmp_path):
    assert refused(tmp_path, "fw.elf", b"\x7fELF\x01\x01\x01" + bytes(100)) == (
        "an ELF file (give the .uf2 or .bin built with it)"
    )
    assert refused(tmp_path, "x.uf2", b"hello\n") == "6 bytes, not a whole number of 512-byte UF2 blocks"
    assert "less than boot2 and a vector table" in refused(tmp_path, "x.bin", b"hello\n")
    assert "no RP2040 boot2" in refused(tmp_path, "zeros.bin", bytes(4096))
    ram_only = uf2(bytes(512), base=0x20000000)  # blocks for SRAM only
    assert "no block writes the RP2040's flash" in refused(tmp_path, "ram.uf2", ram_only)
