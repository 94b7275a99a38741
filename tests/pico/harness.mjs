#!/usr/bin/env node
// The Pico without a board (#23): runs the Pico firmware's .uf2, exactly as a teacher flashes it,
// on an emulated RP2040 (rp2040js, pinned in tests/pico/package.json), presses its buttons and
// records what its pins do. Prints ONE JSON object on stdout (the facts; the judging is done by
// the checker, tests/tests/pico_emu.rs, against the host core); diagnostics go to stderr.
//
// Usage: node tests/pico/harness.mjs --uf2 FILE [--presets N] [--max-cycles N] [--wall-s S]
//                                     [--idle-ticks N] [--uart-tcp PORT]
//   --presets N     preset button presses (GP15) before the start (0: the boot preset, slow)
//   --start-hold-ms MS  how long the start button stays low after its bounces (default 40: the
//                   rig starts on a press held steady for 20 ticks, as the preset button's;
//                   firmware/src/realtime.rs, `Buttons`, and rig/src/rig.rs)
//   --max-cycles N  cap on emulated cycles (default 2e9: 16 s at 125 MHz)
//   --wall-s S      cap on wall-clock seconds (default 120)
//   --idle-ticks N  the run counts as ended after N ticks without a scene step, or N ticks
//                   after the fault light came on (default 50)
//   --uart-tcp PORT bridge UART0 (GP0/GP1) to a TCP server on 127.0.0.1:PORT (0: a free
//                   port), for the host link (`host-sim monitor --port tcp:127.0.0.1:PORT`):
//                   no button is pressed, the run lasts until the client disconnects (or a cap)
//   --port-file F   with --uart-tcp, write {"port": N} to F once listening
//
// Boot: rp2040js ships no boot ROM, so the harness does what the ROM and the second-stage boot
// loader end with: VTOR at the application's vector table (0x10000100, after the 256-byte boot2
// that firmware/memory/rp2040.x places first), SP and PC from it. Only builds whose float
// arithmetic does not call the boot ROM run here (`builtins-float`, scripts/lib.sh).
//
// Pins (firmware/src/pico.rs): UART0 GP0/GP1, STEP GP2, DIR GP3, finger 1 lights GP6/7/8,
// finger 2 lights GP9/10/11 (sticking/sliding/separated), start GP14 (active low, pull-up),
// preset GP15 (active low, pull-up), the stack's third interface lights GP16/17/18 (the link
// build's), fault light GP25.
//
// Time: rp2040js counts Cortex-M0+ cycles; the harness advances the emulated clock by 8 ns per
// cycle (125 MHz, the Pico's core clock, firmware/src/pico.rs). A tick is found where the
// firmware finds it: the read of SYST_CSR that returns COUNTFLAG (firmware/src/realtime.rs,
// `syst.has_wrapped()`); the tick's work is the cycles from that read to the next SYST_CSR read
// (the loop back in its wait).

import { readFileSync, writeFileSync } from 'node:fs';
import { createServer } from 'node:net';
import { RP2040, GPIOPinState } from 'rp2040js';

const CORE_HZ = 125_000_000;
const NS_PER_CYCLE = 1e9 / CORE_HZ;
const FLASH_BASE = 0x1000_0000;
const APP_VECTORS = 0x1000_0100;
const UF2_MAGIC0 = 0x0a324655;
const UF2_MAGIC1 = 0x9e5d5157;
const UF2_MAGIC_END = 0x0ab16f30;
const UF2_FAMILY_PRESENT = 0x2000;
const RP2040_FAMILY = 0xe48bff56;
const SYST_CSR = 0x010; // offset in the PPB as rp2040js dispatches it (address & 0xfff)
const COUNTFLAG = 1 << 16;

const PIN = { tx: 0, rx: 1, step: 2, dir: 3, start: 14, preset: 15, fault: 25 };
const LIGHTS = [
  [6, 7, 8],
  [9, 10, 11],
];
const LIGHT_NAMES = ['sticking', 'sliding', 'separated'];
// The stack's block 2 / block 3 interface lights (the link build's, while the host runs the
// stack; the other two interfaces' are the fingers' LIGHTS).
const STACK_LIGHTS = [16, 17, 18];

function fail(msg) {
  process.stderr.write(`pico harness: ${msg}\n`);
  process.exit(2);
}

function parseArgs(argv) {
  const o = { uf2: null, presets: 0, startHoldMs: 40, maxCycles: 2e9, wallS: 120, idleTicks: 50, uartTcp: null, portFile: null };
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i];
    const v = () => {
      if (i + 1 >= argv.length) fail(`${a} needs a value`);
      return argv[++i];
    };
    const num = (s, min, max) => {
      const n = Number(s);
      if (!Number.isFinite(n) || n < min || n > max) fail(`${a} ${s}: not a number in ${min}..${max}`);
      return n;
    };
    if (a === '--uf2') o.uf2 = v();
    else if (a === '--presets') o.presets = num(v(), 0, 9);
    else if (a === '--start-hold-ms') o.startHoldMs = num(v(), 0, 1000);
    else if (a === '--max-cycles') o.maxCycles = num(v(), 1e6, 1e11);
    else if (a === '--wall-s') o.wallS = num(v(), 1, 3600);
    else if (a === '--idle-ticks') o.idleTicks = num(v(), 1, 1e6);
    else if (a === '--uart-tcp') o.uartTcp = num(v(), 0, 65535);
    else if (a === '--port-file') o.portFile = v();
    else fail(`unknown argument ${a}`);
  }
  if (!o.uf2) fail('--uf2 FILE is required');
  return o;
}

// Copies a .uf2's payloads into the flash image; checks every block's magic numbers, the RP2040
// family (when the block names one) and the flash range.
function loadUf2(bytes, flash) {
  if (bytes.length === 0 || bytes.length % 512 !== 0) fail(`.uf2 of ${bytes.length} bytes: not whole 512-byte blocks`);
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  let lowest = Infinity;
  let blocks = 0;
  for (let off = 0; off < bytes.length; off += 512) {
    const w = (i) => view.getUint32(off + i, true);
    if (w(0) !== UF2_MAGIC0 || w(4) !== UF2_MAGIC1 || w(508) !== UF2_MAGIC_END) fail(`block ${off / 512}: bad UF2 magic`);
    const flags = w(8);
    if (flags & 1) continue; // "not main flash"
    if (flags & UF2_FAMILY_PRESENT && w(28) !== RP2040_FAMILY) fail(`block ${off / 512}: family 0x${w(28).toString(16)}, not the RP2040's`);
    const addr = w(12);
    const size = w(16);
    if (size > 476 || addr < FLASH_BASE || addr + size > FLASH_BASE + flash.length) fail(`block ${off / 512}: ${size} bytes at 0x${addr.toString(16)} outside the flash`);
    flash.set(bytes.subarray(off + 32, off + 32 + size), addr - FLASH_BASE);
    lowest = Math.min(lowest, addr);
    blocks++;
  }
  if (lowest !== FLASH_BASE) fail(`the image starts at 0x${lowest.toString(16)}, not at the start of flash (boot2)`);
  return blocks;
}

const opts = parseArgs(process.argv.slice(2));
const mcu = new RP2040();
const clock = mcu.clock;
const logged = { warn: 0, error: 0, first: [] };
const note = (level) => (component, message) => {
  logged[level]++;
  if (logged.first.length < 5) logged.first.push(`${level} ${component}: ${message}`);
};
mcu.logger = { debug() {}, info() {}, warn: note('warn'), error: note('error') };

let blocks;
try {
  blocks = loadUf2(readFileSync(opts.uf2), mcu.flash);
} catch (e) {
  fail(`reading ${opts.uf2}: ${e.message}`);
}
const core = mcu.core;
core.VTOR = APP_VECTORS;
core.SP = mcu.readUint32(APP_VECTORS);
core.PC = mcu.readUint32(APP_VECTORS + 4) & ~1;
const boot = { blocks, vtor: APP_VECTORS, sp: core.SP, pc: core.PC };

// --- ticks: SYST_CSR reads -------------------------------------------------------------------
const ticks = []; // cycle at which the firmware saw each wrap
const tickWork = []; // cycles from that read to the next SYST_CSR read
let inTick = false;
const onTick = [];
const ppbRead = mcu.ppb.readUint32.bind(mcu.ppb);
mcu.ppb.readUint32 = (offset) => {
  const value = ppbRead(offset);
  if (offset === SYST_CSR) {
    const now = core.cycles;
    if (inTick) {
      tickWork.push(now - ticks[ticks.length - 1]);
      inTick = false;
    }
    if (value & COUNTFLAG) {
      ticks.push(now);
      inTick = true;
      for (const f of onTick) f(ticks.length - 1);
    }
  }
  return value;
};

// --- pins --------------------------------------------------------------------------------------
const level = new Map(); // pin -> 0/1 (driven outputs only)
const edges = []; // { pin, level, cycle, tick }
const stepPulse = { rises: [0, 0], minHigh: Infinity, minLow: Infinity, lastRise: null, lastFall: null };
const stepRisesPerTick = []; // STEP rises in each tick (index: tick)
const watched = [PIN.step, PIN.dir, ...LIGHTS.flat(), ...STACK_LIGHTS, PIN.fault];
for (const p of watched) {
  mcu.gpio[p].addListener((state) => {
    if (state !== GPIOPinState.High && state !== GPIOPinState.Low) return;
    const l = state === GPIOPinState.High ? 1 : 0;
    const prev = level.get(p) ?? 0; // an input (before the firmware drives it) counts as low
    level.set(p, l);
    if (prev === l) return;
    const now = core.cycles;
    if (p === PIN.step) {
      if (l === 1) {
        stepPulse.rises[level.get(PIN.dir) ?? 0]++;
        const k = ticks.length - 1;
        stepRisesPerTick[k] = (stepRisesPerTick[k] ?? 0) + 1;
        if (stepPulse.lastFall !== null) stepPulse.minLow = Math.min(stepPulse.minLow, now - stepPulse.lastFall);
        stepPulse.lastRise = now;
      } else {
        if (stepPulse.lastRise !== null) stepPulse.minHigh = Math.min(stepPulse.minHigh, now - stepPulse.lastRise);
        stepPulse.lastFall = now;
      }
      return; // pulses are counted, not listed
    }
    edges.push({ pin: p, level: l, cycle: now, tick: ticks.length - 1 });
  });
}
// The buttons: released (pull-up reads high) until pressed.
mcu.gpio[PIN.start].setInputValue(true);
mcu.gpio[PIN.preset].setInputValue(true);

// --- the button script, in ticks after the first tick -------------------------------------------
// Each press bounces: low and high for 0.5 to 1.8 ms each (across ticks, so the firmware samples
// them), then held low, then released.
const BOUNCE_NS = [0, 1.3e6, 2.1e6, 3.9e6, 4.4e6]; // low, high, low, high, low (held)
function press(pin, holdNs) {
  BOUNCE_NS.forEach((t, i) => {
    const a = clock.createAlarm(() => mcu.gpio[pin].setInputValue(i % 2 === 1));
    a.schedule(t);
  });
  clock.createAlarm(() => mcu.gpio[pin].setInputValue(true)).schedule(BOUNCE_NS.at(-1) + holdNs);
}
const PRESET_EVERY = 100; // ticks between preset presses (> 2 x the firmware's 20-tick debounce)
const script = new Map();
for (let i = 0; i < opts.presets; i++) script.set(20 + i * PRESET_EVERY, () => press(PIN.preset, 40e6));
const startAtTick = 20 + opts.presets * PRESET_EVERY + 20;
script.set(startAtTick, () => press(PIN.start, opts.startHoldMs * 1e6));
if (opts.uartTcp === null) onTick.push((k) => script.get(k)?.());

// --- UART0: what rp2040js 1.4.1 leaves out -------------------------------------------------------
// It answers a read of a register it does not model with 0xffffffff; rp2040-hal's `read_raw`
// reads UARTRSR (0x04) on every empty poll, and all ones there is an overrun, every time. The
// bridge loses nothing: UARTRSR reads 0 (no receive error), its clear (a write) and UARTDMACR
// (0x48, DMA requests: no DMA here) are accepted. Every other unmodelled access is counted in
// `emulated.logged` (the checker requires none).
const UARTRSR = 0x04;
const UARTDMACR = 0x48;
for (const u of mcu.uart) {
  const read = u.readUint32.bind(u);
  const write = u.writeUint32.bind(u);
  u.readUint32 = (offset) => (offset === UARTRSR ? 0 : read(offset));
  u.writeUint32 = (offset, value) => {
    if (offset !== UARTRSR && offset !== UARTDMACR) write(offset, value);
  };
}

// --- UART0 <-> TCP (the host link) ------------------------------------------------------------
let uart = null;
if (opts.uartTcp !== null) {
  uart = { socket: null, rx: [], rxHead: 0, txBytes: 0, rxBytes: 0, closed: false, port: null };
  const server = createServer((socket) => {
    if (uart.socket) {
      socket.destroy();
      return;
    }
    uart.socket = socket;
    socket.on('data', (d) => {
      for (const b of d) uart.rx.push(b);
    });
    socket.on('close', () => (uart.closed = true));
    socket.on('error', () => (uart.closed = true));
  });
  await new Promise((resolve) => server.listen(opts.uartTcp, '127.0.0.1', resolve));
  uart.server = server;
  uart.port = server.address().port;
  process.stderr.write(`pico harness: UART0 on tcp:127.0.0.1:${uart.port}\n`);
  if (opts.portFile) writeFileSync(opts.portFile, JSON.stringify({ port: uart.port }) + '\n');
  mcu.uart[0].onByte = (b) => {
    uart.txBytes++;
    uart.socket?.write(Uint8Array.of(b));
  };
  // Received bytes enter UART0's receive FIFO at the link's 921,600 baud (10 bits a byte), as
  // the FIFO takes them (the bridge holds the rest: no overrun).
  const BYTE_NS = 1e10 / 921_600;
  const rxAlarm = clock.createAlarm(() => {
    if (uart.rxHead < uart.rx.length && !mcu.uart[0].rxFIFO.full) {
      mcu.uart[0].feedByte(uart.rx[uart.rxHead++]);
      if (uart.rxHead === uart.rx.length) uart.rx.length = uart.rxHead = 0;
      uart.rxBytes++;
    }
    rxAlarm.schedule(BYTE_NS);
  });
  rxAlarm.schedule(BYTE_NS);
}

// --- run ---------------------------------------------------------------------------------------
const wallStart = Date.now();
const wallEnd = wallStart + opts.wallS * 1000;
let stopped = null;
let startTick = null; // the tick in which DIR went high (the run's start)
let lastStepTick = null; // the last tick whose work looked like a scene step
let faultTick = null;
const STEP_WORK = { threshold: null };

function endOfRun() {
  const k = ticks.length - 1;
  if (startTick === null) {
    const dirUp = edges.find((e) => e.pin === PIN.dir && e.level === 1);
    if (dirUp) startTick = dirUp.tick;
  }
  if (faultTick === null) {
    const f = edges.find((e) => e.pin === PIN.fault && e.level === 1);
    if (f) faultTick = f.tick;
  }
  if (faultTick !== null && k - faultTick >= opts.idleTicks) return true;
  if (startTick === null || uart) return false;
  if (STEP_WORK.threshold === null) {
    // Ticks before the start do no scene step: ten times their median is the threshold (a
    // preset press loads a scene: a few ticks above the median).
    const before = tickWork.slice(0, startTick).sort((a, b) => a - b);
    if (before.length === 0) return false;
    STEP_WORK.threshold = 10 * before[before.length >> 1];
  }
  for (let i = (lastStepTick ?? startTick) + 1; i < tickWork.length; i++) {
    if (tickWork[i] > STEP_WORK.threshold) lastStepTick = i;
  }
  return lastStepTick !== null && tickWork.length - 1 - lastStepTick >= opts.idleTicks;
}

const BATCH = 200_000;
for (;;) {
  for (let i = 0; i < BATCH; i++) {
    if (core.waiting) {
      const n = clock.nanosToNextAlarm;
      if (!(n > 0) || !Number.isFinite(n)) break;
      clock.tick(n);
      core.cycles += Math.round(n / NS_PER_CYCLE);
    } else {
      clock.tick(core.executeInstruction() * NS_PER_CYCLE);
    }
  }
  if (uart) {
    await new Promise((r) => setImmediate(r)); // let the socket move bytes
    if (uart.closed) {
      stopped = 'link-closed';
      break;
    }
  }
  if (endOfRun()) {
    stopped = faultTick !== null ? 'fault' : 'run-ended';
    break;
  }
  if (core.cycles >= opts.maxCycles) {
    stopped = 'cycle-cap';
    break;
  }
  if (Date.now() >= wallEnd) {
    stopped = 'wall-cap';
    break;
  }
  if (ticks.length === 0 && core.cycles > 200e6) {
    stopped = 'no-ticks';
    break;
  }
}
const wallS = (Date.now() - wallStart) / 1000;
if (uart) {
  uart.socket?.destroy();
  uart.server.close();
}

// --- results -------------------------------------------------------------------------------------
const ns = (c) => (c === Infinity || c === null ? null : Math.round(c * NS_PER_CYCLE));
const stats = (xs) => {
  if (xs.length === 0) return null;
  let min = Infinity;
  let max = -Infinity;
  let sum = 0;
  for (const x of xs) {
    min = Math.min(min, x);
    max = Math.max(max, x);
    sum += x;
  }
  return { n: xs.length, mean: sum / xs.length, min, max };
};
// Intervals between the ticks the loop saw, from the second (the first wrap follows SysTick's
// start, firmware/src/realtime.rs `systick::start`, not a whole period).
const intervals = [];
for (let i = 2; i < ticks.length; i++) intervals.push(ticks[i] - ticks[i - 1]);
const period = stats(intervals);
const periodCycles = Math.round(mcu.ppb.systickReload + 1);

// The lights tick by tick from the start: how many of each finger's lights were on at the end
// of each tick while running (start tick .. last step tick, or the fault tick).
let lightsPerFinger = null;
const runEnd = faultTick ?? lastStepTick;
if (startTick !== null && runEnd !== null) {
  const on = new Map();
  let e = 0;
  const counts = [new Set(), new Set()];
  for (let k = 0; k <= runEnd; k++) {
    while (e < edges.length && edges[e].tick <= k) {
      on.set(edges[e].pin, edges[e].level);
      e++;
    }
    if (k < startTick) continue;
    if (faultTick !== null && k >= faultTick) break;
    LIGHTS.forEach((pins, f) => counts[f].add(pins.reduce((n, p) => n + (on.get(p) ?? 0), 0)));
  }
  lightsPerFinger = counts.map((s) => [...s].sort());
}

const runWork = startTick !== null ? tickWork.slice(startTick, (runEnd ?? tickWork.length - 1) + 1) : [];
const stepWork = stats(runWork.slice(1)); // the start tick lights the lights; the steps follow
const pinName = (p) => {
  for (const [f, pins] of LIGHTS.entries()) {
    const i = pins.indexOf(p);
    if (i >= 0) return `GP${p} finger ${f + 1} ${LIGHT_NAMES[i]}`;
  }
  const i = STACK_LIGHTS.indexOf(p);
  if (i >= 0) return `GP${p} interface 2 ${LIGHT_NAMES[i]}`;
  return { [PIN.dir]: `GP${p} DIR`, [PIN.fault]: `GP${p} fault` }[p] ?? `GP${p}`;
};

const result = {
  uf2: opts.uf2,
  rp2040js: JSON.parse(readFileSync(new URL('./node_modules/rp2040js/package.json', import.meta.url))).version,
  boot,
  stopped,
  emulated: {
    cycles: core.cycles,
    seconds_at_125mhz: core.cycles / CORE_HZ,
    clk_sys_hz: mcu.clkSys,
    wall_s: wallS,
    mcycles_per_wall_s: core.cycles / 1e6 / Math.max(wallS, 1e-3),
    logged,
  },
  ticks: {
    count: ticks.length,
    systick_period_cycles: periodCycles,
    first_cycle: ticks[0] ?? null,
    interval_cycles: period,
    jitter_cycles: period ? period.max - period.min : null,
    jitter_ns: period ? ns(period.max - period.min) : null,
  },
  buttons: { presets: opts.presets, start_pressed_at_tick: startAtTick, bounce_ns: BOUNCE_NS, start_hold_ms: opts.startHoldMs },
  run: {
    start_tick: startTick,
    last_step_tick: lastStepTick,
    fault_tick: faultTick,
    step_work_threshold_cycles: STEP_WORK.threshold,
    // Work per tick from the start tick (index 0) to the run's end, cycles.
    tick_work_cycles: runWork,
    cycles_per_step: stepWork,
    margin_at_125mhz: stepWork
      ? { period_cycles: periodCycles, worst_used: stepWork.max / periodCycles, worst_spare_cycles: periodCycles - stepWork.max }
      : null,
  },
  step: {
    pulses_dir_high: stepPulse.rises[1],
    pulses_dir_low: stepPulse.rises[0],
    min_high_ns: ns(stepPulse.minHigh),
    min_low_ns: ns(stepPulse.minLow),
    // STEP rises in each tick from the start tick (index 0) to the run's end.
    rises_per_tick:
      startTick !== null ? Array.from({ length: (runEnd ?? ticks.length - 1) - startTick + 1 }, (_, i) => stepRisesPerTick[startTick + i] ?? 0) : [],
  },
  dir_level: level.get(PIN.dir) ?? null,
  fault_level: level.get(PIN.fault) ?? null,
  lights_on_per_finger_while_running: lightsPerFinger,
  // Every edge of DIR, the lights and the fault light, with the tick it happened in.
  edges: edges.map((e) => ({ ...e, name: pinName(e.pin) })),
  // With the link: the work of every tick (cycles, index: tick), for the checker to pick a run's
  // steps out by the edges of its lights.
  uart: uart ? { port: uart.port, tx_bytes: uart.txBytes, rx_bytes: uart.rxBytes, tick_work_cycles: tickWork } : null,
};
// Exit once stdout is flushed (a pipe takes 64 KiB at a time).
process.stdout.write(JSON.stringify(result) + '\n', () => process.exit(0));
