// The scenes in three dimensions drawn in perspective with plain WebGL2 (no library: boxes, balls,
// flat cylinders, planes and arrows are a few hundred lines; docs/page.md says why not three.js):
// the body at its position and orientation (quaternion [w, x, y, z], world z up), the plane or the
// fingers it rests on, each contact's force as an arrow coloured by its mode, the path of its
// centre traced on the plane; the camera orbits the body (drag), zooms (wheel, pinch) and follows
// it. A row is the core's (`web/src/spatial.rs`): t, then per body (up to three, NaN past the
// scene's) position, orientation, velocity, angular velocity, then per contact point, normal,
// friction direction, mode, normal and friction impulse.

import { COLORS } from './draw.js';

const STATE = 13;
const BODIES = 3;
const BODY = 1 + STATE * BODIES;
const CONTACT = 12;

const VERT = `#version 300 es
layout(location = 0) in vec3 aPos;
layout(location = 1) in vec3 aNormal;
uniform mat4 uModel, uViewProj;
out vec3 vNormal; out vec3 vLocal; out vec3 vWorld;
void main() {
  vec4 w = uModel * vec4(aPos, 1.0);
  vWorld = w.xyz; vLocal = aPos;
  vNormal = mat3(uModel) * aNormal;
  gl_Position = uViewProj * w;
}`;

const FRAG = `#version 300 es
precision highp float;
in vec3 vNormal; in vec3 vLocal; in vec3 vWorld;
uniform vec3 uColor; uniform int uPattern; uniform float uLit;
out vec4 outColor;
void main() {
  vec3 c = uColor;
  // 1: a ball's octants, 2: a puck's radial mark (their turning shows), 3: a 10 cm grid.
  if (uPattern == 1 && vLocal.x * vLocal.y * vLocal.z > 0.0) c *= 0.55;
  if (uPattern == 2 && vLocal.x > 0.3 && abs(vLocal.y) < 0.18 && vLocal.z > 0.49) c = vec3(0.1);
  if (uPattern == 3) {
    vec2 g = abs(fract(vWorld.xy * 10.0 + 0.5) - 0.5);
    if (min(g.x, g.y) < 0.04) c *= 0.85;
  }
  vec3 n = normalize(vNormal);
  float light = 0.45 + 0.55 * abs(dot(n, normalize(vec3(0.4, -0.5, 0.8))));
  outColor = vec4(mix(c, c * light, uLit), 1.0);
}`;

/// Unit meshes, centred: a cube of side 1, a sphere of radius 1, a cylinder of radius 1 from
/// z = -0.5 to 0.5, a cone of radius 1 from z = 0 to 1, a square of side 1 in z = 0.
function meshes() {
  const cube = []; const sphere = []; const cylinder = []; const cone = []; const square = [];
  const tri = (out, a, b, c, n) => {
    for (const p of [a, b, c]) out.push(...p, ...(n || normalise(p)));
  };
  for (let axis = 0; axis < 3; axis += 1) {
    for (const s of [-0.5, 0.5]) {
      const n = [0, 0, 0]; n[axis] = Math.sign(s);
      const u = (axis + 1) % 3; const v = (axis + 2) % 3;
      const corner = (a, b) => { const p = [0, 0, 0]; p[axis] = s; p[u] = a; p[v] = b; return p; };
      tri(cube, corner(-0.5, -0.5), corner(0.5, -0.5), corner(0.5, 0.5), n);
      tri(cube, corner(-0.5, -0.5), corner(0.5, 0.5), corner(-0.5, 0.5), n);
    }
  }
  const N = 32;
  const sp = (i, j) => {
    const th = (Math.PI * i) / (N / 2); const ph = (2 * Math.PI * j) / N;
    return [Math.sin(th) * Math.cos(ph), Math.sin(th) * Math.sin(ph), Math.cos(th)];
  };
  for (let i = 0; i < N / 2; i += 1) {
    for (let j = 0; j < N; j += 1) {
      tri(sphere, sp(i, j), sp(i + 1, j), sp(i + 1, j + 1));
      tri(sphere, sp(i, j), sp(i + 1, j + 1), sp(i, j + 1));
    }
  }
  for (let j = 0; j < N; j += 1) {
    const a = (2 * Math.PI * j) / N; const b = (2 * Math.PI * (j + 1)) / N;
    const [ca, sa, cb, sb] = [Math.cos(a), Math.sin(a), Math.cos(b), Math.sin(b)];
    tri(cylinder, [ca, sa, -0.5], [cb, sb, -0.5], [cb, sb, 0.5], [ca, sa, 0]);
    tri(cylinder, [ca, sa, -0.5], [cb, sb, 0.5], [ca, sa, 0.5], [ca, sa, 0]);
    tri(cylinder, [0, 0, 0.5], [ca, sa, 0.5], [cb, sb, 0.5], [0, 0, 1]);
    tri(cylinder, [0, 0, -0.5], [cb, sb, -0.5], [ca, sa, -0.5], [0, 0, -1]);
    tri(cone, [ca, sa, 0], [cb, sb, 0], [0, 0, 1], [ca, sa, 0.7]);
    tri(cone, [0, 0, 0], [cb, sb, 0], [ca, sa, 0], [0, 0, -1]);
  }
  tri(square, [-0.5, -0.5, 0], [0.5, -0.5, 0], [0.5, 0.5, 0], [0, 0, 1]);
  tri(square, [-0.5, -0.5, 0], [0.5, 0.5, 0], [-0.5, 0.5, 0], [0, 0, 1]);
  return { cube, sphere, cylinder, cone, square };
}

const normalise = (v) => { const l = Math.hypot(...v) || 1; return v.map((x) => x / l); };
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const rgb = (hex) => [1, 3, 5].map((i) => parseInt(hex.slice(i, i + 2), 16) / 255);
const MODE_RGB = [COLORS.separated, COLORS.stick, COLORS.slide, COLORS.slide].map(rgb);

/// Column-major 4x4 from the columns of a 3x3 (a rotation times a scale) and a translation.
function model(c0, c1, c2, t) {
  return new Float32Array([...c0, 0, ...c1, 0, ...c2, 0, ...t, 1]);
}

/// A basis whose third column is `dir` (unit).
function basis(dir) {
  const other = Math.abs(dir[2]) < 0.9 ? [0, 0, 1] : [1, 0, 0];
  const u = normalise(cross(other, dir));
  return [u, cross(dir, u), dir];
}

/// The rotation of the quaternion [w, x, y, z], as its three columns.
function rotation([w, x, y, z]) {
  return [
    [1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)],
    [2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)],
    [2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)],
  ];
}

function perspective(fovy, aspect, near, far) {
  const f = 1 / Math.tan(fovy / 2);
  return [f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) / (near - far), -1, 0, 0, (2 * far * near) / (near - far), 0];
}

function lookAt(eye, target, up) {
  const f = normalise(target.map((v, i) => v - eye[i]));
  const s = normalise(cross(f, up)); const u = cross(s, f);
  return [s[0], u[0], -f[0], 0, s[1], u[1], -f[1], 0, s[2], u[2], -f[2], 0, -dot(s, eye), -dot(u, eye), dot(f, eye), 1];
}

function multiply(a, b) {
  const out = new Float32Array(16);
  for (let c = 0; c < 4; c += 1) for (let r = 0; r < 4; r += 1) {
    let v = 0;
    for (let k = 0; k < 4; k += 1) v += a[k * 4 + r] * b[c * 4 + k];
    out[c * 4 + r] = v;
  }
  return out;
}

export class SpaceView {
  constructor(canvas) {
    this.canvas = canvas;
    this.gl = canvas.getContext('webgl2', { antialias: true, preserveDrawingBuffer: true });
    this.orbit = { yaw: -2.2, pitch: 0.45, zoom: 1 };
    this.background = [0.96, 0.96, 0.95];
    this.bodyColor = rgb('#d55e00');
    this.planeColor = rgb(COLORS.ground);
    if (!this.gl) return;
    const gl = this.gl;
    const shader = (type, src) => {
      const s = gl.createShader(type); gl.shaderSource(s, src); gl.compileShader(s);
      if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
      return s;
    };
    this.program = gl.createProgram();
    gl.attachShader(this.program, shader(gl.VERTEX_SHADER, VERT));
    gl.attachShader(this.program, shader(gl.FRAGMENT_SHADER, FRAG));
    gl.linkProgram(this.program);
    this.u = Object.fromEntries(['uModel', 'uViewProj', 'uColor', 'uPattern', 'uLit'].map((n) => [n, gl.getUniformLocation(this.program, n)]));
    this.mesh = Object.fromEntries(Object.entries(meshes()).map(([name, data]) => [name, this.upload(new Float32Array(data))]));
    this.path = { vao: gl.createVertexArray(), buffer: gl.createBuffer(), count: 0 };
    this.wire();
  }

  upload(data) {
    const gl = this.gl;
    const vao = gl.createVertexArray(); gl.bindVertexArray(vao);
    const buffer = gl.createBuffer(); gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
    gl.bufferData(gl.ARRAY_BUFFER, data, gl.STATIC_DRAW);
    gl.enableVertexAttribArray(0); gl.vertexAttribPointer(0, 3, gl.FLOAT, false, 24, 0);
    gl.enableVertexAttribArray(1); gl.vertexAttribPointer(1, 3, gl.FLOAT, false, 24, 12);
    return { vao, count: data.length / 6 };
  }

  /// Orbit by dragging (mouse or one finger), zoom by the wheel or two fingers' pinch.
  wire() {
    const c = this.canvas; const o = this.orbit;
    const redraw = () => { if (this.lastRow) this.draw(this.lastRow, this.lastInfo); };
    const turn = (dx, dy) => {
      o.yaw -= dx * 0.01;
      o.pitch = Math.min(1.5, Math.max(0.05, o.pitch + dy * 0.01));
      redraw();
    };
    const zoom = (f) => { o.zoom = Math.min(20, Math.max(0.05, o.zoom * f)); redraw(); };
    let drag = null;
    c.addEventListener('mousedown', (e) => { drag = [e.clientX, e.clientY]; });
    window.addEventListener('mouseup', () => { drag = null; });
    c.addEventListener('mousemove', (e) => {
      if (!drag) return;
      turn(e.clientX - drag[0], e.clientY - drag[1]); drag = [e.clientX, e.clientY];
    });
    c.addEventListener('wheel', (e) => { e.preventDefault(); zoom(Math.exp(e.deltaY * 0.001)); }, { passive: false });
    let touch = null;
    const spread = (t) => Math.hypot(t[0].clientX - t[1].clientX, t[0].clientY - t[1].clientY);
    c.addEventListener('touchstart', (e) => {
      touch = e.touches.length === 2 ? { d: spread(e.touches) } : { x: e.touches[0].clientX, y: e.touches[0].clientY };
    }, { passive: true });
    c.addEventListener('touchmove', (e) => {
      e.preventDefault();
      if (!touch) return;
      if (e.touches.length === 2 && touch.d) { const d = spread(e.touches); zoom(touch.d / d); touch.d = d; }
      else if (e.touches.length === 1 && touch.x !== undefined) {
        turn(e.touches[0].clientX - touch.x, e.touches[0].clientY - touch.y);
        touch = { x: e.touches[0].clientX, y: e.touches[0].clientY };
      }
    }, { passive: false });
    c.addEventListener('touchend', () => { touch = null; });
  }

  /// The scene's body (`shapes.solid`: [code, a, b], web/src/spatial.rs `Solid`) and supports.
  setScene(scene, params, start, k, shapes) {
    this.scene = scene; this.params = params; this.shapes = shapes;
    const [code, a, b, c] = shapes.solid;
    this.size = code === 0 || code === 3 ? a : 2 * a;
    this.halfHeight = code === 0 ? b / 2 : code === 1 ? a : code === 3 ? c / 2 : b / 2;
    this.forceScale = 0;
    this.worst = 0;
  }

  extent() { return this.size; }

  /// The body is in view while within 100 sizes of the origin (the camera follows it).
  inView(row) {
    return Math.hypot(row[1], row[2], row[3]) < 100 * Math.max(this.size, 0.1);
  }

  /// Where the camera is: orbiting the body's centre, at a distance from its size.
  cameraFor(row) {
    const o = this.orbit;
    const target = [row[1], row[2], row[3]];
    const dist = (this.shapes.solid[0] === 0 ? 1.4 : 3.5) * Math.max(this.size, 0.08) * o.zoom;
    const eye = [
      target[0] + dist * Math.cos(o.pitch) * Math.cos(o.yaw),
      target[1] + dist * Math.cos(o.pitch) * Math.sin(o.yaw),
      target[2] + dist * Math.sin(o.pitch),
    ];
    const w = this.canvas.width; const h = this.canvas.height;
    return { target, dist, viewProj: multiply(perspective(0.8, w / h, dist / 100, dist * 100), lookAt(eye, target, [0, 0, 1])) };
  }

  /// A world point in the canvas's pixels (x right, y down), as drawn last.
  project(p) {
    if (!this.viewProj) return null;
    const m = this.viewProj; const v = [0, 0, 0, 0];
    for (let r = 0; r < 4; r += 1) v[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
    return [(v[0] / v[3] + 1) * 0.5 * this.canvas.width, (1 - v[1] / v[3]) * 0.5 * this.canvas.height];
  }

  put(mesh, m, color, pattern = 0, lit = 1) {
    const gl = this.gl;
    gl.uniformMatrix4fv(this.u.uModel, false, m);
    gl.uniform3fv(this.u.uColor, color);
    gl.uniform1i(this.u.uPattern, pattern);
    gl.uniform1f(this.u.uLit, lit);
    gl.bindVertexArray(this.mesh[mesh].vao);
    gl.drawArrays(gl.TRIANGLES, 0, this.mesh[mesh].count);
  }

  /// An arrow from `from` along `vec` (m), shaft radius `r`.
  arrow(from, vec, r, color) {
    const len = Math.hypot(...vec);
    if (!(len > 1e-9)) return;
    const [u, v, d] = basis(vec.map((x) => x / len));
    const head = Math.min(len * 0.4, 5 * r);
    const shaft = len - head;
    const mid = from.map((x, i) => x + d[i] * shaft / 2);
    this.put('cylinder', model(u.map((x) => x * r), v.map((x) => x * r), d.map((x) => x * shaft), mid), color);
    const base = from.map((x, i) => x + d[i] * shaft);
    this.put('cone', model(u.map((x) => x * 2.5 * r), v.map((x) => x * 2.5 * r), d.map((x) => x * head), base), color);
  }

  /// Draws `row`; `info.trace` (the run's columns, for the path) and `info.supports` (where the
  /// supports are now: web/src/spatial.rs `SupportOf`).
  draw(row, info = {}) {
    this.lastRow = row; this.lastInfo = info;
    const gl = this.gl;
    if (!gl) return;
    const w = Math.round(this.canvas.clientWidth * devicePixelRatio) || this.canvas.width;
    const h = Math.round(this.canvas.clientHeight * devicePixelRatio) || this.canvas.height;
    if (this.canvas.width !== w || this.canvas.height !== h) { this.canvas.width = w; this.canvas.height = h; }
    gl.viewport(0, 0, w, h);
    gl.clearColor(...this.background, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.useProgram(this.program);
    const cam = this.cameraFor(row);
    this.viewProj = cam.viewProj;
    gl.uniformMatrix4fv(this.u.uViewProj, false, cam.viewProj);
    const supports = info.supports || (this.shapes && this.shapes.supports) || [];
    const s = this.size;
    let plane = null;
    for (const sup of supports) {
      const p = sup.slice(1, 4); const d = sup.slice(4, 7);
      if (sup[0] === 1) {
        // The plane, under the body, 20 camera distances wide.
        plane = { p, n: d };
        const [u, v] = basis(d);
        const off = dot(cam.target.map((x, i) => x - p[i]), d);
        const centre = cam.target.map((x, i) => x - off * d[i]);
        const side = 20 * cam.dist;
        this.put('square', model(u.map((x) => x * side), v.map((x) => x * side), d, centre), this.planeColor, 3);
      } else if (sup[0] === 3) {
        // The table: its top z = 0 over x <= the edge's x, a slab 20 camera distances wide.
        plane = { p, n: d };
        const side = 20 * cam.dist; const depth = 0.02;
        const centre = [p[0] - side / 2, cam.target[1], -depth / 2];
        this.put('cube', model([side, 0, 0], [0, side, 0], [0, 0, depth], centre), this.planeColor, 3);
      } else if (sup[0] === 2) {
        // A finger lying along d under the line through its tip.
        const r = 0.012;
        const centre = p.map((x, i) => x - (i === 2 ? r : 0));
        const [u, v] = basis(d);
        this.put('cylinder', model(u.map((x) => x * r), v.map((x) => x * r), d.map((x) => x * 0.12), centre), rgb(COLORS.finger1));
      }
    }
    // The path of the body's centre, traced on the plane (or under the body).
    this.drawPath(info.trace, plane);
    // The bodies, each of the scene's solid.
    const [code, a, b, c] = this.shapes.solid;
    // A rod: its length along its x, its thickness along its z, its width (the scene's parameter;
    // the view's box has two sides) along its y; a block: its length, width and height.
    const scale = code === 0 ? [a, this.params.rod_width || b, b] : code === 1 ? [a, a, a] : code === 3 ? [a, b, c] : [a, a, b];
    for (let k = 0; k < BODIES; k += 1) {
      const at = 1 + STATE * k;
      if (Number.isNaN(row[at])) continue;
      const [c0, c1, c2] = rotation([row[at + 3], row[at + 4], row[at + 5], row[at + 6]]);
      const pos = [row[at], row[at + 1], row[at + 2]];
      const m = model(c0.map((x) => x * scale[0]), c1.map((x) => x * scale[1]), c2.map((x) => x * scale[2]), pos);
      this.put(code === 1 ? 'sphere' : code === 2 ? 'cylinder' : 'cube', m, this.bodyColor, code === 1 ? 1 : code === 2 ? 2 : 0);
    }
    // Each contact's force ((pn n + pf t) / h) as an arrow, scaled to the largest seen; its mode's colour.
    const hstep = this.params.step;
    const forces = [];
    for (let i = 0; BODY + CONTACT * (i + 1) <= row.length; i += 1) {
      const at = BODY + CONTACT * i;
      if (Number.isNaN(row[at])) continue;
      const p = [row[at], row[at + 1], row[at + 2]];
      const f = [0, 1, 2].map((k) => (row[at + 10] * row[at + 3 + k] + row[at + 11] * row[at + 6 + k]) / hstep);
      forces.push({ p, f, mode: row[at + 9] });
      this.forceScale = Math.max(this.forceScale, Math.hypot(...f));
    }
    gl.disable(gl.DEPTH_TEST);
    if (info.bare) return;
    for (const { p, f, mode } of forces) {
      const color = MODE_RGB[mode] || MODE_RGB[0];
      const r = Math.max(s, 0.05) * 0.02;
      this.put('sphere', model([r * 1.8, 0, 0], [0, r * 1.8, 0], [0, 0, r * 1.8], p), color, 0, 0);
      if (this.forceScale > 0) this.arrow(p, f.map((x) => (x / this.forceScale) * 1.2 * Math.max(s, 0.1)), r, color);
    }
  }

  drawPath(trace, plane) {
    if (!trace || trace.n < 2) return;
    const gl = this.gl;
    const n = trace.n; const stride = Math.max(1, Math.ceil(n / 4000));
    const pts = [];
    const lift = 0.002 * Math.max(this.size, 0.05);
    for (let i = 0; i < n; i += stride) {
      let p = [trace.cols.x[i], trace.cols.y[i], trace.cols.z[i]];
      if (plane) {
        const off = dot(p.map((x, k) => x - plane.p[k]), plane.n);
        p = p.map((x, k) => x - (off - lift) * plane.n[k]);
      }
      pts.push(...p, 0, 0, 1);
    }
    gl.bindVertexArray(this.path.vao);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.path.buffer);
    gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(pts), gl.DYNAMIC_DRAW);
    gl.enableVertexAttribArray(0); gl.vertexAttribPointer(0, 3, gl.FLOAT, false, 24, 0);
    gl.enableVertexAttribArray(1); gl.vertexAttribPointer(1, 3, gl.FLOAT, false, 24, 12);
    gl.uniformMatrix4fv(this.u.uModel, false, model([1, 0, 0], [0, 1, 0], [0, 0, 1], [0, 0, 0]));
    gl.uniform3fv(this.u.uColor, rgb(COLORS.normal));
    gl.uniform1i(this.u.uPattern, 0);
    gl.uniform1f(this.u.uLit, 0);
    gl.drawArrays(gl.LINE_STRIP, 0, pts.length / 6);
  }

  /// The canvas's pixels: how many distinct colours, the colour at the body's centre and how many
  /// pixels have the body's hue (for the page's test: the bodies are drawn, not a blank frame).
  pixels() {
    const gl = this.gl;
    if (!gl || !this.lastRow) return null;
    // The body's pixel is read in a frame without the arrows (which are drawn over it).
    const [row, info] = [this.lastRow, this.lastInfo];
    this.draw(row, { ...info, bare: true });
    const w = this.canvas.width; const h = this.canvas.height;
    const data = new Uint8Array(w * h * 4);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, data);
    const seen = new Set();
    const hue = (r, g, b) => { const s = Math.max(r + g + b, 1); return [r / s, g / s, b / s]; };
    const bodyHue = hue(...this.bodyColor);
    let bodyPixels = 0;
    for (let i = 0; i < data.length; i += 4) {
      seen.add((data[i] << 16) | (data[i + 1] << 8) | data[i + 2]);
      const q = hue(data[i], data[i + 1], data[i + 2]);
      if (data[i] > 30 && Math.hypot(q[0] - bodyHue[0], q[1] - bodyHue[1], q[2] - bodyHue[2]) < 0.08) bodyPixels += 1;
    }
    const [x, y] = this.project([this.lastRow[1], this.lastRow[2], this.lastRow[3]]).map(Math.round);
    const at = ((h - 1 - y) * w + x) * 4;
    const to255 = (c) => c.map((v) => Math.round(v * 255));
    this.draw(row, info);
    return {
      colours: seen.size, width: w, height: h, centre: [x, y], bodyPixels,
      body: Array.from(data.subarray(at, at + 3)), bodyColor: to255(this.bodyColor),
      background: to255(this.background), plane: to255(this.planeColor),
    };
  }
}
