#!/usr/bin/env node
// The hexapod firmware on an emulated Raspberry Pi Pico (rp2040js 1.4.1, MicroPython RPI_PICO).
// Started by host/hexapod_host/pico/emulator.py (`hexapod pico ...`); usable alone:
//
//   node run.mjs --firmware F.uf2|F.bin [--fs IMG] [--devices JSON] [--trace OUT]
//                [--main SECONDS] [--stats OUT] [--max-emu-s N] FILE.py ...
//   node run.mjs --firmware F --serial [--fs IMG] [--save-fs OUT] [--devices JSON] [--trace OUT]
//
// FILE.py are sent one after another through the raw REPL in raw-paste mode (as mpremote run);
// whatever main.py the image holds is interrupted first (Ctrl-C), as mpremote does. With
// --main SECONDS the board's own main.py runs instead for that many emulated seconds.
// Board output goes to stdout, tracebacks to stderr; exit status 1 when a script raised.
//
// --serial: the board's USB CDC bridged raw to stdin/stdout (bytes both ways, nothing translated),
// emulated time paced to wall time (never ahead of it), until stdin closes or SIGTERM/SIGINT;
// a watchdog reset (machine.reset(), mpremote reset) powers the chip up again with the flash it
// has. --save-fs OUT writes the littlefs region (what the board wrote to its flash) at exit.
//
// Time: each emulated instruction advances the clock by its Cortex-M0+ cycle count at 125 MHz;
// the TIMER (ticks_us) reads that clock, WFI skips to the next alarm. Deterministic, and a lower
// bound on silicon: flash is zero-wait here (no XIP cache misses), cycle costs are approximate.
//
// Environment: RP2040_PROFILE=FILE writes executed instructions per PC (prof2sym.py sums them by
// function), RP2040_DEBUG=1 turns on rp2040js's log, PICO_DEBUG=1 shows what main.py printed
// before it was stopped.
//
// Devices (--devices JSON, all optional): {"i2c": {"id": 0, "sda": 4, "scl": 5},
//   "pca9685": [{"address": 64, "plugged": true, "power_pin": 22}], "sonars": [{"trigger": 6, "echo": 7,
//   "distance": 10000}], "temp_centi_c": 2000, "schedule": [[t_us, sonar, distance]],
//   "adc": {"pin": 28, "codes": [c0, c1, ...]}}
// A PCA9685 answers only while the firmware has routed the I2C block to those pins; its
// register writes are decoded into per-channel counts, one --trace line per burst (STOP).
// An HC-SR04 answers a trigger pulse >= 10 us with an echo 460 us after its falling edge, high
// for 2 d / c (c = 331.3 + 0.606 T m/s), or held 38 ms when nothing is in 2 cm..4 m.
// The ADC input on a pin (26..29: channels 0..3, rp2040js's RPADC): its n-th conversion returns
// codes[n] (12-bit), the last one from then on; one --trace line per conversion. A battery
// profile is given per conversion, not per emulated microsecond: the firmware's frame clock starts
// after boot and imports, at no fixed time from power-up, and the hand-worked frames need the
// readings lined up with the frames exactly (the test maps its time profile onto the readings).
import fs from 'fs';
import path from 'path';
import { fileURLToPath } from 'url';

const here = path.dirname(fileURLToPath(import.meta.url));
const pkg = path.join(here, 'node_modules', 'rp2040js', 'dist', 'esm');
const { RP2040, USBCDC, ConsoleLogger, LogLevel } = await import(path.join(pkg, 'index.js'));
const { SimulationClock } = await import(path.join(pkg, 'clock', 'simulation-clock.js'));
const ROM = await import(path.join(here, 'bootrom.mjs'));   // our own minimal bootrom

// Synchronous writes: process.exit() would drop what an asynchronous pipe write still holds.
const writeOut = (s) => fs.writeSync(1, s);
const writeErr = (s) => fs.writeSync(2, s);

const MHZ = 125;
const CYCLE_NS = 1000 / MHZ;
const FS_OFFSET = 0xa0000;      // RPI_PICO: littlefs2, 352 x 4096 B blocks at 0x100A0000
const FS_SIZE = 352 * 4096;

// ---------- arguments ----------
const opt = { firmware: null, fs: null, devices: null, trace: null, main: 0, stats: null, maxEmuS: 600, serial: false, saveFs: null };
const scripts = [];
const argv = process.argv.slice(2);
for (let i = 0; i < argv.length; i++) {
  const a = argv[i];
  const val = () => { if (i + 1 >= argv.length) fail(`${a} needs a value`); return argv[++i]; };
  if (a === '--firmware') opt.firmware = val();
  else if (a === '--fs') opt.fs = val();
  else if (a === '--devices') opt.devices = JSON.parse(fs.readFileSync(val(), 'utf8'));
  else if (a === '--trace') opt.trace = val();
  else if (a === '--main') opt.main = Number(val());
  else if (a === '--stats') opt.stats = val();
  else if (a === '--max-emu-s') opt.maxEmuS = Number(val());
  else if (a === '--serial') opt.serial = true;
  else if (a === '--save-fs') opt.saveFs = val();
  else if (a.startsWith('--')) fail(`unknown option ${a}`);
  else scripts.push(a);
}
function fail(msg) { writeErr(`run.mjs: ${msg}\n`); process.exit(2); }
if (!opt.firmware) fail('--firmware FILE (.uf2 or .bin) is required');
if (!(opt.main >= 0)) fail('--main takes emulated seconds >= 0');
if (opt.devices && opt.devices.adc) {
  const a = opt.devices.adc;
  if (!Number.isInteger(a.pin) || a.pin < 26 || a.pin > 29) fail(`adc.pin ${a.pin}: allowed 26..29 (ADC channels 0..3)`);
  if (!Array.isArray(a.codes) || !a.codes.length || !a.codes.every((c) => Number.isInteger(c) && c >= 0 && c <= 4095)) {
    fail('adc.codes: a non-empty list of 12-bit codes (0..4095)');
  }
}

// ---------- the chip and its flash ----------
let clock, mcu, cdc, resets = 0, resetRequested = false;
// A soft reset stops core 1 through the inter-core FIFO, which rp2040js does not model (it warns
// on the console): keep those two warnings off the board's stderr.
const consoleWarn = console.warn;
console.warn = (msg, ...rest) => { if (!/^Read from invalid SIO address: 5[08]$/.test(msg)) consoleWarn(msg, ...rest); };
const image = fs.readFileSync(opt.firmware);
function loadFirmware() {
if (opt.firmware.endsWith('.uf2')) {
  let blocks = 0;
  for (let off = 0; off + 512 <= image.length; off += 512) {   // UF2: magic, flags, addr @12, size @16, data @32
    const b = image.subarray(off, off + 512);
    if (b.readUInt32LE(0) !== 0x0a324655 || b.readUInt32LE(4) !== 0x9e5d5157) continue;
    const addr = b.readUInt32LE(12);
    if (addr < 0x10000000 || addr >= 0x10200000) continue;     // not flash (e.g. a RAM-only block)
    mcu.flash.set(b.subarray(32, 32 + b.readUInt32LE(16)), addr - 0x10000000);
    blocks++;
  }
  if (!blocks) fail(`${opt.firmware}: no RP2040 flash blocks in this UF2 file`);
} else {
  mcu.flash.set(image, 0);
}
}

// rp2040js has no QSPI flash model: littlefs writes go through the bootrom's flash_range_erase
// ('RE') and flash_range_program ('RP'), which we perform on the flash array and return from.
const ROM_ERASE = ROM.ADDRESS.RE, ROM_PROGRAM = ROM.ADDRESS.RP;
// A lookup of a code our bootrom does not serve: say which, and stop (the image would jump to 0).
function romMissing() {
  const c = mcu.core.registers[1];
  const tag = String.fromCharCode(c & 0xff, (c >> 8) & 0xff);
  writeErr(`run.mjs: the image asked the bootrom for '${tag}' (code 0x${c.toString(16)}), which our bootrom ` +
    `does not serve (it serves ${ROM.FUNCTIONS.join(' ')}: an image built by host/pico/firmware.py needs no ` +
    `more; a stock MicroPython release takes its float functions from the RP2040's ROM)\n`);
  process.exit(3);
}
function flashCall(pc) {
  const r = mcu.core.registers;
  if (pc === ROM_ERASE) mcu.flash.fill(0xff, r[0], r[0] + r[1]);          // (offset, count, ...)
  else for (let i = 0; i < r[2]; i++) mcu.flash[r[0] + i] &= mcu.readUint8(r[1] + i);  // NOR: 1 -> 0 only
  mcu.core.PC = mcu.core.LR & ~1;
}

// ---------- USB CDC, host side ----------
// rp2040js answers an armed OUT endpoint at once (0 bytes when we have nothing), and the
// firmware re-arms it: an interrupt every few us stealing cycles from code being timed. A real
// host NAKs until it has data; so do we: the read stays pending until bytes are queued.
const outgoing = [];
let armed = -1, connected = false, rx = '', deviceRead;
function pump() {
  while (outgoing.length && !cdc.txFIFO.full) cdc.txFIFO.push(outgoing.shift());
  if (armed >= 0 && !cdc.txFIFO.empty) { const n = armed; armed = -1; deviceRead(cdc.outEndpoint, n); }
}
let echoOut = false;                                  // --main: stream board output as it comes
function onSerialData(buf) {
  if (opt.serial) { writeRaw(Buffer.from(buf)); return; }
  const s = Buffer.from(buf).toString('latin1');
  if (echoOut) { writeOut(s.replace(/\r\n/g, '\n')); mainOut += s; } else rx += s;
}
function writeRaw(b) {                                // stdout may be a non-blocking pipe
  for (let off = 0; off < b.length;) {
    try { off += fs.writeSync(1, b, off); } catch (e) { if (e.code !== 'EAGAIN') throw e; }
  }
}

// Power-up: a fresh chip with the firmware and fsBytes (null: erased) in its flash, USB host side
// reattached. Run again on a watchdog reset, with the flash the board has written.
function powerOn(fsBytes) {
  clock = new SimulationClock(MHZ * 1e6);
  mcu = new RP2040(clock);
  mcu.loadBootrom(ROM.bootrom);
  mcu.logger = new ConsoleLogger(process.env.RP2040_DEBUG ? LogLevel.Debug : LogLevel.Error);
  loadFirmware();
  mcu.flash.fill(0xff, FS_OFFSET, FS_OFFSET + FS_SIZE);          // erased NOR; MicroPython formats it
  if (fsBytes) mcu.flash.set(fsBytes, FS_OFFSET);
  mcu.core.reset();                       // SP and PC from the ROM's vectors: boot through boot2
  mcu.peripherals[0x40058].onWatchdogTrigger = () => { resetRequested = true; };
  cdc = new USBCDC(mcu.usbCtrl);
  outgoing.length = 0; armed = -1; connected = false;
  deviceRead = mcu.usbCtrl.onEndpointRead;
  mcu.usbCtrl.onEndpointRead = (ep, size) => {
    if (ep === cdc.outEndpoint && cdc.txFIFO.empty && !outgoing.length) { armed = size; return; }
    deviceRead(ep, size); pump();
  };
  cdc.onDeviceConnected = () => { connected = true; };
  cdc.onSerialData = onSerialData;
  attachDevices();
}
const fsRegion = () => Buffer.from(mcu.flash.subarray(FS_OFFSET, FS_OFFSET + FS_SIZE));
let mainOut = '';
const send = (s) => { for (const c of Buffer.from(s, 'latin1')) outgoing.push(c); pump(); };

// ---------- devices ----------
const trace = opt.trace ? fs.openSync(opt.trace, 'w') : null;
const emuUs = () => Math.round(clock.nanos / 1000);
const record = (obj) => { if (trace) fs.writeSync(trace, JSON.stringify(obj) + '\n'); };
const dev = opt.devices || {};

function attachPCA9685(bus, chips) {
  // One register file per chip (NXP data sheet: MODE1 0x11 at power-on, pointer auto-increment
  // with MODE1.AI wrapping LED15_OFF_H -> MODE1, PRE_SCALE writable only asleep).
  const models = new Map();
  const powerOnRegs = (reg) => {
    reg.fill(0);
    reg[0x00] = 0x11; reg[0x01] = 0x04; reg[0xfe] = 0x1e;
    for (let ch = 0; ch < 16; ch++) reg[0x09 + 4 * ch] = 0x10;  // full OFF
  };
  for (const c of chips) {
    const reg = new Uint8Array(256);
    powerOnRegs(reg);
    const m = { reg, plugged: c.plugged !== false, ptr: 0, ledWrites: 0, writes: 0 };
    models.set(c.address, m);
    if (c.power_pin !== undefined) {
      // The chip's supply switched by a GPIO (a test rig's MOSFET): pin driven high = power off
      // (it NACKs); back low = power-on reset, registers as at power-up (MODE1 0x11: asleep).
      const pin = mcu.gpio[c.power_pin];
      pin.addListener(() => {
        const off = pin.outputEnable && pin.outputValue;
        if (off && m.plugged) m.plugged = false;
        else if (!off && !m.plugged) { powerOnRegs(m.reg); m.plugged = true; }
      });
    }
  }
  const i2c = mcu.i2c[bus.id];
  // rp2040js flushes the TX FIFO on an abort (a NACK) but never raises TX_EMPTY for it; the RP2040
  // does (an empty FIFO is at or below IC_TX_TL; datasheet 4.3.11, TX_ABRT flushes the FIFO), and
  // pico-sdk's blocking write waits for TX_EMPTY before it looks at the abort: without this a NACK
  // made machine.I2C wait out its 50 ms timeout (ETIMEDOUT, not silicon's EIO) and left TX_ABRT
  // set for the next transaction to trip over.
  const abort = i2c.abort.bind(i2c);
  i2c.abort = (reason) => { abort(reason); i2c.setInterrupts(1 << 4); };   // R_TX_EMPTY
  const routed = () => mcu.gpio[bus.sda].functionSelect === 3 && mcu.gpio[bus.scl].functionSelect === 3;
  const bitNs = () => (i2c.sclHighPeriod + i2c.sclLowPeriod) * CYCLE_NS;  // one SCL period, clk_sys counts
  let cur = null, first = false;
  const later = (bits, fn) => { const a = clock.createAlarm(fn); a.schedule(bits * bitNs()); };
  i2c.onStart = () => later(1, () => i2c.completeStart());
  i2c.onConnect = (address, mode) => later(9, () => {
    const m = models.get(address);
    cur = m && m.plugged && routed() ? m : null;
    first = mode === 0;                               // a write starts with the register pointer
    i2c.completeConnect(!!cur);
  });
  i2c.onWriteByte = (v) => later(9, () => {
    if (!cur) { i2c.completeWrite(false); return; }
    if (first) { cur.ptr = v; first = false; }
    else {
      const p = cur.ptr, asleep = cur.reg[0] & 0x10;
      if (p === 0xfe) { if (asleep) cur.reg[p] = Math.max(v, 3); }
      else if (p === 0x00) cur.reg[p] = v & 0x7f;      // RESTART: a 1 written clears it; only PWM stopped by SLEEP sets it
      else cur.reg[p] = v;
      if (p >= 0x06 && p <= 0x45) cur.ledWrites++;
      cur.ptr = cur.reg[0] & 0x20 ? (p === 0x45 ? 0 : p === 0xfe ? 0 : (p + 1) & 0xff) : p;
    }
    i2c.completeWrite(true);
  });
  i2c.onReadByte = () => later(9, () => {
    const v = cur ? cur.reg[cur.ptr] : 0xff;
    if (cur && cur.reg[0] & 0x20) cur.ptr = cur.ptr === 0x45 ? 0 : (cur.ptr + 1) & 0xff;
    i2c.completeRead(v);
  });
  i2c.onStop = () => later(1, () => {
    if (cur && cur.ledWrites) {
      const counts = [];
      for (let ch = 0; ch < 16; ch++) {                 // (OFF - ON) mod 4096; -1 full off, 4096 full on
        const r = cur.reg, b = 0x06 + 4 * ch;
        const on = r[b] | ((r[b + 1] & 0x0f) << 8), off = r[b + 2] | ((r[b + 3] & 0x0f) << 8);
        counts.push(r[b + 3] & 0x10 ? -1 : r[b + 1] & 0x10 ? 4096 : (off - on) & 0x0fff);
      }
      const address = [...models].find(([, m]) => m === cur)[0];
      record({ t: emuUs(), chip: address, prescale: cur.reg[0xfe], mode1: cur.reg[0], counts });
      cur.ledWrites = 0;
    }
    cur = null;
    i2c.completeStop();
  });
  return models;
}

function attachHCSR04(s, tempCentiC) {
  const echo = mcu.gpio[s.echo], trig = mcu.gpio[s.trigger];
  let rise = -1, busyUntil = -1;
  const alarm = clock.createAlarm(() => { echo.setInputValue(state === 1); if (state === 1) { state = 2; alarm.schedule(width * 1000); } });
  let state = 0, width = 0;
  s.pings = 0;
  echo.setInputValue(false);
  trig.addListener(() => {
    const high = trig.outputEnable && trig.outputValue, now = clock.nanos;
    if (high) { rise = now; return; }
    if (rise < 0 || now - rise < 10000 || now < busyUntil) return;   // short trigger, or still echoing
    rise = -1;
    const d = s.distance;
    const c = 33130000 + 606 * tempCentiC;                            // 0.01 mm/s
    width = d >= 200 && d <= 40000 ? Math.floor((2 * d * 10000000 + Math.floor(c / 2)) / c) : 38000;
    state = 1; s.pings++;
    busyUntil = now + (460 + width) * 1000;
    alarm.schedule(460 * 1000);
    record({ t: Math.round(now / 1000), ping: s.trigger, echo_us: width });
  });
}

function attachADC(a) {
  const adc = mcu.adc, ch = a.pin - 26, read = adc.onADCRead;
  let n = 0;
  adc.channelValues[ch] = a.codes[0];
  adc.onADCRead = (channel) => {
    if (channel === ch) {
      const code = a.codes[Math.min(n, a.codes.length - 1)];
      adc.channelValues[ch] = code;
      record({ t: emuUs(), adc: ch, n, code });
      n++;
    }
    read(channel);
  };
}

const sonars = dev.sonars || [];
function attachDevices() {
  if (dev.pca9685) attachPCA9685(dev.i2c || { id: 0, sda: 4, scl: 5 }, dev.pca9685);
  for (const s of sonars) attachHCSR04(s, dev.temp_centi_c ?? 2000);
  if (dev.adc) attachADC(dev.adc);
}
const schedule = (dev.schedule || []).slice().sort((a, b) => a[0] - b[0]);

// ---------- stepping ----------
let instructions = 0;
const profile = process.env.RP2040_PROFILE ? new Map() : null;   // PC -> executed count
function step(n) {
  // The chip, its clock and the count in locals (module bindings are context slots: a load or a
  // store each instruction); the clock is the same object throughout (powerOn runs between steps).
  const core = mcu.core, clk = clock, prof = profile;
  let executed = 0;
  for (let i = 0; i < n; i++) {
    if (core.waiting) {
      const dt = clk.nanosToNextAlarm;
      if (dt <= 0) { clk.tick(CYCLE_NS); continue; }
      clk.tick(dt); i += dt / CYCLE_NS;
      continue;
    }
    const pc = core.PC;
    if (pc < 0x4000) {
      if (pc === ROM_ERASE || pc === ROM_PROGRAM) { flashCall(pc); continue; }
      if (pc === ROM.NOT_FOUND) { instructions += executed; executed = 0; romMissing(); }
    }
    if (prof) prof.set(pc, (prof.get(pc) || 0) + 1);
    clk.tick(core.executeInstruction() * CYCLE_NS);
    executed++;
  }
  instructions += executed;
  while (schedule.length && schedule[0][0] * 1000 <= clock.nanos) {
    const [, k, d] = schedule.shift();
    sonars[k].distance = d;
  }
  pump();
}
function runUntil(done, emuSeconds) {
  const limit = clock.nanos + emuSeconds * 1e9;
  while (!done()) { if (clock.nanos > limit) return false; step(20000); }
  return true;
}
function expect(text, emuSeconds) {
  if (!runUntil(() => rx.includes(text), emuSeconds)) {
    throw new Error(`board silent: waited ${emuSeconds} emulated s for ${JSON.stringify(text)}, last output ${JSON.stringify(rx.slice(-300))}`);
  }
  const i = rx.indexOf(text), before = rx.slice(0, i);
  rx = rx.slice(i + text.length);
  return before;
}

// Raw-paste (Ctrl-A, Ctrl-E 'A' Ctrl-A): the board grants a window of bytes, and one more window
// each time it sends \x01; \x04 from it aborts. Then it compiles, runs, and sends out \x04 err \x04.
function runScript(code) {
  send('\x05A\x01');
  runUntil(() => rx.length >= 2, 5);
  if (!rx.startsWith('R\x01')) throw new Error(`board refused raw-paste: ${JSON.stringify(rx.slice(0, 40))}`);
  runUntil(() => rx.length >= 4, 5);
  const increment = rx.charCodeAt(2) | (rx.charCodeAt(3) << 8);
  rx = rx.slice(4);
  let window = increment, pos = 0;
  const data = Buffer.from(code, 'latin1');
  while (pos < data.length) {
    runUntil(() => window > 0 || rx.length > 0, 30);
    while (rx.length) {
      const c = rx.charCodeAt(0); rx = rx.slice(1);
      if (c === 1) window += increment; else if (c === 4) throw new Error('board aborted the paste');
    }
    const n = Math.min(window, data.length - pos);
    send(data.subarray(pos, pos + n).toString('latin1')); pos += n; window -= n;
  }
  send('\x04');
  expect('\x04', 30);                                         // end of paste acknowledged
  const out = expect('\x04', opt.maxEmuS), err = expect('\x04', opt.maxEmuS);
  expect('>', 5);
  return [out.replace(/\r\n/g, '\n'), err.replace(/\r\n/g, '\n')];
}

// ---------- serial mode ----------
async function serial() {
  let done = false, wall0 = Date.now(), emu0 = 0;
  const finish = () => {
    if (done) return;
    done = true;
    if (opt.saveFs) fs.writeFileSync(opt.saveFs, fsRegion());
    if (opt.stats) fs.writeFileSync(opt.stats, JSON.stringify({ emu_s: clock.nanos / 1e9, resets, instructions }));
    if (trace) fs.closeSync(trace);
    process.exit(0);
  };
  process.stdin.on('data', (b) => { for (const c of b) outgoing.push(c); pump(); });
  process.stdin.on('end', finish);
  process.on('SIGTERM', finish);
  process.on('SIGINT', finish);
  const slice = () => {
    if (done) return;
    const t0 = Date.now();
    while (Date.now() - t0 < 10) {
      // Paced: emulated time never runs ahead of wall time (an idle board would race through hours).
      const ahead = (clock.nanos - emu0) / 1e6 - (Date.now() - wall0);
      if (ahead > 2) { setTimeout(slice, Math.min(ahead, 10)); return; }
      if (ahead < -100) { wall0 = Date.now(); emu0 = clock.nanos; }   // fell behind: no catching up
      step(20000);
      if (resetRequested) {                  // watchdog reset: power up again with the flash as written
        resetRequested = false; resets++;
        powerOn(fsRegion());
        wall0 = Date.now(); emu0 = 0;
      }
    }
    setImmediate(slice);
  };
  slice();
}

// ---------- main ----------
powerOn(opt.fs ? fs.readFileSync(opt.fs) : null);
if (opt.serial) await serial();
else {
const host0 = Date.now();
let status = 0;
const stats = { scripts: [] };
if (!runUntil(() => connected, 20)) fail('the board never enumerated on USB (is this an RP2040 MicroPython image?)');
stats.boot_emu_s = clock.nanos / 1e9;
if (opt.main > 0) {
  writeOut(rx.replace(/\r\n/g, '\n'));
  echoOut = true;
  mainOut = rx; rx = '';
  runUntil(() => false, opt.main);
  if (/Traceback \(most recent call last\)/.test(mainOut)) status = 1;
} else {
  // Stop main.py if the image has one, as mpremote does: Ctrl-C until the friendly REPL answers.
  for (let k = 0; k < 50 && !rx.includes('>>> '); k++) { send('\x03'); runUntil(() => rx.includes('>>> '), 0.1); }
  if (process.env.PICO_DEBUG) writeErr(JSON.stringify(rx) + '\n');
  rx = '';
  send('\r\x01');
  expect('raw REPL; CTRL-B to exit\r\n>', 10);
  send('\x04');                              // soft reset from the raw REPL: a fresh heap, main.py not run
  expect('raw REPL; CTRL-B to exit\r\n>', 10);
  for (const file of scripts) {
    const e0 = clock.nanos, i0 = instructions, h0 = Date.now();
    const [out, err] = runScript(fs.readFileSync(file, 'latin1'));
    writeOut(out);
    if (err) { writeErr(err); status = 1; }
    stats.scripts.push({ file, emu_s: (clock.nanos - e0) / 1e9, host_s: (Date.now() - h0) / 1000, instructions: instructions - i0 });
    if (err) break;
  }
}
stats.emu_s = clock.nanos / 1e9;
stats.host_s = (Date.now() - host0) / 1000;
stats.instructions = instructions;
stats.pings = sonars.map((s) => s.pings);
if (opt.stats) fs.writeFileSync(opt.stats, JSON.stringify(stats));
if (profile) fs.writeFileSync(process.env.RP2040_PROFILE, [...profile].map(([pc, n]) => pc.toString(16) + ' ' + n).join('\n'));
if (trace) fs.closeSync(trace);
process.exit(status);
}
