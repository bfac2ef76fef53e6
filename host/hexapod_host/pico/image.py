"""Is this file an RP2040 flash image? Checked before the emulator boots it: run.mjs would load any bytes
and the chip would run garbage (an ELF, a UF2 for another chip) until the runner's 900 s timeout.

A .bin is the flash from 0x10000000: the RP2040 datasheet (2.8.1.3, "Checksum") has the bootrom
accept the 256-byte second-stage bootloader (boot2) only when its last 4 bytes are the CRC32 of the
first 252 (polynomial 0x04c11db7, initial value 0xffffffff, no reflection, no final xor), and the
vector table that follows it (at 0x10000100) holds the initial stack pointer (in SRAM) and the
reset handler (a Thumb address: odd, in flash). A .uf2 (Microsoft's UF2 spec) is 512-byte blocks:
magic 0x0A324655 0x9E5D5157 at the start, 0x0AB16F30 at the end, the target address at 12, the
payload size at 16 (at most 476), the family ID at 28 when flag 0x2000 is set (RP2040: 0xe48bff56);
its flash blocks must make such a .bin.
"""

import os
import struct

FLASH = 0x10000000
FLASH_END = FLASH + 0x200000  # the Pico's 2 MB: what run.mjs loads
SRAM, SRAM_END = 0x20000000, 0x20042000  # 264 KB; an initial SP may sit at the very end
UF2_MAGIC = (0x0A324655, 0x9E5D5157, 0x0AB16F30)
UF2_FAMILY_PRESENT = 0x2000
UF2_NOT_MAIN_FLASH = 0x0001
RP2040_FAMILY = 0xE48BFF56
BOOT2 = 256


class ImageError(ValueError):
    """The file is no RP2040 image: the message says why."""


def crc32_boot2(data):
    """The bootrom's CRC32 (MSB first, polynomial 0x04c11db7, initial 0xffffffff, no final xor)."""
    crc = 0xFFFFFFFF
    for byte in data:
        crc ^= byte << 24
        for _ in range(8):
            crc = ((crc << 1) ^ 0x04C11DB7) if crc & 0x80000000 else crc << 1
            crc &= 0xFFFFFFFF
    return crc


def check_flash(flash):
    """ImageError unless flash (bytes from 0x10000000) starts with a boot2 the bootrom accepts and a
    vector table it can jump through."""
    if len(flash) < BOOT2 + 8:
        raise ImageError("%d bytes, less than boot2 and a vector table (264)" % len(flash))
    want = struct.unpack_from("<I", flash, BOOT2 - 4)[0]
    got = crc32_boot2(flash[: BOOT2 - 4])
    if got != want:
        raise ImageError(
            "no RP2040 boot2 at its start (the CRC32 of bytes 0-251 is 0x%08x, bytes 252-255 say 0x%08x)" % (got, want)
        )
    sp, reset = struct.unpack_from("<II", flash, BOOT2)
    if not SRAM < sp <= SRAM_END:
        raise ImageError("its initial stack pointer 0x%08x is not in SRAM (0x%08x..0x%08x)" % (sp, SRAM, SRAM_END))
    if not (reset & 1 and FLASH + BOOT2 <= reset < FLASH + len(flash)):
        raise ImageError("its reset handler 0x%08x is not a Thumb address in the image" % reset)


def uf2_flash(data):
    """The flash bytes a UF2 file's main-flash blocks write (from 0x10000000); ImageError names a bad block."""
    if not data or len(data) % 512:
        raise ImageError("%d bytes, not a whole number of 512-byte UF2 blocks" % len(data))
    flash = bytearray()
    for n in range(len(data) // 512):
        b = data[512 * n : 512 * n + 512]
        m0, m1, flags, addr, size = struct.unpack_from("<5I", b)
        family = struct.unpack_from("<I", b, 28)[0]
        if (m0, m1, struct.unpack_from("<I", b, 508)[0]) != UF2_MAGIC:
            raise ImageError("block %d lacks the UF2 magic numbers" % n)
        if flags & UF2_FAMILY_PRESENT and family != RP2040_FAMILY:
            raise ImageError("block %d is for UF2 family 0x%08x, not the RP2040's 0x%08x" % (n, family, RP2040_FAMILY))
        if flags & UF2_NOT_MAIN_FLASH or not FLASH <= addr < FLASH_END:
            continue
        if size > 476 or addr + size > FLASH_END:
            raise ImageError("block %d: %d bytes at 0x%08x do not fit" % (n, size, addr))
        end = addr - FLASH + size
        if len(flash) < end:
            flash.extend(b"\xff" * (end - len(flash)))  # erased flash between blocks
        flash[addr - FLASH : end] = b[32 : 32 + size]
    if not flash:
        raise ImageError("no block writes the RP2040's flash (0x%08x..0x%08x)" % (FLASH, FLASH_END))
    return bytes(flash)


def check(path):
    """ImageError unless path is an RP2040 image as run.mjs loads it: a UF2 when named .uf2, else a .bin."""
    uf2 = path.endswith(".uf2")
    with open(path, "rb") as f:
        if f.read(4) == b"\x7fELF":
            raise ImageError("an ELF file (give the .uf2 or .bin built with it)")
        size = os.fstat(f.fileno()).st_size
        if size > (FLASH_END - FLASH) * (2 if uf2 else 1):  # a UF2 block carries at most 476 B of its 512
            raise ImageError("%d bytes, more than the Pico's 2 MB of flash holds" % size)
        f.seek(0)
        data = f.read()
    if uf2:
        check_flash(uf2_flash(data))
    elif len(data) >= 4 and struct.unpack_from("<I", data)[0] == UF2_MAGIC[0]:
        raise ImageError("a UF2 file not named .uf2 (the emulator tells UF2 from .bin by the name)")
    else:
        check_flash(data)
