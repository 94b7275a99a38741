// Drawing: the scene to scale (the body, its supports, contact points coloured by mode, normal and
// friction forces as arrows, the centre of mass, time) and line plots with switch marks. Any scene
// of the catalogue, with its number of contacts: a rod on fingers (meter stick, three fingers), a
// block or a round body on a slope (incline, cylinder), a rod against a wall or on a floor (ladder,
// Painleve's rod).

import { COL, contactColumns } from './trace.js';

export const COLORS = {
  ink: '#111', muted: '#555', grid: '#d8d8d8', paper: '#fff',
  stick: '#009e73', slide: '#e69f00', separated: '#777',
  normal: '#0072b2', friction: '#cc79a7', weight: '#555',
  finger1: '#0072b2', finger2: '#d55e00', finger3: '#56b4e9', com: '#111',
  balanced: '#009e73', fell: '#d55e00', unfinished: '#999', failed: '#000',
  wood: '#f0d9a0', ground: '#cfcac0', drive: '#111',
};
const MODE_COLORS = [COLORS.separated, COLORS.stick, COLORS.slide, COLORS.slide];
/// Each contact's colour in the plots and the fingers (contact 1 first).
export const CONTACT_COLORS = [COLORS.finger1, COLORS.finger2, COLORS.finger3];

/// Scenes whose body is a rod on fingers, on a slope, on the floor (ladder: and a wall).
const ON_FINGERS = ['meter-stick', 'three-fingers'];
const ON_SLOPE = ['incline', 'cylinder'];

/// Sizes a canvas's backing store to its displayed size (sharp on any screen); returns the
/// 2D context scaled to CSS pixels, with the CSS width and height.
export function fitCanvas(canvas, aspect) {
  const dpr = window.devicePixelRatio || 1;
  const w = Math.max(200, canvas.clientWidth || canvas.width);
  const h = Math.round(w * aspect);
  if (canvas.width !== Math.round(w * dpr) || canvas.height !== Math.round(h * dpr)) {
    canvas.width = Math.round(w * dpr);
    canvas.height = Math.round(h * dpr);
  }
  const g = canvas.getContext('2d');
  g.setTransform(dpr, 0, 0, dpr, 0, 0);
  return { g, w, h };
}

function arrow(g, x0, y0, dx, dy, color, width) {
  const len = Math.hypot(dx, dy);
  if (len < 2) return;
  const ux = dx / len; const uy = dy / len;
  const head = Math.min(14, len * 0.5);
  g.strokeStyle = color; g.fillStyle = color; g.lineWidth = width;
  g.beginPath(); g.moveTo(x0, y0); g.lineTo(x0 + dx - ux * head * 0.8, y0 + dy - uy * head * 0.8); g.stroke();
  g.beginPath();
  g.moveTo(x0 + dx, y0 + dy);
  g.lineTo(x0 + dx - ux * head - uy * head * 0.45, y0 + dy - uy * head + ux * head * 0.45);
  g.lineTo(x0 + dx - ux * head + uy * head * 0.45, y0 + dy - uy * head - ux * head * 0.45);
  g.closePath(); g.fill();
}

/// A drive (an applied force, a support's motion): a thick arrow with its label at the tail.
function driveArrow(g, x0, y0, dx, label) {
  arrow(g, x0, y0, dx, 0, COLORS.drive, 5);
  g.font = '600 16px system-ui, "DejaVu Sans", sans-serif';
  g.textBaseline = 'bottom'; g.textAlign = dx >= 0 ? 'left' : 'right';
  const tw = g.measureText(label).width;
  g.fillStyle = 'rgba(255,255,255,0.85)';
  g.fillRect(dx >= 0 ? x0 - 2 : x0 - tw - 2, y0 - 26, tw + 4, 20);
  g.fillStyle = COLORS.drive; g.fillText(label, x0, y0 - 7);
  g.textAlign = 'left';
}

function hatch(g, x, y, w, h) {
  g.save();
  g.beginPath(); g.rect(x, y, w, h); g.clip();
  g.fillStyle = COLORS.ground; g.fillRect(x, y, w, h);
  g.strokeStyle = '#9a9488'; g.lineWidth = 1.5;
  for (let s = -h; s < w + h; s += 14) { g.beginPath(); g.moveTo(x + s, y + h); g.lineTo(x + s + h, y); g.stroke(); }
  g.restore();
}

/// The centre-of-mass symbol: a circle with two filled quadrants.
function comSymbol(g, x, y, r) {
  g.fillStyle = COLORS.paper; g.strokeStyle = COLORS.com; g.lineWidth = 2;
  g.beginPath(); g.arc(x, y, r, 0, 2 * Math.PI); g.fill(); g.stroke();
  g.fillStyle = COLORS.com;
  for (const a of [0, Math.PI]) {
    g.beginPath(); g.moveTo(x, y); g.arc(x, y, r, a - Math.PI / 2, a); g.closePath(); g.fill();
  }
}

/// The scene's contact frames (normal n and tangent d of each of its k contacts), as
/// docs/scenes.md defines them.
function frames(scene, params, theta, k) {
  const same = (n, d) => Array.from({ length: k }, () => ({ n, d }));
  if (ON_FINGERS.includes(scene)) return same([-Math.sin(theta), Math.cos(theta)], [Math.cos(theta), Math.sin(theta)]);
  if (ON_SLOPE.includes(scene)) {
    const a = params.angle;
    return same([-Math.sin(a), Math.cos(a)], [Math.cos(a), Math.sin(a)]);
  }
  if (scene === 'ladder') return [{ n: [0, 1], d: [1, 0] }, { n: [-1, 0], d: [0, 1] }];
  return same([0, 1], [1, 0]);
}

/// The body's size (width along its axis, height across it; a round body's diameter).
function bodySize(scene, p) {
  if (ON_FINGERS.includes(scene)) return [p.rod_length, p.rod_thickness];
  if (scene === 'incline') return [p.width, p.height];
  if (scene === 'cylinder') return [2 * p.radius, 2 * p.radius];
  return [p.length, p.thickness];
}

export class SceneView {
  constructor(canvas) {
    this.canvas = canvas;
    this.aspect = 0.52;
  }

  /// A new scene: its name, parameters (core fields, SI), start row, number of contacts, and for
  /// a scene of several bodies their shapes ({sizes: [[w, h]], table: [lo, hi]}, core.js `shapes`).
  setScene(scene, params, start, k, shapes = null) {
    this.scene = scene;
    this.k = k;
    this.shapes = shapes;
    this.params = params;
    this.start = start;
    this.camera = null;
    // The drawing's worst frame so far: the least room (px) between a body and the drawing's
    // edge (negative: a body was out of the drawing); the browser test reads it.
    this.worst = Infinity;
  }

  /// The drawing's extent in the scene's coordinates (m): {left, right, bottom, top}.
  extent() {
    const c = this.camera;
    if (!c) return null;
    return { left: c.x0 - c.cx / c.k, right: c.x0 + (c.w - c.cx) / c.k, bottom: c.y0 - (c.h - c.cy) / c.k, top: c.y0 + c.cy / c.k };
  }

  /// Each body's bounding box in a row: [[left, right, bottom, top]] (m): a box's turned with it,
  /// a disc's; a scene of one body, its circumscribed circle's.
  boxes(row) {
    if (this.shapes) {
      return this.shapes.sizes.map(([bw, bh], b) => {
        const x = row[1 + 3 * b]; const y = row[2 + 3 * b]; const t = row[3 + 3 * b];
        const c = Math.abs(Math.cos(t)); const s = Math.abs(Math.sin(t));
        const ex = this.shapes.round[b] ? bw / 2 : (bw * c + bh * s) / 2;
        const ey = this.shapes.round[b] ? bw / 2 : (bw * s + bh * c) / 2;
        return [x - ex, x + ex, y - ey, y + ey];
      });
    }
    const [bw, bh] = bodySize(this.scene, this.params);
    const r = Math.hypot(bw, bh) / 2;
    return [[row[COL.x] - r, row[COL.x] + r, row[COL.y] - r, row[COL.y] + r]];
  }

  /// The least room (px) between a body of `row` and the drawing's edge (negative: out of it).
  room(row) {
    const e = this.extent();
    if (!e) return Infinity;
    let m = Infinity;
    for (const [l, r, b, t] of this.boxes(row)) m = Math.min(m, l - e.left, e.right - r, b - e.bottom, e.top - t);
    return m * this.camera.k;
  }

  /// `false` once a body of `row` has left the view: its centre out of the drawing, or (a scene of
  /// several bodies, whose view follows them) farther from the others than the view can follow, or
  /// into the table or floor where the scene has no contact for it (block-on-block's top block
  /// has none with the floor: it would fall through).
  inView(row) {
    if (this.shapes && this.camera && !this.camera.lost) this.track(row);
    if (this.camera && this.camera.lost) return false;
    const e = this.extent();
    if (!e) return true;
    if (this.shapes) {
      // A corner (a disc's lowest point) more than 2 mm into the table, over the table.
      const [lo, hi] = this.shapes.table;
      const over = (x) => (lo === null || x >= lo) && (hi === null || x <= hi);
      const sunk = this.shapes.sizes.some(([bw, bh], i) => {
        const x = row[1 + 3 * i]; const y = row[2 + 3 * i]; const t = row[3 + 3 * i];
        if (this.shapes.round[i]) return y - bw / 2 < -2e-3 && over(x);
        const c = Math.cos(t); const s = Math.sin(t);
        return [[-1, -1], [1, -1], [1, 1], [-1, 1]].some(([u, v]) => {
          const cx = x + (u * bw * c - v * bh * s) / 2; const cy = y + (u * bw * s + v * bh * c) / 2;
          return cy < -2e-3 && over(cx);
        });
      });
      if (sunk) return false;
    }
    // A body whose centre is out of the drawing has left it.
    return this.boxes(row).every(([l, r, b, t]) => (l + r) / 2 > e.left && (l + r) / 2 < e.right && (b + t) / 2 > e.bottom && (b + t) / 2 < e.top);
  }

  /// Keeps every body of a scene of several bodies in the drawing: the view pans with them, and
  /// zooms out when they spread or rise (never back in during a run), down to half its first
  /// scale; past that the bodies have left the view (`camera.lost`). A body falling off the
  /// table leaves the drawing at the bottom (the table's top stays where it is on the drawing).
  track(row) {
    const cam = this.camera;
    const m = 14 / cam.k; // room at the edge (m)
    const boxes = this.boxes(row);
    // The pull's arrow and its label ahead of the lowest body.
    const f = this.params.force;
    if (f > 0) boxes[0][1] += (40 + 110 * (f / (f + 10)) + 50) / cam.k;
    const l = Math.min(...boxes.map((x) => x[0])); const r = Math.max(...boxes.map((x) => x[1]));
    const t = Math.max(...boxes.map((x) => x[3]));
    // Zoom out (the table's top stays at its height on the drawing) so that the bodies fit.
    let k = cam.k;
    k = Math.min(k, (cam.w - 28) / Math.max(r - l, 1e-9));
    if (t > 0) k = Math.min(k, (cam.cy - 14) / t);
    if (k < cam.k) {
      if (k < cam.k0 / 2) { cam.lost = true; return; }
      cam.k = k * 0.9; // a little more, so that the zoom does not creep
    }
    const half = cam.w / (2 * cam.k);
    if (l - m < cam.x0 - half) cam.x0 = l - m + half;
    if (r + m > cam.x0 + half) cam.x0 = r + m - half;
  }

  camera0(w, h) {
    if (this.shapes) return this.bodiesCamera(w, h);
    const p = this.params;
    const [bw, bh] = bodySize(this.scene, p);
    if (this.scene === 'meter-stick') {
      // Wide enough for the rod at the start and where the fingers stop (or as far as they go).
      const lo = Math.min(p.finger1_x, p.finger2_x); const hi = Math.max(p.finger1_x, p.finger2_x);
      let end = 0;
      if (p.finger1_velocity > p.finger2_velocity) {
        end = p.finger2_velocity === 0 ? p.finger2_x - p.finger_width / 2
          : p.finger1_velocity === 0 ? p.finger1_x + p.finger_width / 2
            : p.finger1_x + p.finger1_velocity * ((p.finger2_x - p.finger1_x - p.finger_width) / (p.finger1_velocity - p.finger2_velocity)) + p.finger_width / 2;
      }
      const left = Math.min(-bw / 2, end - bw / 2, lo); const right = Math.max(bw / 2, end + bw / 2, hi);
      const k = w / (1.08 * (right - left));
      return { k, x0: (left + right) / 2, y0: this.start[COL.y], cx: w / 2, cy: h * 0.42, follow: false };
    }
    if (this.scene === 'three-fingers') {
      // Finger 1 may drag the rod as far as it travels (to finger 2's width from it).
      const travel = Math.max(0, p.finger2_x - p.finger_width - p.finger1_x);
      const left = Math.min(-bw / 2, p.finger1_x); const right = Math.max(bw / 2 + travel, p.finger3_x);
      const k = w / (1.08 * (right - left));
      return { k, x0: (left + right) / 2, y0: this.start[COL.y], cx: w / 2, cy: h * 0.42, follow: false };
    }
    if (this.scene === 'ladder') {
      const k = Math.min(w / (1.45 * bw), h / (1.25 * bw));
      return { k, x0: 0, y0: 0, cx: w * 0.84, cy: h * 0.9, follow: false };
    }
    if (this.scene === 'painleve') {
      // The floor low in the view, the rod's end in the middle: it slides to the left, or jams.
      const k = Math.min(w / (2.2 * bw), (0.7 * h) / bw);
      return { k, x0: 0, y0: 0, cx: w * 0.45, cy: h * 0.85, follow: false };
    }
    const span = Math.max(10 * Math.max(bw, bh), 0.8);
    return { k: w / span, x0: this.start[COL.x], y0: this.start[COL.y], cx: w / 2, cy: h * 0.5, follow: true };
  }

  /// The view of a scene of several bodies: every body at the start with room around it (the
  /// tablecloth's board leaves to the right, a stack's blocks fall past the table's edge), fixed.
  bodiesCamera(w, h) {
    const s = this.start; const sizes = this.shapes.sizes;
    let left = Infinity; let right = -Infinity; let top = 0;
    sizes.forEach(([bw, bh], b) => {
      const x = s[1 + 3 * b]; const y = s[2 + 3 * b]; const r = Math.hypot(bw, bh) / 2;
      left = Math.min(left, x - r); right = Math.max(right, x + r); top = Math.max(top, y + r);
    });
    for (const end of this.shapes.table) if (end !== null) { left = Math.min(left, end); right = Math.max(right, end); }
    const span = right - left;
    const k = Math.min(w / (1.6 * span), (0.6 * h) / Math.max(top, 1e-3));
    return { k, k0: k, x0: (left + right) / 2 + 0.15 * span, y0: 0, cx: w / 2, cy: h * 0.8, follow: false };
  }

  /// Draws a row of a scene of several bodies: the table (hatched, with its edge), each body a box
  /// (a long one marked every 10 cm) or a disc with a spoke.
  drawBodies(g, w, h, row, info) {
    const cam = this.camera;
    const X = (x) => cam.cx + (x - cam.x0) * cam.k;
    const Y = (y) => cam.cy - (y - cam.y0) * cam.k;
    g.fillStyle = COLORS.paper; g.fillRect(0, 0, w, h);
    const [lo, hi] = this.shapes.table;
    const a = lo === null ? 0 : Math.max(0, X(lo)); const b = hi === null ? w : Math.min(w, X(hi));
    if (b > a) {
      hatch(g, a, Y(0), b - a, h - Y(0));
      g.strokeStyle = COLORS.ink; g.lineWidth = 3;
      g.beginPath();
      if (lo !== null) { g.moveTo(a, h); g.lineTo(a, Y(0)); } else g.moveTo(a, Y(0));
      g.lineTo(b, Y(0));
      if (hi !== null) g.lineTo(b, h);
      g.stroke();
      // A mark every 10 cm on the table, so that the motion shows.
      g.lineWidth = 2;
      const from = Math.ceil((cam.x0 - w / (2 * cam.k)) / 0.1); const to = Math.floor((cam.x0 + w / (2 * cam.k)) / 0.1);
      for (let i = from; i <= to; i += 1) {
        const x = X(i * 0.1);
        if (x >= a && x <= b) { g.beginPath(); g.moveTo(x, Y(0)); g.lineTo(x - 8, Y(0) + 10); g.stroke(); }
      }
    }
    this.shapes.sizes.forEach(([bw, bh], i) => {
      const x = row[1 + 3 * i]; const y = row[2 + 3 * i]; const theta = row[3 + 3 * i];
      g.save();
      g.translate(X(x), Y(y)); g.rotate(-theta);
      const pw = bw * cam.k; const ph = Math.max(bh * cam.k, 3);
      g.fillStyle = CONTACT_COLORS[i % CONTACT_COLORS.length]; g.globalAlpha = 0.45;
      if (this.shapes.round[i]) {
        // A disc with a spoke from the centre to the rim (and a lighter one across), as the
        // cylinder: rolling turns the spoke as the disc moves over the board.
        const r = pw / 2;
        g.beginPath(); g.arc(0, 0, r, 0, 2 * Math.PI); g.fill();
        g.globalAlpha = 1; g.strokeStyle = COLORS.ink; g.lineWidth = 2; g.stroke();
        g.lineWidth = 1.5; g.strokeStyle = COLORS.muted;
        g.beginPath(); g.moveTo(0, -r); g.lineTo(0, r); g.stroke();
        g.lineWidth = 4; g.strokeStyle = COLORS.ink;
        g.beginPath(); g.moveTo(0, 0); g.lineTo(r, 0); g.stroke();
        g.restore();
        comSymbol(g, X(x), Y(y), 7);
        return;
      }
      g.fillRect(-pw / 2, -ph / 2, pw, ph);
      g.globalAlpha = 1; g.strokeStyle = COLORS.ink; g.lineWidth = 2; g.strokeRect(-pw / 2, -ph / 2, pw, ph);
      if (bw >= 0.5) {
        // Marks every 10 cm on a long body (a board), so that what moves over it shows.
        g.lineWidth = 1.5;
        for (let m = 1; m < Math.round(bw / 0.1); m += 1) {
          const mx = -pw / 2 + m * 0.1 * cam.k;
          g.beginPath(); g.moveTo(mx, -ph / 2); g.lineTo(mx, -ph / 2 + Math.max(ph * 0.6, 3)); g.stroke();
        }
      }
      g.restore();
      comSymbol(g, X(x), Y(y), 7);
    });
    // The pull on the lowest body (block-on-block, the tablecloth, disc-on-board: along +x at its
    // centre of mass), from its leading face.
    const force = this.params.force;
    if (force > 0) {
      const [bw] = this.shapes.sizes[0];
      driveArrow(g, X(row[1] + bw / 2), Y(row[2]), 40 + 110 * (force / (force + 10)), `F = ${force} N`);
    }
    this.drawOverlay(g, w, h, cam, info);
  }

  /// Draws the row; `info` = {title, time, steps, outcome: {name} | null, reference: row | null, rate,
  /// moving: each support's velocity (m/s, 0 at rest) | undefined}.
  draw(row, info) {
    this.moving = info.moving;
    const { g, w, h } = fitCanvas(this.canvas, this.aspect);
    if (!this.camera || this.camera.w !== w) this.camera = { ...this.camera0(w, h), w, h };
    if (this.shapes) {
      if (!this.camera.lost) this.track(row);
      this.drawBodies(g, w, h, row, info);
      if (!this.camera.lost) this.worst = Math.min(this.worst, this.room(row));
      return;
    }
    const cam = this.camera;
    if (cam.follow) {
      // The camera rides with the body (the slope's marks show the motion).
      cam.x0 = row[COL.x]; cam.y0 = row[COL.y];
    }
    const X = (x) => cam.cx + (x - cam.x0) * cam.k;
    const Y = (y) => cam.cy - (y - cam.y0) * cam.k;
    const p = this.params;
    g.fillStyle = COLORS.paper; g.fillRect(0, 0, w, h);
    this.drawSupports(g, X, Y, w, h, row);
    if (info.reference) this.drawBody(g, X, Y, info.reference, true);
    this.drawBody(g, X, Y, row, false);

    // Forces on the body at each contact: F = p / h, the weight m g as 25 % of the view's height.
    const weight = p.rod_mass !== undefined ? p.rod_mass * p.gravity : p.mass * p.gravity;
    const kf = (0.25 * h) / Math.max(weight, 1e-12);
    const cap = 0.45 * h;
    const fr = frames(this.scene, p, row[COL.theta], this.k);
    const at = Array.from({ length: this.k }, (_, i) => contactColumns(this.k, i));
    for (const c of at) {
      const sx = X(row[c.sx]); const sy = Y(row[c.sy]);
      const mode = row[c.mode];
      g.lineWidth = 3;
      g.beginPath(); g.arc(sx, sy, 7, 0, 2 * Math.PI);
      if (mode === 0) {
        g.fillStyle = COLORS.paper; g.fill(); g.strokeStyle = COLORS.separated; g.stroke();
      } else {
        g.fillStyle = MODE_COLORS[mode]; g.fill(); g.strokeStyle = COLORS.ink; g.stroke();
      }
    }
    for (const [i, c] of at.entries()) {
      if (row[c.mode] === 0) continue;
      const sx = X(row[c.sx]); const sy = Y(row[c.sy]);
      const clamp = (v) => Math.max(-cap, Math.min(cap, v));
      const fn = clamp((row[c.pn] / p.step) * kf); const ff = clamp((row[c.pf] / p.step) * kf);
      arrow(g, sx, sy, fn * fr[i].n[0], -fn * fr[i].n[1], COLORS.normal, 4);
      arrow(g, sx, sy, ff * fr[i].d[0], -ff * fr[i].d[1], COLORS.friction, 4);
    }
    // The weight at the centre of mass (dashed: the scale for the force arrows).
    g.setLineDash([6, 5]);
    arrow(g, X(row[COL.x]), Y(row[COL.y]), 0, Math.min(cap, weight * kf), COLORS.weight, 2.5);
    g.setLineDash([]);
    comSymbol(g, X(row[COL.x]), Y(row[COL.y]), 9);

    this.drawOverlay(g, w, h, cam, info);
  }

  drawSupports(g, X, Y, w, h, row) {
    const p = this.params;
    if (ON_FINGERS.includes(this.scene)) {
      const half = Math.max(p.finger_width / 2, 2.5 / this.camera.k);
      for (let i = 0; i < this.k; i += 1) {
        const color = CONTACT_COLORS[i];
        const c = contactColumns(this.k, i);
        const tx = row[c.sx]; const ty = row[c.sy];
        const left = X(tx - half); const right = X(tx + half); const top = Y(ty);
        const r = Math.min((right - left) / 2, 10);
        g.fillStyle = color; g.globalAlpha = 0.35;
        g.beginPath();
        g.moveTo(left, h); g.lineTo(left, top + r); g.quadraticCurveTo(left, top, left + r, top);
        g.lineTo(right - r, top); g.quadraticCurveTo(right, top, right, top + r); g.lineTo(right, h);
        g.closePath(); g.fill();
        g.globalAlpha = 1; g.strokeStyle = color; g.lineWidth = 2; g.stroke();
        // A moving finger: its velocity as an arrow in the finger, below the tip.
        const v = this.moving ? this.moving[i] : 0;
        if (v) driveArrow(g, (left + right) / 2, Math.min(h - 24, top + 0.36 * h), Math.sign(v) * 60, `${plainSpeed(Math.abs(v))} m/s`);
      }
    } else if (ON_SLOPE.includes(this.scene)) {
      const a = p.angle; const far = 1e3;
      g.fillStyle = COLORS.ground;
      g.beginPath();
      g.moveTo(X(-far * Math.cos(a)), Y(-far * Math.sin(a)));
      g.lineTo(X(far * Math.cos(a)), Y(far * Math.sin(a)));
      g.lineTo(X(far * Math.cos(a)), Y(-far)); g.lineTo(X(-far * Math.cos(a)), Y(-far));
      g.closePath(); g.fill();
      g.strokeStyle = COLORS.ink; g.lineWidth = 3;
      g.beginPath(); g.moveTo(X(-far * Math.cos(a)), Y(-far * Math.sin(a))); g.lineTo(X(far * Math.cos(a)), Y(far * Math.sin(a))); g.stroke();
      // A mark every 10 cm along the slope, so that the motion shows while the camera follows.
      const along = row[COL.x] * Math.cos(a) + row[COL.y] * Math.sin(a);
      const span = w / this.camera.k;
      g.lineWidth = 2;
      for (let s = Math.floor((along - span) / 0.1) * 0.1; s < along + span; s += 0.1) {
        const px = s * Math.cos(a); const py = s * Math.sin(a);
        g.beginPath(); g.moveTo(X(px), Y(py)); g.lineTo(X(px) + 10 * Math.sin(a), Y(py) + 10 * Math.cos(a)); g.stroke();
      }
    } else if (this.scene === 'painleve') {
      hatch(g, 0, Y(0), w, h - Y(0));
      g.strokeStyle = COLORS.ink; g.lineWidth = 3;
      g.beginPath(); g.moveTo(0, Y(0)); g.lineTo(w, Y(0)); g.stroke();
      // A mark every 10 cm on the floor, so that the end's slide shows.
      g.lineWidth = 2;
      const span = w / this.camera.k;
      for (let s = Math.floor((this.camera.x0 - span) / 0.1) * 0.1; s < this.camera.x0 + span; s += 0.1) {
        g.beginPath(); g.moveTo(X(s), Y(0)); g.lineTo(X(s) - 8, Y(0) + 10); g.stroke();
      }
    } else {
      hatch(g, 0, Y(0), w, h - Y(0));
      hatch(g, X(0), 0, w - X(0), Y(0));
      g.strokeStyle = COLORS.ink; g.lineWidth = 3;
      g.beginPath(); g.moveTo(0, Y(0)); g.lineTo(X(0), Y(0)); g.lineTo(X(0), 0); g.stroke();
    }
  }

  drawBody(g, X, Y, row, ghost) {
    const [bw, bh] = bodySize(this.scene, this.params);
    const k = this.camera.k;
    g.save();
    g.translate(X(row[COL.x]), Y(row[COL.y]));
    g.rotate(-row[COL.theta]);
    const pw = bw * k; const ph = Math.max(bh * k, 3);
    if (this.scene === 'cylinder') {
      // A disc with a spoke from the centre to the rim (and a lighter one across): rolling turns
      // the spoke as the disc moves, slipping turns it less.
      const r = pw / 2;
      g.beginPath(); g.arc(0, 0, r, 0, 2 * Math.PI);
      if (ghost) {
        g.setLineDash([8, 6]); g.strokeStyle = COLORS.muted; g.lineWidth = 2; g.stroke();
      } else {
        g.fillStyle = COLORS.wood; g.fill(); g.strokeStyle = COLORS.ink; g.lineWidth = 2; g.stroke();
        g.lineWidth = 1.5; g.strokeStyle = COLORS.muted;
        g.beginPath(); g.moveTo(0, -r); g.lineTo(0, r); g.stroke();
        g.lineWidth = 4; g.strokeStyle = COLORS.ink;
        g.beginPath(); g.moveTo(0, 0); g.lineTo(r, 0); g.stroke();
      }
      g.restore();
      return;
    }
    if (ghost) {
      g.setLineDash([8, 6]); g.strokeStyle = COLORS.muted; g.lineWidth = 2;
      g.strokeRect(-pw / 2, -ph / 2, pw, ph);
    } else {
      g.fillStyle = COLORS.wood; g.fillRect(-pw / 2, -ph / 2, pw, ph);
      g.strokeStyle = COLORS.ink; g.lineWidth = 2; g.strokeRect(-pw / 2, -ph / 2, pw, ph);
      if (ON_FINGERS.includes(this.scene) && bw >= 0.2) {
        // Marks every 10 cm, as on a meter stick.
        g.lineWidth = 1.5;
        for (let i = 1; i < Math.round(bw / 0.1); i += 1) {
          const x = -pw / 2 + i * 0.1 * k;
          g.beginPath(); g.moveTo(x, -ph / 2); g.lineTo(x, -ph / 2 + Math.max(ph * 0.6, 3)); g.stroke();
        }
      }
    }
    g.restore();
  }

  drawOverlay(g, w, h, cam, info) {
    g.fillStyle = COLORS.ink;
    g.font = '600 22px system-ui, "DejaVu Sans", sans-serif';
    g.textBaseline = 'top'; g.textAlign = 'left';
    g.fillText(`t = ${info.time.toFixed(3)} s`, 14, 12);
    g.font = '17px system-ui, "DejaVu Sans", sans-serif';
    g.fillText(info.title, 14, 42);
    g.fillText(`step ${info.steps}${info.rate ? ` · ${info.rate}` : ''}`, 14, 64);
    // Legend.
    const items = this.shapes ? [['com', COLORS.com, 'centre of mass'], ...(this.params.force > 0 ? [['line', COLORS.drive, 'pull']] : [])] : [
      ['circle', COLORS.stick, 'sticking'], ['circle', COLORS.slide, 'sliding'], ['ring', COLORS.separated, 'separated'],
      ['line', COLORS.normal, 'normal force'], ['line', COLORS.friction, 'friction'], ['com', COLORS.com, 'centre of mass'],
    ];
    g.font = '16px system-ui, "DejaVu Sans", sans-serif';
    let y = 14;
    const x = w - 190;
    g.fillStyle = 'rgba(255,255,255,0.85)'; g.fillRect(x - 10, 6, 196, items.length * 23 + 10);
    for (const [kind, color, label] of items) {
      if (kind === 'line') { arrow(g, x, y + 9, 26, 0, color, 4); } else if (kind === 'com') { comSymbol(g, x + 10, y + 9, 8); } else {
        g.beginPath(); g.arc(x + 10, y + 9, 7, 0, 2 * Math.PI); g.lineWidth = 3;
        if (kind === 'ring') { g.strokeStyle = color; g.stroke(); } else { g.fillStyle = color; g.fill(); g.strokeStyle = COLORS.ink; g.stroke(); }
      }
      g.fillStyle = COLORS.ink; g.fillText(label, x + 36, y + 1);
      y += 23;
    }
    // Scale bar.
    const lengths = [0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1];
    const m = lengths.find((l) => l * cam.k >= 60) || 1;
    const bx = 16; const by = h - 22;
    g.strokeStyle = COLORS.ink; g.lineWidth = 3;
    g.beginPath(); g.moveTo(bx, by - 6); g.lineTo(bx, by); g.lineTo(bx + m * cam.k, by); g.lineTo(bx + m * cam.k, by - 6); g.stroke();
    const scaleText = m >= 1 ? `${m} m` : `${Math.round(m * 100)} cm`;
    g.fillStyle = 'rgba(255,255,255,0.85)';
    g.fillRect(bx + m * cam.k + 4, by - 16, g.measureText(scaleText).width + 8, 22);
    g.fillStyle = COLORS.ink; g.textBaseline = 'bottom';
    g.fillText(scaleText, bx + m * cam.k + 8, by + 4);
    if (info.outcome) {
      const text = info.outcome.name;
      g.font = '800 40px system-ui, "DejaVu Sans", sans-serif';
      const color = {
        Balanced: COLORS.balanced, Held: COLORS.balanced, Rolled: COLORS.balanced,
        Rode: COLORS.balanced, Stayed: COLORS.balanced,
        Fell: COLORS.fell, Tipped: COLORS.fell, Jammed: COLORS.fell, Failed: COLORS.fell,
      }[text] || '#8a6200';
      const tw = g.measureText(text).width;
      const by0 = 96; // below the title lines
      g.fillStyle = 'rgba(255,255,255,0.9)'; g.fillRect(w / 2 - tw / 2 - 16, by0, tw + 32, 56);
      g.strokeStyle = color; g.lineWidth = 4; g.strokeRect(w / 2 - tw / 2 - 16, by0, tw + 32, 56);
      g.fillStyle = color; g.textAlign = 'center'; g.textBaseline = 'middle';
      g.fillText(text, w / 2, by0 + 29);
      g.textAlign = 'left';
    }
  }
}

/// A speed as typed (0.1, not 0.09999999999999999).
function plainSpeed(v) {
  return String(Number(v.toPrecision(3)));
}

/// Rounds a span to 1, 2 or 5 times a power of ten for tick spacing.
function niceStep(span, ticks) {
  const raw = span / Math.max(1, ticks);
  const p = 10 ** Math.floor(Math.log10(raw));
  const f = raw / p;
  return (f < 1.5 ? 1 : f < 3.5 ? 2 : f < 7.5 ? 5 : 10) * p;
}

function fmtTick(v, step) {
  const digits = Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
  return digits > 4 ? v.toExponential(1) : v.toFixed(digits);
}

/// A line plot. `series`: [{t, y, n, color, width, dash, markers}] (t, y arrays of n points);
/// `marks`: [{t, y, color, label}] drawn as triangles (labels where there is room); `ticks`: [{t, color}]
/// drawn as short lines at the bottom; `tMax`: the right end of the time axis.
/// `minSpan`: the y axis covers at least this much (noise-level wiggles then look flat).
export function drawPlot(canvas, { series, marks = [], ticks = [], tMax, yLabel, aspect, minSpan = 0 }) {
  const { g, w, h } = fitCanvas(canvas, aspect);
  g.fillStyle = COLORS.paper; g.fillRect(0, 0, w, h);
  const left = 64; const right = 12; const top = 10; const bottom = 30;
  const pw = w - left - right; const ph = h - top - bottom;
  let lo = Infinity; let hi = -Infinity;
  for (const s of series) for (let i = 0; i < s.n; i += 1) { const v = s.y[i]; if (v < lo) lo = v; if (v > hi) hi = v; }
  if (!Number.isFinite(lo)) { lo = 0; hi = 1; }
  if (hi - lo < Math.max(minSpan, 1e-9)) {
    const c = (hi + lo) / 2; const d = Math.max(minSpan / 2, Math.abs(c) * 0.05, 1e-3); lo = c - d; hi = c + d;
  }
  const pad = (hi - lo) * 0.08; lo -= pad; hi += pad;
  const t1 = Math.max(tMax, 1e-9);
  const X = (t) => left + (t / t1) * pw;
  const Y = (v) => top + (1 - (v - lo) / (hi - lo)) * ph;
  g.font = '14px system-ui, "DejaVu Sans", sans-serif';
  g.strokeStyle = COLORS.grid; g.lineWidth = 1; g.fillStyle = COLORS.ink;
  const ys = niceStep(hi - lo, Math.max(2, Math.floor(ph / 40)));
  g.textAlign = 'right'; g.textBaseline = 'middle';
  for (let v = Math.ceil(lo / ys) * ys; v <= hi; v += ys) {
    g.beginPath(); g.moveTo(left, Y(v)); g.lineTo(left + pw, Y(v)); g.stroke();
    g.fillText(fmtTick(Math.abs(v) < ys * 1e-6 ? 0 : v, ys), left - 6, Y(v));
  }
  const ts = niceStep(t1, Math.max(2, Math.floor(pw / 90)));
  g.textAlign = 'center'; g.textBaseline = 'top';
  for (let t = 0; t <= t1 + ts * 1e-9; t += ts) {
    g.beginPath(); g.moveTo(X(t), top); g.lineTo(X(t), top + ph); g.stroke();
    g.fillText(fmtTick(t, ts), X(t), top + ph + 6);
  }
  g.save();
  g.translate(14, top + ph / 2); g.rotate(-Math.PI / 2); g.textBaseline = 'middle';
  g.fillText(yLabel, 0, 0);
  g.restore();
  g.strokeStyle = COLORS.ink; g.lineWidth = 1.5; g.strokeRect(left, top, pw, ph);

  g.save();
  g.beginPath(); g.rect(left, top, pw, ph); g.clip();
  for (const s of series) {
    g.strokeStyle = s.color; g.lineWidth = s.width || 2; g.setLineDash(s.dash || []);
    // One vertical segment (min..max) per pixel column: every extreme shows, whatever n is.
    g.beginPath();
    let col = -1; let mn = 0; let mx = 0; let first = true; let lastY = 0;
    const flush = () => {
      if (col < 0) return;
      const x = left + col + 0.5;
      if (first) { g.moveTo(x, Y(lastY)); first = false; }
      g.lineTo(x, Y(mn)); g.lineTo(x, Y(mx)); g.lineTo(x, Y(lastY));
    };
    for (let i = 0; i < s.n; i += 1) {
      const c = Math.floor(X(s.t[i]) - left);
      const v = s.y[i];
      if (c !== col) { flush(); col = c; mn = v; mx = v; } else { if (v < mn) mn = v; if (v > mx) mx = v; }
      lastY = v;
    }
    flush();
    g.stroke();
    if (s.markers) {
      g.fillStyle = s.color;
      const every = Math.max(1, Math.floor(s.n / 12));
      for (let i = 0; i < s.n; i += every) { g.fillRect(X(s.t[i]) - 3, Y(s.y[i]) - 3, 6, 6); }
    }
  }
  g.setLineDash([]);
  for (const tk of ticks) {
    g.strokeStyle = tk.color; g.lineWidth = 2;
    g.beginPath(); g.moveTo(X(tk.t), top + ph); g.lineTo(X(tk.t), top + ph - 10); g.stroke();
  }
  let lastLabel = -Infinity;
  g.font = '600 14px system-ui, "DejaVu Sans", sans-serif';
  g.textAlign = 'center'; g.textBaseline = 'bottom';
  for (const m of marks) {
    const x = X(m.t); const y = Y(m.y);
    g.fillStyle = m.color; g.strokeStyle = COLORS.ink; g.lineWidth = 1;
    g.beginPath(); g.moveTo(x, y + 2); g.lineTo(x - 6, y - 9); g.lineTo(x + 6, y - 9); g.closePath(); g.fill(); g.stroke();
    if (m.label && x - lastLabel > 46) {
      g.fillStyle = 'rgba(255,255,255,0.85)';
      const tw = g.measureText(m.label).width;
      const ly = y - 28 < top ? y + 22 : y - 11; // below the mark when there is no room above
      g.fillRect(x - tw / 2 - 2, ly - 17, tw + 4, 17);
      g.fillStyle = COLORS.ink; g.fillText(m.label, x, ly);
      lastLabel = x;
    }
  }
  g.restore();
}
