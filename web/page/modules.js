// Which wasm module runs a scene, and the cores made from them (one per module, and a second
// for run B): the first module (meterstick_web.wasm) runs the two-contact scenes; another scene of
// a module it names runs in the module of its contacts; a scene it does not name (one in three
// dimensions) in the module pkg/intros.json names for the run's precision (`module`, `module_f64`:
// web/examples/intros.rs, config::Module::file_for; one module a precision, for their size).

import { compileCore, instantiateCore, moduleFileUrl, moduleUrl } from './core.js';

/// The page's modules over its state `S` (S.main, S.module, S.cores, S.coresB, S.intros), for runs
/// in the precision `precision()` gives ('f32' or 'f64').
export function pageModules(S, precision) {
  /// The module that runs `scene`: the first module, the module of the scene's contacts, or, for a
  /// scene the first module does not name (one in three dimensions), the one pkg/intros.json names
  /// for the precision.
  function moduleOf(scene) {
    if (!S.main.scene(scene)) {
      const intro = S.intros && S.intros[scene];
      const file = intro ? (precision() === 'f64' ? intro.module_f64 : intro.module) : null;
      return { key: file, url: file ? moduleFileUrl(file) : null, main: false };
    }
    const k = S.main.contacts(scene);
    return { key: k, url: moduleUrl(k), main: S.main.desc.holds.includes(k) };
  }

  /// `true` for a scene some module runs.
  function knownScene(scene) {
    return Boolean(S.main.scene(scene) || moduleOf(scene).url);
  }

  /// The core that runs `scene`: the first module, or the module of `moduleOf` (fetched and
  /// compiled once).
  function coreFor(scene) {
    const m = moduleOf(scene);
    if (m.main) return Promise.resolve(S.main);
    if (!S.cores.has(m.key)) {
      const loading = compileCore(m.url).then(instantiateCore);
      loading.catch(() => S.cores.delete(m.key));
      S.cores.set(m.key, loading);
    }
    return S.cores.get(m.key);
  }

  /// A second instance of the module that runs `scene`, for run B (made once per module).
  function coreBFor(scene) {
    const m = moduleOf(scene);
    if (!S.coresB.has(m.key)) {
      const module = m.main ? Promise.resolve(S.module) : compileCore(m.url);
      const loading = module.then(instantiateCore);
      loading.catch(() => S.coresB.delete(m.key));
      S.coresB.set(m.key, loading);
    }
    return S.coresB.get(m.key);
  }

  /// Every scene's name: the first module's, then those of the other modules it does not name (from
  /// pkg/intros.json: the scenes in three dimensions).
  function sceneNames() {
    const names = S.main.desc.scenes.map((s) => s.name);
    const others = Object.keys(S.intros || {}).filter((name) => !names.includes(name) && moduleOf(name).url);
    return [...names, ...others];
  }

  return { coreFor, coreBFor, knownScene, sceneNames };
}
