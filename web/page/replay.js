// Replaying a run written by `host-sim run` (served by `host-sim serve --replay DIR` under
// replay/): replay/runs.json lists the runs; each has core.csv, reference.csv (the trajectory
// columns of trace.js, modes by name) and summary.json (scene, parameters, outcomes).

import { ROW } from './trace.js';

const MODE_CODES = { separated: 0, sticking: 1, 'sliding+': 2, 'sliding-': 3 };
const HEADER = 't,x,y,theta,vx,vy,omega,support1_x,support1_y,support2_x,support2_y,mode1,mode2,pn1,pn2,pf1,pf2,along1,along2';

/// The runs on offer, or null when the server has none ([{name, path}]).
export async function listRuns() {
  try {
    const r = await fetch('replay/runs.json', { cache: 'no-store' });
    if (!r.ok) return null;
    const j = await r.json();
    return Array.isArray(j.runs) && j.runs.length > 0 ? j : null;
  } catch {
    return null;
  }
}

/// Parses a trajectory CSV into rows of ROW numbers.
export function parseTrajectory(text, file) {
  const lines = text.split('\n').filter((l) => l.length > 0);
  if (lines.length === 0 || lines[0].trim() !== HEADER) {
    throw new Error(`${file}: not a trajectory of host-sim run (header ${JSON.stringify(lines[0] || '')})`);
  }
  const rows = new Float64Array((lines.length - 1) * ROW);
  for (let k = 1; k < lines.length; k += 1) {
    const cells = lines[k].split(',');
    if (cells.length !== ROW) throw new Error(`${file}, line ${k + 1}: ${cells.length} columns, expected ${ROW}`);
    for (let c = 0; c < ROW; c += 1) {
      const v = c === 11 || c === 12 ? MODE_CODES[cells[c]] : Number(cells[c]);
      if (v === undefined) throw new Error(`${file}, line ${k + 1}: unknown mode ${JSON.stringify(cells[c])}`);
      rows[(k - 1) * ROW + c] = v;
    }
  }
  return { rows, n: lines.length - 1 };
}

/// Loads one run: {name, summary, core: {rows, n}, reference: {rows, n}}.
export async function loadRun(run) {
  const get = async (file) => {
    const r = await fetch(`replay/${run.path}${file}`, { cache: 'no-store' });
    if (!r.ok) throw new Error(`replay/${run.path}${file}: ${r.status} ${r.statusText}`);
    return r.text();
  };
  const [core, reference, summary] = await Promise.all([get('core.csv'), get('reference.csv'), get('summary.json')]);
  return {
    name: run.name,
    summary: JSON.parse(summary),
    core: parseTrajectory(core, `${run.path}core.csv`),
    reference: parseTrajectory(reference, `${run.path}reference.csv`),
  };
}
