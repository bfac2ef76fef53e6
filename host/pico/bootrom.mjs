// Our own minimal RP2040 bootrom, written from the RP2040 datasheet's "Bootrom" section (2.8):
// what a MicroPython image built with the compiler's float, double, memory and bit operations
// (host/pico/firmware.py) needs from the ROM, and nothing else.
//
//   0x00  initial SP, reset, NMI and HardFault vectors (2.8.1: the ROM's vector table at 0x0)
//   0x10  'M' 'u' 0x01 and the bootrom version byte (2.8.2, "Bootrom Contents")
//   0x14  16-bit pointer to the public function table, 0x16 to the public data table,
//   0x18  16-bit pointer to rom_table_lookup(table, code) (2.8.3, "Bootrom Functions")
//   table: (16-bit code, 16-bit pointer) pairs, code = c1 | c2 << 8, ended by a zero code
//
// Reset does what 2.8.1 "Processor-Controlled Boot Sequence" says core 0 does to boot from
// flash: copy the first 256 bytes of flash (boot2) to the top of SRAM at 0x20041f00 and enter
// them with lr = 0, which tells boot2 to go on into the image's vector table at 0x10000100.
// Not done (the emulator has one core, no USB boot): core 1's wait loop, boot2's CRC32 check,
// the USB mass-storage fallback.
//
// Functions served: connect_internal_flash 'IF', flash_exit_xip 'EX', flash_range_erase 'RE',
// flash_range_program 'RP', flash_flush_cache 'FC', flash_enter_cmd_xip 'CX'. Each is a single
// `bx lr`: rp2040js has no QSPI flash, so the runner traps 'RE' and 'RP' (run.mjs performs them
// on its flash array); the others have nothing to do. A lookup of any other code ends at
// NOT_FOUND, which the runner traps and reports with the code asked for (the real ROM returns 0
// there, and the caller would jump to address 0).

// Thumb-1 encodings (ARMv6-M Architecture Reference Manual, A6.7), one helper per form used.
const ldrhImm = (rt, rn, off) => 0x8800 | ((off >> 1) << 6) | (rn << 3) | rt;   // LDRH Rt, [Rn, #off]
const cmpImm = (rn, imm) => 0x2800 | (rn << 8) | imm;                           // CMP Rn, #imm8
const cmpReg = (rn, rm) => 0x4280 | (rm << 3) | rn;                             // CMP Rn, Rm
const addsImm = (rdn, imm) => 0x3000 | (rdn << 8) | imm;                        // ADDS Rdn, #imm8
const subsImm = (rdn, imm) => 0x3800 | (rdn << 8) | imm;                        // SUBS Rdn, #imm8
const movsImm = (rd, imm) => 0x2000 | (rd << 8) | imm;                          // MOVS Rd, #imm8
const movLr = (rm) => 0x4600 | 0x80 | (rm << 3) | 6;                            // MOV LR, Rm
const ldm = (rn, regs) => 0xc800 | (rn << 8) | regs;                            // LDM Rn!, {regs}
const stm = (rn, regs) => 0xc000 | (rn << 8) | regs;                            // STM Rn!, {regs}
const bx = (rm) => 0x4700 | (rm << 3);                                          // BX Rm
const BX_LR = bx(14);
const EQ = 0x0, NE = 0x1;

export const VERSION = 2;                 // the byte at 0x13 (B1's): pico-sdk reads it for B0 errata only
export const STACK_TOP = 0x20041f00;      // below the boot2 copy, as the datasheet's ROM sets it
export const BOOT2_SRAM = 0x20041f00;
export const BOOT2_BYTES = 256;
export const FUNCTIONS = ['IF', 'EX', 'RE', 'RP', 'FC', 'CX'];
export const code = (tag) => tag.charCodeAt(0) | (tag.charCodeAt(1) << 8);

// Assemble: halfwords placed from CODE_START, labels resolved in a second pass.
const CODE_START = 0x20;
const rom = new Uint8Array(16 * 1024);
const dv = new DataView(rom.buffer);
let at = CODE_START;
const labels = {};
const fixups = [];
const here = (name) => { labels[name] = at; };
const h = (v) => { dv.setUint16(at, v, true); at += 2; };
const bcond = (cond, label) => fixups.push([at, (off) => 0xd000 | (cond << 8) | (off & 0xff), label]) && h(0);
const b = (label) => fixups.push([at, (off) => 0xe000 | (off & 0x7ff), label]) && h(0);
const literals = [];
const ldrLit = (rt, value) => { literals.push([at, rt, value]); h(0); };   // LDR Rt, =value

// reset: copy boot2 into SRAM and enter it with lr = 0 (2.8.1)
here('reset');
ldrLit(0, 0x10000000);
ldrLit(1, BOOT2_SRAM);
h(movsImm(2, BOOT2_BYTES / 4));
here('copy');
h(ldm(0, 1 << 3));
h(stm(1, 1 << 3));
h(subsImm(2, 1));
bcond(NE, 'copy');
h(movsImm(0, 0));
h(movLr(0));
ldrLit(0, BOOT2_SRAM | 1);
h(bx(0));
here('hang');                              // NMI, HardFault: stay (the runner's time limit ends it)
b('hang');

// rom_table_lookup(table: r0, code: r1) -> r0: the entry's pointer (2.8.3.1)
here('lookup');
h(ldrhImm(2, 0, 0));
h(cmpImm(2, 0));
bcond(EQ, 'notFound');
h(cmpReg(2, 1));
bcond(EQ, 'found');
h(addsImm(0, 4));
b('lookup');
here('found');
h(ldrhImm(0, 0, 2));
h(BX_LR);
here('notFound');
h(movsImm(0, 0));
h(BX_LR);

// one `bx lr` per served function, each at its own address (the runner tells RE from RP by PC)
for (const tag of FUNCTIONS) { here(tag); h(BX_LR); }

// literal pool, word aligned: LDR Rt, [PC, #imm8*4] reads Align(PC + 4, 4) + imm8 * 4
if (at & 2) h(0);
for (const [pos, rt, value] of literals) {
  const base = (pos + 4) & ~3;
  dv.setUint16(pos, 0x4800 | (rt << 8) | ((at - base) >> 2), true);
  dv.setUint32(at, value >>> 0, true); at += 4;
}
for (const [pos, enc, label] of fixups) dv.setUint16(pos, enc((labels[label] - (pos + 4)) >> 1), true);

// the tables: functions (pointers with the Thumb bit, as the ROM's), then an empty data table
const FUNC_TABLE = at;
for (const tag of FUNCTIONS) { dv.setUint16(at, code(tag), true); dv.setUint16(at + 2, labels[tag] | 1, true); at += 4; }
dv.setUint16(at, 0, true); at += 4;
const DATA_TABLE = at;
dv.setUint16(at, 0, true); at += 4;

// the header
dv.setUint32(0x00, STACK_TOP, true);
dv.setUint32(0x04, labels.reset | 1, true);
dv.setUint32(0x08, labels.hang | 1, true);
dv.setUint32(0x0c, labels.hang | 1, true);
rom.set([0x4d, 0x75, 0x01, VERSION], 0x10);
dv.setUint16(0x14, FUNC_TABLE, true);
dv.setUint16(0x16, DATA_TABLE, true);
dv.setUint16(0x18, labels.lookup | 1, true);

export const SIZE = at;
export const NOT_FOUND = labels.notFound;
export const LOOKUP = labels.lookup;
export const RESET = labels.reset;
export const ADDRESS = Object.fromEntries(FUNCTIONS.map((t) => [t, labels[t]]));
export const bootrom = new Uint32Array(rom.buffer);
