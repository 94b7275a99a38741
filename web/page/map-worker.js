// A map worker: its own instance of the core; runs whole meter-stick runs without rows and posts
// each cell's outcome ({rows of the map}), or runs the benchmark.

import { instantiateCore } from './core.js';

let core = null;

self.onmessage = async (event) => {
  const msg = event.data;
  try {
    if (!core) core = await instantiateCore(msg.module);
    if (msg.kind === 'map') {
      // msg: {given: [[flag, value]...] without speed and mu-k, muS, speeds, ratios, rows: [j...], precision, lcpSize}
      for (const j of msg.rows) {
        const outcomes = new Int8Array(msg.speeds.length);
        let steps = 0;
        for (let i = 0; i < msg.speeds.length; i += 1) {
          const given = [...msg.given, ['speed', msg.speeds[i]], ['mu-k', msg.ratios[j] * msg.muS]];
          const made = core.create('meter-stick', given, msg.precision, msg.lcpSize);
          if (!made.ok) { outcomes[i] = -2; continue; }
          steps += core.run(1e9);
          const o = core.outcome();
          outcomes[i] = o ? o.code : -1;
        }
        self.postMessage({ kind: 'row', j, outcomes, steps });
      }
      self.postMessage({ kind: 'done' });
    } else if (msg.kind === 'bench') {
      // The slow meter stick, f32 6x6, run to its outcome again and again for msg.seconds.
      const given = [['x1', -0.35], ['speed', 0.1]];
      const t0 = performance.now();
      let steps = 0; let runs = 0; let outcome = null;
      while (performance.now() - t0 < msg.seconds * 1000) {
        core.create('meter-stick', given, 'f32', 6);
        steps += core.run(1e9);
        runs += 1;
        outcome = core.outcome();
      }
      const seconds = (performance.now() - t0) / 1000;
      self.postMessage({ kind: 'bench', steps, runs, seconds, outcome: outcome && outcome.name, checksum: core.checksum() });
    }
  } catch (e) {
    self.postMessage({ kind: 'error', message: String(e && e.message ? e.message : e) });
  }
};
