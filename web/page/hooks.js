// The page's hooks for the browser test and the console (`window.meterstick`): the live run's
// trajectory (every step; the test shows the first step that differs from the host's), its last
// and shown rows, the drawing's extent, the CSV offered, and the map's outcome code at a cell.

/// The hooks over the page's state `S` (its runs A and B), the two drawings and the map.
export function testHooks(S, shownView, viewB, map) {
  return {
    trace() {
      const tr = S.source && S.source.trace;
      if (!tr) return null;
      // A scene of several bodies keeps no velocities (x, y, theta: the top body's).
      // The judged run (the rows up to the outcome; not those after it).
      const n = S.source.judgedN || tr.n;
      const pick = (k) => (tr.cols[k] ? Array.from(tr.cols[k].subarray(0, n)) : []);
      return { t: pick('t'), x: pick('x'), y: pick('y'), theta: pick('theta'), vx: pick('vx'), vy: pick('vy'), omega: pick('omega') };
    },
    /// The shown run's last row (a scene of several bodies: t, then each body's x, y, theta).
    lastRow() {
      const src = S.source;
      if (!src) return null;
      return Array.from(src.judgedRow || src.trace.last);
    },
    /// The row shown last (past the outcome when the run went on), of run A or run B (`b`).
    shownRow(b = false) {
      const src = b ? S.other : S.source;
      return src ? Array.from(src.trace.last) : null;
    },
    /// The drawing of run A (or B): its extent (m) and the least room between a body and its edge
    /// over every frame drawn (px; negative: a body was out of the drawing), the bodies' sizes.
    view(b = false) {
      const v = b ? viewB : shownView();
      return { extent: v.extent(), worst: v.worst, sizes: v.shapes ? v.shapes.sizes : null };
    },
    /// The CSV the download button offers (run A, or B).
    csv(b = false) {
      const src = b ? S.other : S.source;
      return src && src.kind === 'live' ? src.trace.csv() : null;
    },
    /// The shown scene's contacts, as the description names them, and the last row's length.
    contacts() {
      const src = S.source;
      return src ? { names: S.core.scene(src.scene).contacts, row: src.trace.last.length } : null;
    },
    /// The drawing's pixels, read back (a scene in three dimensions: how many colours, the colour
    /// at the body's centre, the body's, the plane's and the background's; view3d.js `pixels`).
    pixels() {
      const v = shownView();
      return v.pixels ? v.pixels() : null;
    },
    mapOutcome(i, j) {
      return map.grid[j] ? map.grid[j][i] : null;
    },
    mapCellCenter(i, j) {
      return map.cellCenter(i, j);
    },
  };
}
