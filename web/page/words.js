// The page's words and numbers: the measured quantities in words, the LCP's size, numbers as
// typed, flag units, run B's compare field, plot scales. Pure functions of their arguments (no
// page state), imported by app.js.

/// A measured quantity (summary.json's key) in words.
const MEASURE_WORDS = {
  'meeting.time_s': (v) => `the fingers met at t = ${v.toFixed(3)} s`,
  'meeting.com_offset_m': (v) => `the centre of mass ${(1e3 * v).toFixed(2)} mm from their midpoint`,
  acceleration_m_s2: (v) => `acceleration down the slope ${v.toFixed(5)} m/s²`,
  angular_acceleration_rad_s2: (v) => `angular acceleration ${v.toFixed(4)} rad/s² (counter-clockwise)`,
  wall_release_height_m: (v) => `the top left the wall at ${v.toFixed(4)} m`,
  wall_release_ratio: (v) => `${v.toFixed(4)} of its start height`,
  'jam.time_s': (v) => `the end jammed at t = ${v.toFixed(4)} s`,
  'jam.normal_impulse_n_s': (v) => `normal impulse ${v.toFixed(5)} N s`,
  'jam.friction_impulse_n_s': (v) => `friction impulse ${v.toFixed(5)} N s`,
  block_displacement_m: (v) => `the block moved ${(100 * v).toFixed(2)} cm`,
  top_acceleration_m_s2: (v) => `the top block's acceleration ${v.toFixed(4)} m/s²`,
  max_speed_m_s: (v) => `the fastest point's largest speed ${v.toFixed(4)} m/s`,
};

/// A scene's own words for a key it shares with others.
const SCENE_MEASURE_WORDS = {
  'block-on-block': { acceleration_m_s2: (v) => `the bottom block's acceleration ${v.toFixed(4)} m/s²` },
  'disc-on-board': {
    acceleration_m_s2: (v) => `the board's acceleration ${v.toFixed(4)} m/s²`,
    top_acceleration_m_s2: (v) => `the disc centre's ${v.toFixed(4)} m/s²`,
  },
};

/// The measured quantities ({key: value | null}) of `scene` in words; '-' when there are none.
export function measuredText(values, scene) {
  const words = { ...MEASURE_WORDS, ...(SCENE_MEASURE_WORDS[scene] || {}) };
  const parts = Object.entries(values).filter(([, v]) => v !== null && v !== undefined)
    .map(([key, v]) => (words[key] ? words[key](v) : `${key} ${v}`));
  return parts.length ? parts.join('; ') : '-';
}

/// The LCP of a scene of k contacts in the layout the form's lcp-size (6 reduced, 8 full) selects:
/// 3k x 3k or 4k x 4k.
export function lcpText(k, size) {
  if (k === 0) return 'full LCP'; // a scene of several bodies: sized by its candidate contacts
  const n = (size === '8' ? 4 : 3) * k;
  return `${n}x${n}`;
}

/// A number for display: at most 12 significant digits, as typed (35, not 35.00000000000001).
export function plain(v) {
  return String(Number(v.toPrecision(12)));
}

export function toFlagUnit(flag, v) {
  return flag.unit === 'deg' ? (v * 180) / Math.PI : v;
}

/// Run B's flags as the compare field and the URL write them ("force=20 mu-k=0.3"): [[flag, text]],
/// or {message}.
export function parseCompare(text) {
  const pairs = [];
  for (const part of text.split(/[\s&,]+/).filter(Boolean)) {
    const [key, value] = part.split('=');
    if (value === undefined || value.trim() === '') return { message: `compare: ${JSON.stringify(part)} is not flag=value` };
    pairs.push([key.replace(/^b\./, ''), value]);
  }
  return { pairs };
}

export function niceCeil(t) {
  if (!(t > 0)) return 1;
  const p = 10 ** Math.floor(Math.log10(t));
  for (const f of [1, 1.5, 2, 3, 5, 7.5, 10]) if (f * p >= t) return f * p;
  return 10 * p;
}

export function scaled(a, n, k) {
  if (k === 1) return a;
  const out = new Float64Array(n);
  for (let i = 0; i < n; i += 1) out[i] = a[i] * k;
  return out;
}
