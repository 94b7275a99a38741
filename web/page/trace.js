// A run's rows as they arrive (live from the core, or replayed from host-sim run's core.csv): the
// columns the plots need, kept in growing typed arrays, the last full row for the animation, and
// the switch events found in them, with the eq. 21 ratio where it applies. A scene with K contacts
// has rows of 7 + 6K numbers, the columns of core.csv: t,x,y,theta,vx,vy,omega, then each
// contact's support<i>_x,support<i>_y, then mode<i>, pn<i>, pf<i>, along<i> each over the contacts
// (modes as codes: 0 separated, 1 sticking, 2 sliding+, 3 sliding-).

export const COL = { t: 0, x: 1, y: 2, theta: 3, vx: 4, vy: 5, omega: 6 };
export const MODE_NAMES = ['separated', 'sticking', 'sliding+', 'sliding-'];
const STATE = ['t', 'x', 'y', 'theta', 'vx', 'vy', 'omega'];

/// Numbers per row for k contacts.
export const rowLength = (k) => 7 + 6 * k;

/// core.csv's column names for k contacts (host-sim's csv_header).
export function columns(k) {
  const names = [...STATE];
  for (let i = 1; i <= k; i += 1) names.push(`support${i}_x`, `support${i}_y`);
  for (const group of ['mode', 'pn', 'pf', 'along']) for (let i = 1; i <= k; i += 1) names.push(`${group}${i}`);
  return names;
}

/// Where contact i's (0-based) numbers are in a row of k contacts.
export function contactColumns(k, i) {
  return { sx: 7 + 2 * i, sy: 8 + 2 * i, mode: 7 + 2 * k + i, pn: 7 + 3 * k + i, pf: 7 + 4 * k + i, along: 7 + 5 * k + i };
}

const isSliding = (m) => m === 2 || m === 3;

/// Numbers per row of a scene of several bodies: t, then each of up to 3 bodies' x, y, theta.
export const BODIES_ROW = 10;

/// The columns of a row of a scene in three dimensions (web/src/spatial.rs `write_row`): t, each
/// of three bodies' state (body 0's unnumbered, then b2..., b3...: NaN past the scene's bodies),
/// then each contact.
const SPATIAL_STATE = ['t', 'x', 'y', 'z', 'qw', 'qx', 'qy', 'qz', 'vx', 'vy', 'vz', 'wx', 'wy', 'wz'];
const SPATIAL_BODIES = 3;
function spatialColumns(row) {
  const names = [...SPATIAL_STATE];
  for (let b = 2; b <= SPATIAL_BODIES; b += 1) for (const c of SPATIAL_STATE.slice(1)) names.push(`b${b}${c}`);
  for (let i = 1; names.length < row; i += 1) {
    for (const c of ['px', 'py', 'pz', 'nx', 'ny', 'nz', 'tx', 'ty', 'tz', 'mode', 'pn', 'pf']) names.push(`${c}${i}`);
  }
  return names;
}

/// The most numbers a trace keeps of whole rows for its CSV (32 MB); the plots' columns go on.
const MAX_KEPT = 1 << 22;

export class Trace {
  /// An empty trace of a scene with k contacts, or of `bodies` bodies (k = 0): rows of t and each
  /// body's x, y, theta (body 0 the lowest), kept as b<i>x, b<i>y, b<i>theta (1-based; x, y and
  /// theta are the top body's).
  constructor(k, bodies = 0, spatialRow = 0) {
    this.spatial = spatialRow > 0;
    // A scene in three dimensions keeps its contacts in its rows, not as a planar scene's columns.
    this.k = this.spatial ? 0 : k;
    bodies = this.spatial ? 0 : bodies;
    this.bodies = bodies;
    this.row = this.spatial ? spatialRow : bodies > 0 ? BODIES_ROW : rowLength(k);
    this.at = Array.from({ length: this.k }, (_, i) => contactColumns(this.k, i));
    if (this.spatial) {
      // A scene in three dimensions (web/src/spatial.rs): t, position, orientation, velocity,
      // angular velocity, then each contact.
      this.kept = SPATIAL_STATE.map((name, c) => [name, c]);
    } else if (bodies > 0) {
      const top = 1 + 3 * (bodies - 1);
      this.kept = [['t', 0], ['x', top], ['y', top + 1], ['theta', top + 2]];
      for (let b = 0; b < bodies; b += 1) this.kept.push([`b${b + 1}x`, 1 + 3 * b], [`b${b + 1}y`, 2 + 3 * b], [`b${b + 1}theta`, 3 + 3 * b]);
    } else {
      this.kept = [...STATE.map((name, c) => [name, c]), ...this.at.map((c, i) => [`s${i + 1}x`, c.sx])];
    }
    this.n = 0;
    this.cap = 1024;
    this.cols = Object.fromEntries(this.kept.map(([name]) => [name, new Float64Array(this.cap)]));
    this.last = new Float64Array(this.row);
    this.events = [];
    // Every whole row (for the CSV), up to MAX_KEPT numbers; `judged`: the rows up to the
    // outcome (the rows after it went on past the outcome), null while the run goes on.
    this.rows = new Float64Array(64 * this.row);
    this.whole = 0;
    this.judged = null;
  }

  /// The CSV of the rows kept: core.csv's columns (a scene of several bodies: t and each body's
  /// x, y, theta), and `after_outcome` (1 for a row past the outcome).
  csv() {
    const names = this.spatial ? spatialColumns(this.row) : this.bodies > 0
      ? ['t', ...Array.from({ length: this.bodies }, (_, b) => [`x${b + 1}`, `y${b + 1}`, `theta${b + 1}`]).flat()]
      : columns(this.k);
    const width = this.bodies > 0 ? 1 + 3 * this.bodies : this.row;
    const lines = [[...names, 'after_outcome'].join(',')];
    for (let i = 0; i < this.whole; i += 1) {
      const r = this.rows.subarray(i * this.row, i * this.row + width);
      lines.push(`${Array.from(r, String).join(',')},${this.judged !== null && i >= this.judged ? 1 : 0}`);
    }
    return `${lines.join('\n')}\n`;
  }

  /// Appends the row at rows[offset .. offset + this.row].
  push(rows, offset = 0) {
    if (this.n === this.cap) {
      this.cap *= 2;
      for (const [name] of this.kept) {
        const grown = new Float64Array(this.cap);
        grown.set(this.cols[name]);
        this.cols[name] = grown;
      }
    }
    for (const [name, c] of this.kept) this.cols[name][this.n] = rows[offset + c];
    if ((this.whole + 1) * this.row <= MAX_KEPT) {
      if ((this.whole + 1) * this.row > this.rows.length) {
        const grown = new Float64Array(Math.min(MAX_KEPT, 2 * this.rows.length));
        grown.set(this.rows);
        this.rows = grown;
      }
      for (let c = 0; c < this.row; c += 1) this.rows[this.whole * this.row + c] = rows[offset + c];
      this.whole += 1;
    }
    if (this.n > 0) this.findSwitches(rows, offset);
    this.last.set(rows.subarray ? rows.subarray(offset, offset + this.row) : rows.slice(offset, offset + this.row));
    this.n += 1;
  }

  /// A contact whose mode differs from the previous row's switched. With two contacts, a sticking
  /// contact that starts to slide while the other was sliding is an eq. 21 switch, ratio
  /// |along_other / along_this| at the step's start (as host-sim's `switches`).
  findSwitches(rows, offset) {
    for (let i = 0; i < this.k; i += 1) {
      const c = this.at[i];
      const before = this.last[c.mode]; const after = rows[offset + c.mode];
      if (after === before) continue;
      let ratio = null;
      if (this.k === 2) {
        const other = this.at[1 - i];
        if (before === 1 && isSliding(after) && isSliding(this.last[other.mode])) {
          ratio = Math.abs(rows[offset + other.along] / rows[offset + c.along]);
        }
      }
      this.events.push({ t: rows[offset + COL.t], contact: i, mode: after, ratio, index: this.n, x: rows[offset + c.sx] });
    }
  }

  get time() {
    return this.n > 0 ? this.cols.t[this.n - 1] : 0;
  }
}
