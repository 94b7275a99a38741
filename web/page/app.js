// The page: builds the controls from the core's description, reads and writes the URL contract
// (?scene=meter-stick&speed=0.1&mu-s=0.6&mu-k=0.4&x1=-0.35&autorun=1: the scene and host-sim's flag
// names), runs the core live (or replays a run of host-sim run), animates and plots it, and writes
// the outcome and the trajectory checksum into #outcome and #checksum when the run ends. The
// scenes, their flags, contacts, measured quantities and outcomes come from the core's description
// (the catalogue); a scene whose contacts the first module does not hold runs in the module that
// does, fetched when it is chosen.

import { compileCore, instantiateCore, parseNumber } from './core.js';
import { pageModules } from './modules.js';
import { SpaceView } from './view3d.js';
import { spatialCaptions, drawSpatialPlots } from './space.js';
import { SceneView, drawPlot, COLORS, CONTACT_COLORS } from './draw.js';
import { OutcomeMap } from './map.js';
import { listRuns, loadRun } from './replay.js';
import { liveSource, replaySource } from './sources.js';
import { testHooks } from './hooks.js';
import { MODE_NAMES } from './trace.js';
import { lcpText, measuredText, niceCeil, parseCompare, plain, scaled, toFlagUnit } from './words.js';

const $ = (id) => document.getElementById(id);

/// Query keys that are not scene flags (and `b.<flag>`: run B's flags, the comparison).
const PAGE_KEYS = ['scene', 'precision', 'lcp-size', 'autorun', 'rate', 'replay', 'map', 'bench', 'after'];

const S = {
  core: null,
  main: null,
  cores: new Map(),
  module: null,
  scene: 'meter-stick',
  inputs: new Map(),
  source: null,
  playing: false,
  rate: '1',
  simTarget: 0,
  lastFrame: 0,
  lastPlot: 0,
  shownEvents: -1,
  speedWindow: { t: 0, steps: 0, rate: 0 },
  // Run B (the comparison: the same scene, run A's flags with `compare`'s changed), its cores.
  other: null,
  compare: [],
  coresB: new Map(),
  goOn: true,
  intros: null,
};

const view2d = new SceneView($('scene'));
const view3d = new SpaceView($('scene3d'));
/// The drawing of run A: in the plane, or in perspective for a scene in three dimensions.
let view = view2d;
const { coreFor, coreBFor, knownScene, sceneNames } = pageModules(S, () => $('precision').value);
const viewB = new SceneView($('scene-b'));
const map = new OutcomeMap({
  canvas: $('map'), status: $('map-status'), time: $('map-time'), cell: $('map-cell'),
  onLoad: ({ speed, muK }) => {
    if (S.scene !== 'meter-stick' || (S.source && S.source.kind === 'replay')) return;
    S.inputs.get('speed').value = String(speed);
    S.inputs.get('mu-k').value = String(muK);
    if (makeRun()) {
      play();
      $('scene').scrollIntoView({ block: 'nearest', behavior: 'smooth' });
    }
  },
});

function setState(state) {
  document.body.dataset.state = state;
}

/// Makes `scene` the form's scene, with the core that runs it (and run B's, when comparing).
async function selectScene(scene) {
  S.core = await coreFor(scene);
  S.coreB = S.compare.length ? await coreBFor(scene) : null;
  buildForm(scene);
  showIntro(scene);
}

/// The scene's heading and introduction (the catalogue's, from pkg/intros.json; the title when
/// that is missing).
function showIntro(scene) {
  const intro = S.intros && S.intros[scene];
  $('heading').textContent = intro ? intro.heading : S.core.scene(scene).title;
  $('intro').textContent = intro ? intro.intro : '';
  document.title = `meterstick: ${$('heading').textContent}`;
}

// --- the form ---------------------------------------------------------------------------------

function buildForm(scene) {
  S.scene = scene;
  $('scene-select').value = scene;
  const k = S.core.contacts(scene);
  $('lcp-size').options[0].textContent = `${lcpText(k, '6')} (firmware)`;
  $('lcp-size').options[1].textContent = `${lcpText(k, '8')} (${k === 2 ? 'paper' : 'full'})`;
  // A scene of several bodies has one LCP form, sized by its candidate contacts: no choice.
  $('lcp-size').disabled = k === 0 || S.core.isSpatial(scene);
  const bodies = S.core.isBodies(scene);
  if (!S.captions) S.captions = ['cap-positions', 'cap-angle', 'cap-height'].map((id) => $(id).innerHTML);
  const bodyCaptions = ['Positions: each body\'s centre of mass (body 1 the lowest), x (m) over t (s)',
    'Angle of each body (deg) over t (s)', 'Height of each body\'s centre of mass (cm) over t (s)'];
  ['cap-positions', 'cap-angle', 'cap-height'].forEach((id, i) => {
    if (bodies) $(id).textContent = bodyCaptions[i]; else $(id).innerHTML = S.captions[i];
  });
  if (S.core.isSpatial(scene)) spatialCaptions($);
  // The catalogue's main flags are shown first, the rest under "More parameters".
  const isMain = (flag) => S.core.scene(scene).main_flags.includes(flag.long);
  const main = $('main-fields'); const more = $('more-fields');
  main.replaceChildren(); more.replaceChildren();
  S.inputs.clear();
  const sceneDesc = S.core.scene(scene);
  for (const flag of S.core.flagsOf(scene)) {
    const field = flag.fields[scene];
    const def = sceneDesc.defaults[sceneDesc.fields.indexOf(field)];
    const box = document.createElement('div');
    box.className = 'field';
    const id = `p-${flag.long}`;
    const label = document.createElement('label');
    label.htmlFor = id;
    label.textContent = flag.long;
    if (flag.unit) {
      const unit = document.createElement('span');
      unit.className = 'unit';
      unit.textContent = ` (${flag.unit})`;
      label.append(unit);
    }
    const input = document.createElement('input');
    input.id = id; input.name = flag.long; input.type = 'text'; input.inputMode = 'decimal';
    input.autocomplete = 'off'; input.spellcheck = false;
    input.placeholder = plain(toFlagUnit(flag, def));
    input.title = flag.help;
    input.setAttribute('aria-description', flag.help);
    input.addEventListener('change', () => makeRun());
    box.append(label, input);
    (isMain(flag) ? main : more).append(box);
    S.inputs.set(flag.long, input);
  }
  $('map-run').disabled = scene !== 'meter-stick';
  $('map-section').dataset.scene = scene;
}

/// The flags the user set: [[flag, number]], or {message, flag} for text that is not a number.
function givenFlags() {
  const given = [];
  for (const [long, input] of S.inputs) {
    input.removeAttribute('aria-invalid');
    const text = input.value.trim();
    if (text === '') continue;
    const parsed = parseNumber(text);
    if (parsed.message !== undefined) return { message: `${long}: ${parsed.message}`, flag: long };
    given.push([long, parsed.value]);
  }
  return { given };
}

function showError(message, flag) {
  $('error').textContent = message;
  const input = flag && S.inputs.get(flag);
  if (input) {
    input.setAttribute('aria-invalid', 'true');
    if (input.closest('details')) input.closest('details').open = true;
  }
}

function writeUrl() {
  const q = new URLSearchParams();
  q.set('scene', S.scene);
  for (const [long, input] of S.inputs) if (input.value.trim() !== '') q.set(long, input.value.trim());
  if ($('precision').value !== 'f32') q.set('precision', $('precision').value);
  if ($('lcp-size').value !== '6') q.set('lcp-size', $('lcp-size').value);
  if (S.rate !== '1') q.set('rate', S.rate);
  if (!S.goOn) q.set('after', '0');
  for (const [long, value] of S.compare) q.set(`b.${long}`, value);
  history.replaceState(null, '', `?${q.toString()}`);
}

// --- runs -----------------------------------------------------------------------------------------

/// What a live run takes from the form: its precision and LCP size (shown with its result), and
/// whether it goes on past its outcome (`after`).
function liveOptions() {
  return { precision: $('precision').value, lcpSize: $('lcp-size').value, goOn: S.goOn };
}

function clearResult(status) {
  $('outcome').textContent = '';
  $('outcome').removeAttribute('data-outcome');
  $('checksum').textContent = '';
  $('status').textContent = status;
  $('measured').textContent = '-';
  delete $('measured').dataset.values;
  $('eq21').replaceChildren();
  for (const id of ['outcome-b', 'checksum-b', 'measured-b']) $(id).textContent = '';
  $('outcome-b').removeAttribute('data-outcome');
  $('csv').disabled = true;
  $('cautions').textContent = '';
  document.body.dataset.after = '';
  S.shownEvents = -1;
}

/// Makes a new live run from the form (paused at t = 0); false when the parameters are refused.
function makeRun() {
  pause();
  $('error').textContent = '';
  clearResult('ready: press Play');
  writeUrl();
  const parsed = givenFlags();
  if (parsed.message) {
    showError(parsed.message, parsed.flag);
    S.source = null;
    clearResult('not run: invalid parameters');
    drawEmpty();
    setState('error');
    return false;
  }
  const made = S.core.create(S.scene, parsed.given, $('precision').value, $('lcp-size').value);
  if (!made.ok) {
    showError(made.message, made.flag);
    S.source = null;
    clearResult('not run: invalid parameters');
    drawEmpty();
    setState('error');
    return false;
  }
  // Placeholders show what an empty field means for this run (the meter stick's time limit grows
  // with the fingers' travel).
  for (const flag of S.core.flagsOf(S.scene)) {
    const v = made.params[flag.fields[S.scene]];
    S.inputs.get(flag.long).placeholder = plain(toFlagUnit(flag, v));
  }
  // A scene in three dimensions is drawn in perspective (view3d.js), with no run B.
  const spatial = S.core.isSpatial(S.scene);
  view = spatial ? view3d : view2d;
  $('scene').hidden = spatial; $('scene3d').hidden = !spatial;
  S.source = liveSource(S.core, made.params, view, liveOptions());
  S.other = null;
  S.simTarget = 0;
  view.setScene(S.scene, made.params, S.source.trace.last, S.source.trace.k, S.source.shapes);
  let cautionsB = [];
  if (S.compare.length && S.coreB && !spatial) {
    // Run B: run A's flags with the comparison's changed, in a second instance of the module.
    const given = new Map(parsed.given);
    for (const [long, text] of S.compare) {
      const v = parseNumber(text);
      if (v.message !== undefined) { showError(`b.${long}: ${v.message}`); setState('error'); S.source = null; return false; }
      given.set(long, v.value);
    }
    const madeB = S.coreB.create(S.scene, [...given], $('precision').value, $('lcp-size').value);
    if (!madeB.ok) {
      showError(`run B: ${madeB.message}`);
      S.source = null; clearResult('not run: invalid parameters'); drawEmpty(); setState('error');
      return false;
    }
    S.other = liveSource(S.coreB, madeB.params, viewB, liveOptions());
    cautionsB = madeB.cautions.map((c) => `run B: ${c}`);
    viewB.setScene(S.scene, madeB.params, S.other.trace.last, S.other.trace.k, S.other.shapes);
  }
  // What the precision may not follow (friction beyond it, a mass ratio outside f32's reach).
  $('cautions').textContent = made.cautions.concat(cautionsB).join('\n');
  document.body.classList.toggle('comparing', Boolean(S.other));
  $('run-a-label').textContent = S.other ? `Run A: ${runLabel(S.source)}` : '';
  $('run-b-label').textContent = S.other ? `Run B: ${runLabel(S.other)}` : '';
  if (S.scene === 'meter-stick') {
    map.setCurrent({ speed: made.params.finger1_velocity, ratio: made.params.mu_kinetic / made.params.mu_static });
  }
  $('eq21-target').textContent = S.scene === 'meter-stick'
    ? `mu_k/mu_s = ${(made.params.mu_kinetic / made.params.mu_static).toFixed(4)}` : 'mu_k/mu_s (meter stick)';
  $('run-info').textContent = `${S.source.precision} ${lcpText(S.source.trace.k, S.source.lcpSize)}, h = ${plain(made.params.step)} s, until t = ${plain(made.params.max_time)} s`;
  setState('ready');
  render(true);
  return true;
}

/// A run's flags that differ from run B's or A's: what the comparison changed ("force 20 N").
function runLabel(src) {
  const changed = S.compare.map(([long]) => {
    const flag = S.core.desc.flags.find((f) => f.long === long);
    if (!flag || !(S.scene in flag.fields)) return long;
    return `${long} ${plain(toFlagUnit(flag, src.params[flag.fields[S.scene]]))}${flag.unit ? ` ${flag.unit}` : ''}`;
  });
  return changed.join(', ');
}

/// The runs shown: A, and B when comparing.
function runs() {
  return S.source ? [S.source, ...(S.other ? [S.other] : [])] : [];
}

/// Shows the outcomes of the runs the judge has decided; once all have, the result (the state
/// 'ended'); once nothing is left to step (the runs went on past their outcomes), pauses.
function settle() {
  const all = runs();
  const b = S.other;
  if (b && b.ended && !b.shown) {
    b.shown = true;
    $('outcome-b').textContent = b.outcome.text;
    $('outcome-b').dataset.outcome = b.outcome.name;
    $('checksum-b').textContent = b.checksum;
    $('measured-b').textContent = measuredText(b.measured, b.scene);
    $('measured-b').dataset.values = JSON.stringify(b.measured);
  }
  if (all.every((r) => r.ended) && !S.source.shown) {
    S.source.shown = true;
    finish();
  }
  const going = all.some((r) => r.ended && !r.done);
  if (all.every((r) => r.ended)) document.body.dataset.after = going ? 'going' : 'done';
  if (all.every((r) => r.done)) { pause(); render(true); return true; }
  return false;
}

function finish() {
  const src = S.source;
  const out = $('outcome');
  out.textContent = src.outcome.text;
  out.dataset.outcome = src.outcome.name;
  if (src.kind === 'live') {
    $('checksum').textContent = src.checksum;
    const s = src.stats;
    const k = src.trace.k;
    $('run-info').textContent = `${src.precision} ${lcpText(k, src.lcpSize)}, h = ${plain(src.params.step)} s: `
      + `${s.steps.toLocaleString('en')} steps, ${s.pivots.toLocaleString('en')} pivots`
      + (src.trace.bodies > 0 ? '' : `, ${s.fullLayout.toLocaleString('en')} steps needed the ${lcpText(k, '8')} form`);
    $('measured').textContent = measuredText(src.measured, src.scene);
    $('measured').dataset.values = JSON.stringify(src.measured);
    $('csv').disabled = false;
  } else {
    $('checksum').textContent = 'replay: see host-sim scene';
    const c = src.run.summary.core; const r = src.run.summary.reference;
    $('run-info').textContent = `replay of ${src.run.name}: ${c.implementation} ${c.steps.toLocaleString('en')} steps; `
      + (r ? `${r.implementation}: ${r.outcome}` : 'no reference');
    const keys = S.core.scene(src.scene).measures;
    const values = Object.fromEntries(keys.map((key) => [key, key.split('.').reduce((v, part) => (v == null ? null : v[part]), c.measured)]));
    $('measured').textContent = measuredText(values, src.scene);
  }
  setState('ended');
  if (src.going) $('status').textContent = 'going on after the outcome';
  render(true);
}

// --- playback ---------------------------------------------------------------------------------------

function play() {
  const src = S.source;
  if (!src) return;
  if (runs().every((r) => r.done)) {
    if (src.kind === 'live') { if (!makeRun()) return; } else { startReplay(src.run); }
  }
  S.playing = true;
  S.simTarget = Math.min(...runs().map((r) => r.trace.time));
  S.lastFrame = performance.now();
  S.speedWindow = { t: performance.now(), steps: S.source.trace.n, rate: 0 };
  $('play').textContent = 'Pause';
  $('status').textContent = S.source.ended ? 'going on after the outcome' : 'running';
  if (!S.source.ended) setState('running');
  requestAnimationFrame(tick);
}

function pause() {
  S.playing = false;
  $('play').textContent = 'Play';
  if (S.source && !S.source.done) $('status').textContent = 'paused';
}

function stepOnce() {
  const all = runs();
  if (!all.length || all.every((r) => r.done)) return;
  pause();
  for (const r of all) r.advance(1);
  if (!settle()) render(true);
}

function tick(now) {
  if (!S.playing) return;
  const all = runs();
  const dt = Math.min(0.1, Math.max(0, (now - S.lastFrame) / 1000));
  S.lastFrame = now;
  const t0 = performance.now();
  const active = () => all.filter((r) => !r.done);
  if (S.rate === 'max') {
    do { for (const r of active()) r.advance(2048); } while (active().length && !all.every((r) => r.ended) && performance.now() - t0 < 14);
  } else {
    S.simTarget += dt * Number(S.rate);
    for (const r of active()) {
      let want = Math.floor((S.simTarget - r.trace.time) / r.params.step + 1e-6);
      while (want > 0 && !r.done && performance.now() - t0 < 30) {
        const k = r.advance(Math.min(want, 2048));
        if (k === 0) break;
        want -= k;
      }
    }
    // The machine cannot keep up: do not fall behind.
    const behind = active().map((r) => r.trace.time);
    if (behind.length && Math.min(...behind) < S.simTarget - 0.05) S.simTarget = Math.min(...behind);
  }
  const w = S.speedWindow;
  if (now - w.t > 500) {
    w.rate = ((S.source.trace.n - w.steps) / (now - w.t)) * 1000;
    w.t = now; w.steps = S.source.trace.n;
  }
  if (!settle()) { render(false); requestAnimationFrame(tick); }
}

// --- drawing ------------------------------------------------------------------------------------------

function drawEmpty() {
  const g = $('scene').getContext('2d');
  g.fillStyle = '#fff'; g.fillRect(0, 0, $('scene').width, $('scene').height);
  for (const id of ['plot-positions', 'plot-angle', 'plot-height']) {
    const c = $(id); c.getContext('2d').clearRect(0, 0, c.width, c.height);
  }
  $('clock').textContent = '';
}

function render(full) {
  const src = S.source;
  if (!src) return;
  const tr = src.trace;
  const rateText = S.playing
    ? (S.rate === 'max' ? `${(S.speedWindow.rate / 1e3).toFixed(0)}k steps/s` : `${S.rate}x`) : '';
  const title = src.kind === 'replay'
    ? `replay ${src.run.name}: ${src.run.summary.core.implementation} (reference dashed)`
    : S.other ? `run A: ${runLabel(src)}` : `${S.core.scene(src.scene).title}, ${src.precision} ${lcpText(src.trace.k, src.lcpSize)}`;
  view.draw(tr.last, {
    trace: tr, supports: tr.spatial && src.kind === 'live' ? S.core.supports() : null,
    title, time: tr.time, steps: tr.n - 1, outcome: src.ended ? src.outcome : null,
    reference: src.referenceRow ? src.referenceRow() : null, rate: rateText, moving: moving(tr),
  });
  if (S.other) {
    const b = S.other; const bt = b.trace;
    viewB.draw(bt.last, {
      title: `run B: ${runLabel(b)}`, time: bt.time, steps: bt.n - 1, outcome: b.ended ? b.outcome : null,
      reference: null, rate: rateText, moving: moving(bt),
    });
  }
  $('clock').textContent = `t = ${tr.time.toFixed(3)} s`;
  const now = performance.now();
  if (!full && now - S.lastPlot < (S.rate === 'max' ? 150 : 50)) return;
  S.lastPlot = now;
  drawPlots(src);
  if (tr.events.length !== S.shownEvents) showSwitches(src);
}

/// Each support's velocity over the last step (m/s; 0 when it did not move): the moving fingers.
function moving(tr) {
  if (tr.k === 0 || tr.n < 2) return undefined;
  const dt = tr.cols.t[tr.n - 1] - tr.cols.t[tr.n - 2];
  return Array.from({ length: tr.k }, (_, i) => {
    const c = tr.cols[`s${i + 1}x`];
    const v = (c[tr.n - 1] - c[tr.n - 2]) / dt;
    return Math.abs(v) > 1e-9 ? v : 0;
  });
}

function drawPlots(src) {
  const tr = src.trace;
  if (tr.spatial) { drawSpatialPlots($, src, view3d.shapes); return; }
  // A replay's reference, or run B: dashed on the same time axis.
  const ref = src.reference || (S.other ? S.other.trace : null);
  const markers = Boolean(src.reference);
  const tMax = src.kind === 'replay'
    ? src.run.core.rows[(src.run.core.n - 1) * tr.row] : niceCeil(Math.max(tr.time, ref ? ref.time : 0, 10 * src.params.step));
  const c = tr.cols;
  const series = (key, color, width, scale = 1) => [
    ...(ref ? [{ t: ref.cols.t, y: scaled(ref.cols[key], ref.n, scale), n: ref.n, color, width: markers ? 1.5 : 2.5, dash: [6, 4], markers }] : []),
    { t: c.t, y: scaled(c[key], tr.n, scale), n: tr.n, color, width },
  ];
  const ticks = tr.events.map((e) => ({ t: e.t, color: [COLORS.separated, COLORS.stick, COLORS.slide, COLORS.slide][e.mode] }));
  const marks = tr.events.filter((e) => e.ratio !== null).map((e) => ({
    t: e.t, y: e.x, color: CONTACT_COLORS[e.contact], label: e.ratio.toFixed(3),
  }));
  if (tr.bodies > 0) {
    // Each body's x, angle and height (body 1 the lowest), in the contacts' colours.
    const each = (key, scale) => Array.from({ length: tr.bodies }, (_, b) => series(`b${b + 1}${key}`, CONTACT_COLORS[b], 2.5, scale)).flat();
    drawPlot($('plot-positions'), { series: each('x', 1), ticks, tMax, yLabel: 'x (m)', aspect: 0.39 });
    drawPlot($('plot-angle'), { series: each('theta', 180 / Math.PI), ticks, tMax, yLabel: 'angle (deg)', aspect: 0.24, minSpan: 2 });
    drawPlot($('plot-height'), { series: each('y', 100), ticks, tMax, yLabel: 'height (cm)', aspect: 0.24, minSpan: 1 });
    return;
  }
  const supports = Array.from({ length: tr.k }, (_, i) => series(`s${i + 1}x`, CONTACT_COLORS[i], 2.5)).flat();
  drawPlot($('plot-positions'), {
    series: [...supports, ...series('x', COLORS.com, 3.5)],
    marks, ticks, tMax, yLabel: 'x (m)', aspect: 0.39,
  });
  drawPlot($('plot-angle'), { series: series('theta', COLORS.ink, 2.5, 180 / Math.PI), ticks, tMax, yLabel: 'angle (deg)', aspect: 0.24, minSpan: 2 });
  drawPlot($('plot-height'), { series: series('y', COLORS.ink, 2.5, 100), ticks, tMax, yLabel: 'height (cm)', aspect: 0.24, minSpan: 1 });
}

function showSwitches(src) {
  const list = $('eq21');
  const eq21 = src.trace.events.filter((e) => e.ratio !== null);
  list.replaceChildren(...eq21.map((e) => {
    const li = document.createElement('li');
    li.textContent = `t = ${e.t.toFixed(3)} s: ${S.core.scene(src.scene).contacts[e.contact]} starts to slide, ratio ${e.ratio.toFixed(4)}`;
    return li;
  }));
  if (eq21.length === 0) {
    const li = document.createElement('li');
    li.textContent = src.trace.events.length
      ? `none yet (${src.trace.events.length} switch${src.trace.events.length === 1 ? '' : 'es'}: ${MODE_NAMES[src.trace.events.at(-1).mode]} last)`
      : 'none yet';
    list.append(li);
  }
  S.shownEvents = src.trace.events.length;
}

// --- replay, map, benchmark ---------------------------------------------------------------------------

let replayRuns = null;

function startReplay(run) {
  pause();
  S.source = replaySource(run);
  S.other = null;
  document.body.classList.remove('comparing');
  S.simTarget = 0;
  clearResult('replay: press Play');
  $('error').textContent = '';
  view.setScene(S.source.scene, S.source.params, S.source.trace.last, S.source.trace.k, S.source.shapes);
  const { reference, comparison } = run.summary;
  $('replay-info').textContent = `${run.name}: ${run.summary.scene}, core ${run.summary.core.implementation} ${run.summary.core.outcome}, `
    + (reference && comparison ? `reference ${reference.outcome}; max |COM| deviation ${comparison.max_com_deviation_m.toExponential(2)} m` : 'no reference');
  $('run-info').textContent = `replay of ${run.name} (host-sim run)`;
  $('replay-leave').hidden = false;
  for (const el of document.querySelectorAll('#params input, #params select, #params button')) el.disabled = true;
  setState('ready');
  render(true);
}

async function loadReplay(name) {
  const run = replayRuns.runs.find((r) => r.name === name);
  if (!run) { showError(`replay ${JSON.stringify(name)}: no such run (${replayRuns.runs.map((r) => r.name).join(', ')})`); return; }
  try {
    startReplay(await loadRun(run, (scene) => S.main.contacts(scene)));
  } catch (e) {
    showError(`replay ${name}: ${e.message}`);
  }
}

function leaveReplay() {
  for (const el of document.querySelectorAll('#params input, #params select, #params button')) el.disabled = false;
  $('replay-leave').hidden = true;
  $('replay-info').textContent = '';
  if (S.scene !== 'meter-stick') $('map-run').disabled = true;
  makeRun();
}

async function computeMap() {
  const src = S.source;
  if (S.scene !== 'meter-stick' || !src || src.kind !== 'live') {
    $('map-status').textContent = 'the map needs valid meter-stick parameters';
    return;
  }
  const parsed = givenFlags();
  if (parsed.message) { showError(parsed.message, parsed.flag); return; }
  $('map-run').disabled = true;
  try {
    await map.compute(S.module, {
      given: parsed.given.filter(([long]) => long !== 'speed' && long !== 'mu-k'),
      muS: src.params.mu_static, precision: src.precision, lcpSize: src.lcpSize,
    });
  } finally {
    $('map-run').disabled = S.scene !== 'meter-stick';
  }
}

function bench() {
  $('bench-run').disabled = true;
  $('bench').textContent = 'running (2 s)...';
  const worker = new Worker(new URL('./map-worker.js', import.meta.url), { type: 'module' });
  worker.onmessage = (event) => {
    const m = event.data;
    worker.terminate();
    $('bench-run').disabled = false;
    if (m.kind !== 'bench') { $('bench').textContent = `benchmark failed: ${m.message}`; return; }
    const browser = (navigator.userAgent.match(/(?:Chrome|Chromium|Firefox|Version)\/[\d.]+/) || ['this browser'])[0];
    $('bench').textContent = `${(m.steps / m.seconds / 1e6).toFixed(2)} M steps/s (f32 6x6, ${m.runs} runs of ${Math.round(m.steps / m.runs)} steps in ${m.seconds.toFixed(2)} s, ${m.outcome}, checksum ${m.checksum}; ${browser})`;
    $('bench').dataset.stepsPerSecond = String(m.steps / m.seconds);
  };
  worker.postMessage({ kind: 'bench', module: S.module, seconds: 2 });
}

// --- start ----------------------------------------------------------------------------------------------

/// Offers the shown run's rows (and run B's) as CSV files.
function downloadCsv() {
  for (const [src, suffix] of [[S.source, ''], [S.other, '-b']]) {
    if (!src || src.kind !== 'live') continue;
    const blob = new Blob([src.trace.csv()], { type: 'text/csv' });
    const a = document.createElement('a');
    a.href = URL.createObjectURL(blob);
    a.download = `${src.scene}${suffix}.csv`;
    document.body.append(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(a.href), 10000);
  }
}

function isTyping(target) {
  return target instanceof HTMLInputElement || target instanceof HTMLSelectElement || target instanceof HTMLTextAreaElement
    || target instanceof HTMLButtonElement || target === $('map') || target.isContentEditable;
}

function wire() {
  $('play').addEventListener('click', () => (S.playing ? pause() : play()));
  $('step').addEventListener('click', stepOnce);
  $('reset').addEventListener('click', () => {
    if (S.source && S.source.kind === 'replay') startReplay(S.source.run); else makeRun();
  });
  $('rate').addEventListener('change', () => {
    S.rate = $('rate').value;
    S.simTarget = S.source ? S.source.trace.time : 0;
    writeUrl();
  });
  $('scene-select').addEventListener('change', async () => {
    const scene = $('scene-select').value;
    // Run B's changes are the last scene's flags.
    S.compare = []; $('compare').value = '';
    try {
      await selectScene(scene);
    } catch (e) {
      $('scene-select').value = S.scene;
      showError(`could not load the core for scene ${scene}: ${e.message}`);
      return;
    }
    makeRun();
  });
  // A scene in three dimensions runs in the module of its precision.
  $('precision').addEventListener('change', async () => { S.core = await coreFor(S.scene); makeRun(); });
  $('lcp-size').addEventListener('change', () => makeRun());
  $('params').addEventListener('submit', (e) => { e.preventDefault(); makeRun(); });
  $('map-run').addEventListener('click', computeMap);
  $('csv').addEventListener('click', downloadCsv);
  $('after').addEventListener('change', () => { S.goOn = $('after').checked; writeUrl(); });
  $('compare').addEventListener('change', async () => {
    const parsed = parseCompare($('compare').value);
    if (parsed.message) { showError(parsed.message); return; }
    S.compare = parsed.pairs;
    S.coreB = S.compare.length ? await coreBFor(S.scene) : null;
    makeRun();
  });
  $('bench-run').addEventListener('click', bench);
  $('replay-load').addEventListener('click', () => loadReplay($('replay-select').value));
  $('replay-leave').addEventListener('click', leaveReplay);
  document.addEventListener('keydown', (e) => {
    if (e.ctrlKey || e.metaKey || e.altKey || isTyping(e.target)) return;
    if (e.key === ' ') { e.preventDefault(); if (S.playing) pause(); else play(); } else if (e.key === '.') stepOnce();
    else if (e.key === 'r') $('reset').click();
  });
  let resizeTimer = 0;
  window.addEventListener('resize', () => {
    clearTimeout(resizeTimer);
    resizeTimer = setTimeout(() => { view.camera = null; render(true); map.draw(); }, 100);
  });
}

/// Reads the URL: the scene, the flags (host-sim's names), precision, LCP size, speed of play.
async function readUrl(q) {
  const scene = q.get('scene') || 'meter-stick';
  const problems = [];
  if (!knownScene(scene)) {
    const names = sceneNames().join(', ');
    problems.push(`scene ${JSON.stringify(scene)}: not a scene (${names})`);
    await selectScene('meter-stick');
  } else {
    await selectScene(scene);
  }
  for (const [key, value] of q) {
    if (PAGE_KEYS.includes(key)) continue;
    if (key.startsWith('b.')) {
      // Run B's flag: one of the scene's.
      const long = key.slice(2);
      if (S.inputs.has(long)) S.compare.push([long, value]);
      else problems.push(`${key}: run B's flags are the scene's (${[...S.inputs.keys()].join(', ')})`);
      continue;
    }
    const input = S.inputs.get(key);
    if (input) { input.value = value; continue; }
    const flag = S.core.desc.flags.find((f) => f.long === key);
    if (flag) {
      const applies = Object.keys(flag.fields).join(', ');
      problems.push(`${key} does not apply to scene ${S.scene} (it is a parameter of ${applies})`);
    } else {
      problems.push(`${key}: not a parameter of the page (the scene flags of host-sim, and ${PAGE_KEYS.join(', ')})`);
    }
  }
  const precision = q.get('precision');
  if (precision !== null) {
    if (['f32', 'f64'].includes(precision)) $('precision').value = precision;
    else problems.push(`precision ${JSON.stringify(precision)}: f32 or f64`);
  }
  const size = q.get('lcp-size');
  if (size !== null) {
    if (['6', '8'].includes(size)) $('lcp-size').value = size;
    else problems.push(`lcp-size ${JSON.stringify(size)}: 6 or 8`);
  }
  if (S.compare.length) {
    S.coreB = await coreBFor(S.scene);
    $('compare').value = S.compare.map(([long, value]) => `${long}=${value}`).join(' ');
  }
  const after = q.get('after');
  if (after !== null) {
    if (['0', '1'].includes(after)) { S.goOn = after === '1'; $('after').checked = S.goOn; } else problems.push(`after ${JSON.stringify(after)}: 0 or 1`);
  }
  const rate = q.get('rate');
  if (rate !== null) {
    if ([...$('rate').options].some((o) => o.value === rate)) { S.rate = rate; $('rate').value = rate; } else {
      problems.push(`rate ${JSON.stringify(rate)}: one of ${[...$('rate').options].map((o) => o.value).join(', ')}`);
    }
  }
  return problems;
}

async function main() {
  setState('loading');
  wire();
  try {
    S.module = await compileCore();
    S.core = await instantiateCore(S.module);
    S.main = S.core;
  } catch (e) {
    showError(`could not load the core: ${e.message}`);
    setState('error');
    return;
  }
  $('version').textContent = `meterstick-web ${S.core.desc.version}.`;
  try {
    const response = await fetch(new URL('./pkg/intros.json', import.meta.url));
    if (response.ok) S.intros = await response.json();
  } catch (e) {
    S.intros = null; // the headings fall back to the scenes' titles; no scene in three dimensions
  }
  $('scene-select').replaceChildren(...sceneNames().map((name) => {
    const option = new Option(name, name);
    option.title = S.main.scene(name) ? S.main.scene(name).title : S.intros[name].heading;
    return option;
  }));
  const q = new URLSearchParams(location.search);
  let problems;
  try {
    problems = await readUrl(q);
    // The query's precision may name another module (a scene in three dimensions).
    S.core = await coreFor(S.scene);
  } catch (e) {
    showError(`could not load the core for scene ${q.get('scene')}: ${e.message}`);
    setState('error');
    return;
  }
  const ok = makeRun();
  if (problems.length) {
    // An unusable query is refused as a whole, like a command line with a bad flag.
    pause();
    S.source = null;
    drawEmpty();
    clearResult('not run: invalid parameters');
    showError(problems.join('; '));
    setState('error');
  }
  map.draw();
  replayRuns = await listRuns();
  if (replayRuns) {
    $('replay-box').hidden = false;
    $('no-replay').hidden = true;
    $('replay-select').replaceChildren(...replayRuns.runs.map((r) => new Option(r.name, r.name)));
  }
  if (q.get('replay') !== null) {
    if (!replayRuns) showError('replay: this server has no runs to replay (host-sim serve --replay DIR)');
    else {
      $('replay-select').value = q.get('replay');
      await loadReplay(q.get('replay'));
    }
  }
  if (q.get('bench') === '1') bench();
  if (q.get('map') === '1' && ok && !problems.length) computeMap();
  if (q.get('autorun') === '1' && S.source && !problems.length) play();
}

window.meterstick = testHooks(S, () => view, viewB, map);

main();
