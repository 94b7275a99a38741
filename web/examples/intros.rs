//! Writes each scene's heading, introduction (the catalogue's `INTRODUCTIONS`) and page module
//! for a run in f32 and in f64 (`config::Module::file_for`) as JSON, `{"meter-stick": {"heading":
//! ..., "intro": ..., "module": "meterstick_web.wasm", "module_f64": "meterstick_web.wasm"}, ...}`: `scripts/lib.sh` `build_web` puts it in
//! `web/page/pkg/intros.json`, which the page reads (the wasm modules, within their size budget,
//! do not carry the text; the planar modules do not name the scenes in three dimensions, which
//! the page learns from here).
#![allow(missing_docs)]

use meterstick_web::config::Precision;

fn main() {
    let intros: serde_json::Map<String, serde_json::Value> = meterstick_catalogue::INTRODUCTIONS
        .iter()
        .map(|i| {
            let module = meterstick_web::config::Module::of(i.kind);
            let (f32_file, f64_file) = (module.file_for(Precision::F32), module.file_for(Precision::F64));
            let entry = serde_json::json!({
                "heading": i.heading, "intro": i.intro, "module": f32_file, "module_f64": f64_file
            });
            (i.kind.name().to_owned(), entry)
        })
        .collect();
    println!("{}", serde_json::Value::Object(intros));
}
