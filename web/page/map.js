// The outcome map of the meter stick over finger 1's speed x mu_k/mu_s, computed in Web Workers
// (each with its own instance of the core), drawn as a grid of cells; a click or Enter on a cell
// loads that run.

import { COLORS, fitCanvas } from './draw.js';

/// The default resolution: 0.1 .. 1 m/s by 0.01 (the bands where the trick works are a few
/// hundredths of a m/s wide) x mu_k/mu_s 0.2 .. 1 by 0.05. Exact decimals (i / 100), as typed.
export const SPEEDS = Array.from({ length: 91 }, (_, i) => (10 + i) / 100);
export const RATIOS = Array.from({ length: 17 }, (_, j) => (20 + 5 * j) / 100);

const OUTCOME_COLORS = {
  0: COLORS.balanced, 1: COLORS.fell, 5: COLORS.unfinished, 6: COLORS.failed, '-1': COLORS.unfinished, '-2': '#444',
};
const OUTCOME_NAMES = { 0: 'Balanced', 1: 'Fell', 2: 'Held', 3: 'Slid', 4: 'Tipped', 5: 'Unfinished', 6: 'Failed', '-1': 'Unfinished', '-2': 'invalid' };

export class OutcomeMap {
  constructor({ canvas, status, time, cell, onLoad }) {
    this.canvas = canvas; this.status = status; this.time = time; this.cell = cell; this.onLoad = onLoad;
    this.grid = RATIOS.map(() => new Int8Array(SPEEDS.length).fill(-9));
    this.cursor = { i: 0, j: 8 };
    this.workers = [];
    this.current = null;
    this.base = null;
    canvas.addEventListener('click', (e) => {
      const c = this.cellAt(e);
      if (c) { this.cursor = c; this.load(); }
    });
    canvas.addEventListener('mousemove', (e) => {
      const c = this.cellAt(e);
      if (c) this.describe(c);
    });
    canvas.addEventListener('keydown', (e) => {
      const moves = { ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, 1], ArrowDown: [0, -1] };
      if (moves[e.key]) {
        const [di, dj] = moves[e.key];
        const step = e.shiftKey ? 10 : 1;
        this.cursor = {
          i: Math.max(0, Math.min(SPEEDS.length - 1, this.cursor.i + di * step)),
          j: Math.max(0, Math.min(RATIOS.length - 1, this.cursor.j + dj * step)),
        };
        this.describe(this.cursor);
        this.draw();
        e.preventDefault();
      } else if (e.key === 'Enter' || e.key === ' ') {
        this.load();
        e.preventDefault();
      }
    });
    canvas.addEventListener('focus', () => { this.describe(this.cursor); this.draw(); });
    canvas.addEventListener('blur', () => this.draw());
  }

  layout() {
    const { g, w, h } = fitCanvas(this.canvas, 0.34);
    const left = 70; const right = 150; const top = 10; const bottom = 46;
    return { g, w, h, left, top, pw: w - left - right, ph: h - top - bottom };
  }

  cellAt(e) {
    const r = this.canvas.getBoundingClientRect();
    const { left, top, pw, ph } = this.layout();
    const i = Math.floor(((e.clientX - r.left - left) / pw) * SPEEDS.length);
    // (layout() sizes the canvas to its box: CSS pixels throughout.)
    const j = RATIOS.length - 1 - Math.floor(((e.clientY - r.top - top) / ph) * RATIOS.length);
    if (i < 0 || i >= SPEEDS.length || j < 0 || j >= RATIOS.length) return null;
    return { i, j };
  }

  /// The centre of cell (i, j) in CSS pixels from the canvas's top left corner.
  cellCenter(i, j) {
    const { left, top, pw, ph } = this.layout();
    return [left + ((i + 0.5) * pw) / SPEEDS.length, top + ((RATIOS.length - 0.5 - j) * ph) / RATIOS.length];
  }

  describe({ i, j }) {
    const o = this.grid[j][i];
    const what = o === -9 ? 'not computed' : OUTCOME_NAMES[o];
    const muS = this.base ? this.base.muS : 0.6;
    this.cell.textContent = `speed ${SPEEDS[i]} m/s, mu_k/mu_s ${RATIOS[j].toFixed(2)} (mu-k ${+(RATIOS[j] * muS).toPrecision(6)}): ${what}`;
  }

  load() {
    if (!this.base) return;
    const { i, j } = this.cursor;
    this.onLoad({ speed: SPEEDS[i], muK: RATIOS[j] * this.base.muS });
  }

  /// Marks the run shown in the animation (speed, mu_k/mu_s), or null.
  setCurrent(current) {
    this.current = current;
    this.draw();
  }

  stop() {
    for (const w of this.workers) w.terminate();
    this.workers = [];
  }

  /// Computes the map for `base` = {given: [[flag, value]] other than speed and mu-k, muS,
  /// precision, lcpSize}; resolves with {runs, steps, seconds, workers}.
  compute(module, base) {
    this.stop();
    this.base = base;
    this.grid = RATIOS.map(() => new Int8Array(SPEEDS.length).fill(-9));
    const count = Math.max(1, Math.min(4, navigator.hardwareConcurrency || 2));
    const t0 = performance.now();
    let rowsDone = 0; let steps = 0; let finished = 0;
    this.time.textContent = '';
    this.status.textContent = `computing ${SPEEDS.length * RATIOS.length} runs in ${count} workers...`;
    this.draw();
    return new Promise((resolve, reject) => {
      for (let k = 0; k < count; k += 1) {
        const worker = new Worker(new URL('./map-worker.js', import.meta.url), { type: 'module' });
        this.workers.push(worker);
        worker.onmessage = (event) => {
          const msg = event.data;
          if (msg.kind === 'row') {
            this.grid[msg.j] = msg.outcomes;
            rowsDone += 1; steps += msg.steps;
            this.status.textContent = `computing: ${rowsDone} of ${RATIOS.length} rows`;
            this.draw();
          } else if (msg.kind === 'done') {
            finished += 1;
            if (finished === count) {
              const seconds = (performance.now() - t0) / 1000;
              const runs = SPEEDS.length * RATIOS.length;
              this.status.textContent = `${runs} runs (${(steps / 1e6).toFixed(2)} M steps) in ${seconds.toFixed(2)} s, ${count} workers`;
              this.time.textContent = seconds.toFixed(3);
              this.stop();
              resolve({ runs, steps, seconds, workers: count });
            }
          } else if (msg.kind === 'error') {
            this.status.textContent = `map failed: ${msg.message}`;
            this.stop();
            reject(new Error(msg.message));
          }
        };
        const rows = RATIOS.map((_, j) => j).filter((j) => j % count === k);
        worker.postMessage({
          kind: 'map', module, given: base.given, muS: base.muS, speeds: SPEEDS, ratios: RATIOS, rows,
          precision: base.precision, lcpSize: base.lcpSize,
        });
      }
    });
  }

  draw() {
    const { g, w, h, left, top, pw, ph } = this.layout();
    g.fillStyle = COLORS.paper; g.fillRect(0, 0, w, h);
    const cw = pw / SPEEDS.length; const ch = ph / RATIOS.length;
    for (let j = 0; j < RATIOS.length; j += 1) {
      for (let i = 0; i < SPEEDS.length; i += 1) {
        const o = this.grid[j][i];
        g.fillStyle = o === -9 ? '#eeeeea' : (OUTCOME_COLORS[o] || COLORS.unfinished);
        g.fillRect(left + i * cw, top + (RATIOS.length - 1 - j) * ch, Math.ceil(cw), Math.ceil(ch));
      }
    }
    g.strokeStyle = COLORS.ink; g.lineWidth = 1.5; g.strokeRect(left, top, pw, ph);
    g.fillStyle = COLORS.ink; g.font = '15px system-ui, "DejaVu Sans", sans-serif';
    g.textAlign = 'center'; g.textBaseline = 'top';
    for (let i = 0; i < SPEEDS.length; i += 10) g.fillText(String(SPEEDS[i]), left + (i + 0.5) * cw, top + ph + 5);
    g.fillText('finger 1 speed (m/s)', left + pw / 2, top + ph + 24);
    g.textAlign = 'right'; g.textBaseline = 'middle';
    for (let j = 0; j < RATIOS.length; j += 4) g.fillText(RATIOS[j].toFixed(2), left - 6, top + (RATIOS.length - 0.5 - j) * ch);
    g.save(); g.translate(16, top + ph / 2); g.rotate(-Math.PI / 2); g.textAlign = 'center';
    g.fillText('mu_k / mu_s', 0, 0); g.restore();
    // Legend.
    g.textAlign = 'left';
    [['Balanced', COLORS.balanced], ['Fell', COLORS.fell], ['Unfinished', COLORS.unfinished], ['not computed', '#eeeeea']]
      .forEach(([label, color], k) => {
        const y = top + 8 + k * 26;
        g.fillStyle = color; g.fillRect(left + pw + 12, y, 18, 18);
        g.strokeStyle = COLORS.ink; g.lineWidth = 1; g.strokeRect(left + pw + 12, y, 18, 18);
        g.fillStyle = COLORS.ink; g.fillText(label, left + pw + 36, y + 9);
      });
    if (this.current) {
      const { speed, ratio } = this.current;
      const i = Math.round(speed * 100) - 10; const j = (ratio - 0.2) / 0.05;
      if (i >= 0 && i < SPEEDS.length && j >= -0.5 && j <= RATIOS.length - 0.5) {
        const x = left + (i + 0.5) * cw; const y = top + (RATIOS.length - 0.5 - j) * ch;
        g.strokeStyle = COLORS.ink; g.lineWidth = 3;
        g.beginPath(); g.arc(x, y, Math.max(cw, 7), 0, 2 * Math.PI); g.stroke();
      }
    }
    if (document.activeElement === this.canvas) {
      const { i, j } = this.cursor;
      g.strokeStyle = '#ffbf00'; g.lineWidth = 4;
      g.strokeRect(left + i * cw - 2, top + (RATIOS.length - 1 - j) * ch - 2, cw + 4, ch + 4);
      g.strokeStyle = COLORS.ink; g.lineWidth = 1.5;
      g.strokeRect(left + i * cw - 2, top + (RATIOS.length - 1 - j) * ch - 2, cw + 4, ch + 4);
    }
  }
}
