//! The scenes in three dimensions on the page (`meterstick_web_sp.wasm`, the stack's
//! `meterstick_web_st.wasm`, drawn in perspective by
//! `web/page/view3d.js`): the outcome and checksum of `host-sim scene`, the module fetched, and a
//! drawing that shows the body (its pixels read back: not one colour, the body's colour at its
//! centre or, for a body seen edge on or marked there, in a patch of at least 50 pixels).

use serde_json::Value;

use super::Browser;

/// Chromaticity (each channel over their sum) of an RGB triple.
fn chroma(c: &Value) -> [f64; 3] {
    let v: Vec<f64> = (0..3).map(|i| c[i].as_f64().unwrap()).collect();
    let sum = v.iter().sum::<f64>().max(1.0);
    [v[0] / sum, v[1] / sum, v[2] / sum]
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum::<f64>().sqrt()
}

/// Loads `query` (a scene in three dimensions), waits for the outcome and checks it and the
/// checksum against `host-sim scene`'s, the module fetched, and the drawing's pixels.
pub fn check_spatial(b: &Browser, base: &str, name: &str, query: &str) {
    super::check_contract(b, base, name, query);
    // One module a precision (`config::Module::file_for`); the stack in three dimensions its own.
    let family = if name.starts_with("stack-3d") { "st" } else { "sp" };
    let precision = if query.contains("precision=f64") { "64" } else { "" };
    let module = format!("pkg/meterstick_web_{family}{precision}.wasm");
    let fetched = b.js("return performance.getEntriesByType('resource').map((e) => e.name).join(' ')");
    assert!(fetched.as_str().unwrap().contains(&module), "{name}: {module} not fetched: {fetched}");
    // Time, three bodies' 13 numbers, sixteen contacts' 12 (`web/src/spatial.rs`).
    let row = b.js("return window.meterstick.contacts().row");
    assert_eq!(row.as_u64(), Some(1 + 3 * 13 + 16 * 12), "{name}: the row of a scene in three dimensions");
    // The drawing: WebGL2 in headless Chromium (SwiftShader), read back.
    let px = b.js("return window.meterstick.pixels()");
    assert!(px.is_object(), "{name}: no drawing in three dimensions (no WebGL2?): {px}");
    let colours = px["colours"].as_u64().unwrap();
    assert!(colours > 16, "{name}: a blank frame ({colours} colours): {px}");
    let body = chroma(&px["body"]);
    let to_body = distance(body, chroma(&px["bodyColor"]));
    let to_plane = distance(body, chroma(&px["plane"]));
    let to_background = distance(body, chroma(&px["background"]));
    let at_centre = to_body < to_plane && to_body < to_background;
    let body_pixels = px["bodyPixels"].as_u64().unwrap();
    assert!(body_pixels >= 50, "{name}: the body is not drawn ({body_pixels} pixels of its colour): {px}");
    println!(
        "    drawn: {colours} colours, {body_pixels} pixels of the body's colour, at its centre {} ({})",
        px["body"],
        if at_centre { "the body's" } else { "not the body's: a mark or an edge" }
    );
}
