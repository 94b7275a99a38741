// Replaying a run written by `host-sim run` (served by `host-sim serve --replay DIR` under
// replay/): replay/runs.json lists the runs; each has core.csv, reference.csv (the trajectory
// columns of trace.js for the scene's contacts, modes by name) and summary.json (scene,
// parameters, outcomes).

import { columns } from './trace.js';

const MODE_CODES = { separated: 0, sticking: 1, 'sliding+': 2, 'sliding-': 3 };

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

/// Parses a trajectory CSV of k contacts into rows ({rows, n, k}).
export function parseTrajectory(text, file, k) {
  const lines = text.split('\n').filter((l) => l.length > 0);
  const header = columns(k);
  if (lines.length === 0 || lines[0].trim() !== header.join(',')) {
    throw new Error(`${file}: not a trajectory of host-sim run with ${k} contacts (header ${JSON.stringify(lines[0] || '')})`);
  }
  const row = header.length;
  const isMode = (c) => c >= 7 + 2 * k && c < 7 + 3 * k;
  const rows = new Float64Array((lines.length - 1) * row);
  for (let j = 1; j < lines.length; j += 1) {
    const cells = lines[j].split(',');
    if (cells.length !== row) throw new Error(`${file}, line ${j + 1}: ${cells.length} columns, expected ${row}`);
    for (let c = 0; c < row; c += 1) {
      const v = isMode(c) ? MODE_CODES[cells[c]] : Number(cells[c]);
      if (v === undefined) throw new Error(`${file}, line ${j + 1}: unknown mode ${JSON.stringify(cells[c])}`);
      rows[(j - 1) * row + c] = v;
    }
  }
  return { rows, n: lines.length - 1, k };
}

/// Loads one run: {name, summary, core: {rows, n, k}, reference: {rows, n, k} | null}; `contactsOf`
/// gives a scene's number of contacts. A scene without an independent reference has no
/// reference.csv.
export async function loadRun(run, contactsOf) {
  const get = async (file, optional = false) => {
    const r = await fetch(`replay/${run.path}${file}`, { cache: 'no-store' });
    if (optional && r.status === 404) return null;
    if (!r.ok) throw new Error(`replay/${run.path}${file}: ${r.status} ${r.statusText}`);
    return r.text();
  };
  const summary = JSON.parse(await get('summary.json'));
  const k = contactsOf(summary.scene);
  if (!k) throw new Error(`replay/${run.path}summary.json: unknown scene ${JSON.stringify(summary.scene)}`);
  const [core, reference] = await Promise.all([get('core.csv'), get('reference.csv', true)]);
  return {
    name: run.name,
    summary,
    core: parseTrajectory(core, `${run.path}core.csv`, k),
    reference: reference === null ? null : parseTrajectory(reference, `${run.path}reference.csv`, k),
  };
}
