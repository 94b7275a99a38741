//! Writes each scene's heading and introduction (the catalogue's `INTRODUCTIONS`) as JSON,
//! `{"meter-stick": {"heading": ..., "intro": ...}, ...}`: `scripts/lib.sh` `build_web` puts it in
//! `web/page/pkg/intros.json`, which the page reads (the wasm modules, within their size budget,
//! do not carry the text).
#![allow(missing_docs)]

fn main() {
    let intros: serde_json::Map<String, serde_json::Value> = meterstick_catalogue::INTRODUCTIONS
        .iter()
        .map(|i| (i.kind.name().to_owned(), serde_json::json!({ "heading": i.heading, "intro": i.intro })))
        .collect();
    println!("{}", serde_json::Value::Object(intros));
}
