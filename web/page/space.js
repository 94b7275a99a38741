// The plots of a scene in three dimensions beside its drawing in perspective (view3d.js), in the
// page's three plot canvases: the centre of mass's x and y over t; the paper's kind of plot, the
// speed v of the centre of mass and R omega over t (the curling stone's meet zero together; a
// ball rolls once v = R omega); the height z over t.

import { COLORS, CONTACT_COLORS, drawPlot } from './draw.js';
import { niceCeil, scaled } from './words.js';

/// The captions of the three plots for a scene in three dimensions.
export function spatialCaptions($) {
  $('cap-positions').textContent = 'Position of the centre of mass: x (blue) and y (orange), m, over t (s)';
  $('cap-angle').textContent = 'Speed v of the centre of mass (black) and R omega (green), m/s, over t (s): '
    + 'R the radius (the rod: half its length), omega the spin about the vertical (a ball: its whole angular speed)';
  $('cap-height').textContent = 'Height z of the centre of mass (cm) over t (s)';
}

/// R omega of each row: `solid` [code, a, b, c] (web/src/spatial.rs `Solid`): a ball's whole
/// angular speed times its radius, a puck's spin about the vertical times its radius, a rod's (a
/// block's: body 0's, the lowest) angular speed times half its length.
function rOmega(c, n, [code, a]) {
  const out = new Float64Array(n);
  for (let i = 0; i < n; i += 1) {
    const w = code === 2 ? Math.abs(c.wz[i]) : Math.hypot(c.wx[i], c.wy[i], c.wz[i]);
    out[i] = (code === 0 || code === 3 ? a / 2 : a) * w;
  }
  return out;
}

function speed(c, n) {
  const out = new Float64Array(n);
  for (let i = 0; i < n; i += 1) out[i] = Math.hypot(c.vx[i], c.vy[i], c.vz[i]);
  return out;
}

/// Draws the three plots of `src`'s trace (a live run of a scene in three dimensions).
export function drawSpatialPlots($, src, shapes) {
  const tr = src.trace; const c = tr.cols; const n = tr.n;
  const tMax = niceCeil(Math.max(tr.time, 10 * src.params.step));
  const line = (y, color) => ({ t: c.t, y, n, color, width: 2.5 });
  drawPlot($('plot-positions'), {
    series: [line(c.x, CONTACT_COLORS[0]), line(c.y, COLORS.finger2)], tMax, yLabel: 'x, y (m)', aspect: 0.39,
  });
  drawPlot($('plot-angle'), {
    series: [line(speed(c, n), COLORS.ink), line(rOmega(c, n, shapes.solid), COLORS.stick)],
    tMax, yLabel: 'v, R omega (m/s)', aspect: 0.24, minSpan: 0.01,
  });
  drawPlot($('plot-height'), { series: [line(scaled(c.z, n, 100), COLORS.ink)], tMax, yLabel: 'height (cm)', aspect: 0.24, minSpan: 1 });
}
