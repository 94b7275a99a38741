// A run's rows as they arrive (live from the core, or replayed from host-sim run's core.csv): the
// columns the plots need, kept in growing typed arrays, the last full row for the animation, and
// the switch events found in them, with the eq. 21 ratio where it applies. The rows have the
// columns of core.csv: t,x,y,theta,vx,vy,omega,support1_x,support1_y,support2_x,support2_y,
// mode1,mode2,pn1,pn2,pf1,pf2,along1,along2 (modes as codes: 0 separated, 1 sticking,
// 2 sliding+, 3 sliding-).

export const ROW = 19;
export const COL = {
  t: 0, x: 1, y: 2, theta: 3, vx: 4, vy: 5, omega: 6, s1x: 7, s1y: 8, s2x: 9, s2y: 10,
  mode1: 11, mode2: 12, pn1: 13, pn2: 14, pf1: 15, pf2: 16, along1: 17, along2: 18,
};
export const MODE_NAMES = ['separated', 'sticking', 'sliding+', 'sliding-'];
const KEPT = ['t', 'x', 'y', 'theta', 'vx', 'vy', 'omega', 's1x', 's2x'];

const isSliding = (m) => m === 2 || m === 3;

export class Trace {
  constructor() {
    this.n = 0;
    this.cap = 1024;
    this.cols = Object.fromEntries(KEPT.map((k) => [k, new Float64Array(this.cap)]));
    this.last = new Float64Array(ROW);
    this.events = [];
  }

  /// Appends the row at rows[offset .. offset + ROW].
  push(rows, offset = 0) {
    if (this.n === this.cap) {
      this.cap *= 2;
      for (const k of KEPT) {
        const grown = new Float64Array(this.cap);
        grown.set(this.cols[k]);
        this.cols[k] = grown;
      }
    }
    for (const k of KEPT) this.cols[k][this.n] = rows[offset + COL[k]];
    if (this.n > 0) this.findSwitches(rows, offset);
    this.last.set(rows.subarray ? rows.subarray(offset, offset + ROW) : rows.slice(offset, offset + ROW));
    this.n += 1;
  }

  /// A contact whose mode differs from the previous row's switched; a sticking contact that
  /// starts to slide while the other was sliding is an eq. 21 switch, ratio |along_other / along_this|
  /// at the step's start (as host-sim's `switches`).
  findSwitches(rows, offset) {
    const before = [this.last[COL.mode1], this.last[COL.mode2]];
    const after = [rows[offset + COL.mode1], rows[offset + COL.mode2]];
    const along = [rows[offset + COL.along1], rows[offset + COL.along2]];
    for (let i = 0; i < 2; i += 1) {
      if (after[i] === before[i]) continue;
      let ratio = null;
      if (before[i] === 1 && isSliding(after[i]) && isSliding(before[1 - i])) {
        ratio = Math.abs(along[1 - i] / along[i]);
      }
      this.events.push({
        t: rows[offset + COL.t], contact: i, mode: after[i], ratio, index: this.n,
        x: rows[offset + (i === 0 ? COL.s1x : COL.s2x)],
      });
    }
  }

  get time() {
    return this.n > 0 ? this.cols.t[this.n - 1] : 0;
  }
}
