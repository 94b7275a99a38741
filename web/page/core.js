// The wasm modules (meterstick-web, built into pkg/) and their exports, wrapped for the page and
// the map workers. A module has no imports; its API is plain numbers and two buffers in linear
// memory (see web/src/exports.rs and docs/page.md). Each module holds the scenes of some
// numbers of contacts (its description's `holds`): meterstick_web.wasm the two-contact scenes,
// meterstick_web_k1.wasm and meterstick_web_k3.wasm the others, meterstick_web_mb.wasm the scenes
// of several bodies (contacts 0 in `holds`), fetched when such a scene is chosen.

export const WASM_URL = new URL('./pkg/meterstick_web.wasm', import.meta.url);

/// The module that holds the scenes of k contacts (0: the scenes of several bodies).
export function moduleUrl(k) {
  if (k === 2) return WASM_URL;
  return new URL(k === 0 ? './pkg/meterstick_web_mb.wasm' : `./pkg/meterstick_web_k${k}.wasm`, import.meta.url);
}

/// Compiles a module (once; the map workers get the compiled module).
/// A module by its file name in pkg/ (pkg/intros.json names each scene's: the planar modules do
/// not name the scenes in three dimensions, whose module is meterstick_web_sp.wasm).
export function moduleFileUrl(file) {
  return new URL(`./pkg/${file}`, import.meta.url);
}

export async function compileCore(url = WASM_URL) {
  const response = await fetch(url);
  if (!response.ok) {
    throw new Error(`${url.pathname}: ${response.status} ${response.statusText} (build it: bash scripts/web.sh)`);
  }
  return WebAssembly.compile(await response.arrayBuffer());
}

/// A new instance of the compiled module: one session (one run at a time).
export async function instantiateCore(module) {
  const instance = await WebAssembly.instantiate(module, {});
  return new Core(instance.exports);
}

const decoder = new TextDecoder();

export class Core {
  constructor(exports) {
    this.x = exports;
    /// The description: scenes (fields, defaults, contacts, row length, measures, outcomes), flags
    /// (unit, help, field per scene), modes, outcomes, the contact counts this module holds.
    this.desc = JSON.parse(this.text(exports.ms_describe()));
    this.flagIndex = new Map(this.desc.flags.map((f, i) => [f.long, i]));
  }

  text(len) {
    return decoder.decode(new Uint8Array(this.x.memory.buffer, this.x.ms_text_ptr(), len));
  }

  scene(name) {
    return this.desc.scenes.find((s) => s.name === name);
  }

  /// `true` for a scene of several bodies (rows of time and each body's x, y, theta).
  isBodies(name) {
    const scene = this.scene(name);
    return Boolean(scene && scene.bodies);
  }

  /// The number of contacts of a scene (0 for a scene of several bodies).
  isSpatial(name) {
    const scene = this.scene(name);
    return Boolean(scene && scene.spatial);
  }

  contacts(name) {
    const scene = this.scene(name);
    return scene ? scene.contacts.length : 0;
  }

  /// The flags of a scene, in table order.
  flagsOf(sceneName) {
    return this.desc.flags.filter((f) => sceneName in f.fields);
  }

  /// Makes a run: `given` maps flag names to numbers (in the flag's unit). Returns
  /// {ok: true, params, cautions} (params: core field -> value, SI and radians; cautions: what the
  /// run is told before it starts, host-sim's words without the flags' `--`) or
  /// {ok: false, message, flag}.
  create(sceneName, given, precision, lcpSize) {
    const sceneIndex = this.desc.scenes.findIndex((s) => s.name === sceneName);
    if (sceneIndex < 0 || this.x.ms_configure(sceneIndex) !== 0) {
      const names = this.desc.scenes.map((s) => s.name).join(', ');
      return { ok: false, message: `unknown scene ${JSON.stringify(sceneName)} (${names})`, flag: null };
    }
    for (const [long, value] of given) {
      const i = this.flagIndex.get(long);
      if (i === undefined || this.x.ms_give(i, value) !== 0) {
        return { ok: false, message: `unknown parameter ${JSON.stringify(long)}`, flag: null };
      }
    }
    const bits = precision === 'f64' ? 64 : 32;
    const n = Number(lcpSize) === 8 ? 8 : 6;
    const code = this.x.ms_create(bits, n);
    if (code !== 0) {
      const message = code === 1 ? this.text(this.x.ms_text_len()) : `bad precision or LCP size`;
      const f = this.x.ms_error_flag();
      return { ok: false, message, flag: f >= 0 ? this.desc.flags[f].long : null };
    }
    this.current = this.scene(sceneName);
    const fields = this.current.fields;
    const params = Object.fromEntries(fields.map((name, i) => [name, this.x.ms_param(i)]));
    const n2 = this.x.ms_cautions();
    const cautions = n2 > 0 ? this.text(n2).split('\n') : [];
    return { ok: true, params, cautions };
  }

  /// The run's bodies, for a scene of several bodies: {sizes: [[width, height]] (body 0 the
  /// lowest), round: [bool] (a disc, its diameter the width), table: [lo, hi] (null for an end it
  /// does not have)}; null for a scene of one body.
  shapes() {
    if (this.current && this.current.spatial) return { spatial: true, sizes: [], solid: [0, 1, 2, 3].map((j) => this.x.ms_solid(j)), supports: this.supports() };
    if (!this.current || !this.current.bodies) return null;
    const sizes = [];
    for (let i = 0; !Number.isNaN(this.x.ms_body_size(i, 0)); i += 1) sizes.push([this.x.ms_body_size(i, 0), this.x.ms_body_size(i, 1)]);
    const round = sizes.map((_, i) => this.x.ms_body_round(i) === 1);
    const end = (i) => { const v = this.x.ms_table_end(i); return Number.isNaN(v) ? null : v; };
    return { sizes, round, table: [end(0), end(1)] };
  }

  /// The state at t = 0 as a row (a copy).
  /// The supports of a scene in three dimensions where the last step left them: [code, point,
  /// direction] each (web/src/spatial.rs `SupportOf`).
  supports() {
    const out = [];
    for (let i = 0; !Number.isNaN(this.x.ms_support(i, 0)); i += 1) out.push(Array.from({ length: 7 }, (_, j) => this.x.ms_support(i, j)));
    return out;
  }

  startRow() {
    this.x.ms_start_row();
    return new Float64Array(this.x.memory.buffer, this.x.ms_trace_ptr(), this.current.row).slice();
  }

  /// Steps up to n times; returns the rows written (a view, valid until the next call).
  step(n) {
    const taken = this.x.ms_step(n);
    return new Float64Array(this.x.memory.buffer, this.x.ms_trace_ptr(), taken * this.current.row);
  }

  /// After the outcome, steps a copy of the run on past it (the bodies go on; the run stays as
  /// judged); returns the rows written (a view, valid until the next call; none once it stops).
  stepPast(n) {
    const taken = this.x.ms_step_past(n);
    return new Float64Array(this.x.memory.buffer, this.x.ms_trace_ptr(), taken * this.current.row);
  }

  /// Steps up to max times without rows; returns the steps taken.
  run(max) {
    return this.x.ms_run(max);
  }

  /// null while the run goes on, else {code, name, text}.
  outcome() {
    const code = this.x.ms_outcome();
    if (code < 0) return null;
    return { code, name: this.desc.outcomes[code], text: this.text(this.x.ms_outcome_text()) };
  }

  /// The trajectory checksum as host-sim scene prints it: 8 hex digits.
  checksum() {
    return (this.x.ms_checksum() >>> 0).toString(16).padStart(8, '0');
  }

  time() { return this.x.ms_time(); }

  stats() {
    const s = (i) => this.x.ms_stat(i);
    return { steps: s(0), pivots: s(1), maxPivots: s(2), warmStarts: s(3), fullLayout: s(4), regularized: s(5) };
  }

  /// The run's measured quantities: {key: value or null}, keyed as summary.json names them.
  measured() {
    return Object.fromEntries(this.current.measures.map((key, i) => {
      const v = this.x.ms_measured(i);
      return [key, Number.isNaN(v) ? null : v];
    }));
  }
}

/// Parses a number as host-sim does (Rust's f64 syntax after trimming: "0.1", "-5e-3", ".5",
/// "inf", "NaN"); returns {value} or {message} in host-sim's words.
export function parseNumber(text) {
  const t = text.trim();
  const rust = /^[+-]?(?:(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?|inf|infinity|nan)$/i;
  if (!rust.test(t)) {
    const why = t.startsWith('--') ? ': every flag needs a value' : '';
    return { message: `${JSON.stringify(t)} is not a number${why}` };
  }
  const lower = t.toLowerCase().replace(/^\+/, '');
  if (/^-?inf(inity)?$/.test(lower)) return { value: lower.startsWith('-') ? -Infinity : Infinity };
  if (/^-?nan$/.test(lower)) return { value: NaN };
  return { value: Number(t) };
}
