//! Writes each scene's heading, introduction (the catalogue's `INTRODUCTIONS`) and page module
//! (`config::Module::of`) as JSON, `{"meter-stick": {"heading": ..., "intro": ..., "module":
//! "meterstick_web.wasm"}, ...}`: `scripts/lib.sh` `build_web` puts it in
//! `web/page/pkg/intros.json`, which the page reads (the wasm modules, within their size budget,
//! do not carry the text; the planar modules do not name the scenes in three dimensions, which
//! the page learns from here).
#![allow(missing_docs)]

fn main() {
    let intros: serde_json::Map<String, serde_json::Value> = meterstick_catalogue::INTRODUCTIONS
        .iter()
        .map(|i| {
            let module = meterstick_web::config::Module::of(i.kind).file();
            (
                i.kind.name().to_owned(),
                serde_json::json!({ "heading": i.heading, "intro": i.intro, "module": module }),
            )
        })
        .collect();
    println!("{}", serde_json::Value::Object(intros));
}
