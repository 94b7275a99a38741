// The page's sources of rows: a live run of the core (stepped to its outcome and, unless
// `after=0`, on past it until its bodies rest or leave the view) and a replayed run of
// `host-sim run`. Each is an object with `advance(n)` (rows taken), its `trace`, and `ended` /
// `done` once the judge has decided / nothing is left to step.

import { COL, Trace } from './trace.js';

/// A run goes on past its outcome (`after=0`: it stops there) until its bodies rest (every point
/// slower than REST_SPEED m/s for REST_TIME s), leave the view, or AFTER_SECONDS s have passed.
const AFTER_SECONDS = 5;
const REST_SPEED = 1e-3;
const REST_TIME = 0.2;

/// The fastest point's speed between two rows (m/s; a body's turning counted at 0.1 m from its
/// centre): from the velocities of a scene of one body, from the motion over the step for several.
function rowSpeed(trace, prev, rows, at, h) {
  if (trace.spatial) return Math.hypot(rows[at + 8], rows[at + 9], rows[at + 10]) + 0.1 * Math.hypot(rows[at + 11], rows[at + 12], rows[at + 13]);
  if (trace.bodies === 0) return Math.hypot(rows[at + COL.vx], rows[at + COL.vy]) + 0.1 * Math.abs(rows[at + COL.omega]);
  let v = 0;
  for (let b = 0; b < trace.bodies; b += 1) {
    const i = 1 + 3 * b;
    v = Math.max(v, (Math.hypot(rows[at + i] - prev[i], rows[at + i + 1] - prev[i + 1]) + 0.1 * Math.abs(rows[at + i + 2] - prev[i + 2])) / h);
  }
  return v;
}

/// A live run of `core` (made by core.create), drawn in `sceneView`, with the form's `options`
/// (`{precision, lcpSize, goOn}`). `ended` once the judge has
/// decided (outcome, checksum, counters and measured quantities as decided); then, `going` past
/// the outcome (the core's ms_step_past) until its bodies rest or leave the view; `done` when
/// nothing more is to be stepped.
export function liveSource(core, params, sceneView, options) {
  const shapes = core.shapes();
  const scene = core.current.name;
  const trace = new Trace(core.contacts(scene), shapes ? shapes.sizes.length : 0, core.isSpatial(scene) ? core.current.row : 0);
  trace.push(core.startRow());
  return {
    kind: 'live', scene, params, trace, shapes, view: sceneView, ended: false, outcome: null,
    going: false, done: false, judgedRow: null, judgedN: 0, restFor: 0,
    precision: options.precision, lcpSize: options.lcpSize,
    advance(n) {
      if (this.done) return 0;
      if (this.ended) return this.goOn(n);
      const rows = core.step(n);
      const taken = rows.length / trace.row;
      for (let k = 0; k < taken; k += 1) trace.push(rows, k * trace.row);
      const outcome = core.outcome();
      if (outcome) {
        this.ended = true;
        this.outcome = outcome;
        this.checksum = core.checksum();
        this.stats = core.stats();
        this.measured = core.measured();
        this.judgedRow = trace.last.slice();
        this.judgedN = trace.n;
        trace.judged = trace.whole;
        this.going = options.goOn;
        this.done = !this.going;
      }
      return taken;
    },
    /// Past the outcome: steps on until the bodies rest, leave the view or AFTER_SECONDS pass.
    goOn(n) {
      const rows = core.stepPast(n);
      const taken = rows.length / trace.row;
      const h = params.step;
      let k = 0;
      for (; k < taken && this.going; k += 1) {
        const slow = rowSpeed(trace, trace.last, rows, k * trace.row, h) < REST_SPEED;
        trace.push(rows, k * trace.row);
        this.restFor = slow ? this.restFor + h : 0;
        if (this.restFor >= REST_TIME || trace.time - this.judgedRow[0] >= AFTER_SECONDS || !this.view.inView(trace.last)) {
          this.going = false;
        }
      }
      if (taken === 0) this.going = false;
      this.done = !this.going;
      return k;
    },
  };
}

/// A run of host-sim run, replayed row by row.
export function replaySource(run) {
  const trace = new Trace(run.core.k); const reference = new Trace(run.core.k);
  const src = {
    kind: 'replay', scene: run.summary.scene, params: run.summary.parameters, trace, reference,
    ended: false, outcome: null, run, cursor: 0,
    advance(n) {
      let taken = 0;
      while (taken < n && this.cursor < run.core.n) {
        trace.push(run.core.rows, this.cursor * trace.row);
        if (run.reference && this.cursor < run.reference.n) reference.push(run.reference.rows, this.cursor * trace.row);
        this.cursor += 1; taken += 1;
      }
      if (this.cursor >= run.core.n) {
        this.ended = true;
        this.done = true;
        const c = run.summary.core;
        this.outcome = { name: c.outcome, text: c.outcome_detail ? `${c.outcome} (${c.outcome_detail})` : c.outcome };
      }
      return taken;
    },
    referenceRow() {
      return reference.n > 0 ? reference.last : null;
    },
  };
  src.advance(1);
  return src;
}
