//! What the commands write: their folders ([`create_dir`]), pretty JSON ([`write_json`]), CSV
//! files line by line ([`write_lines`]), a scene's parameters as JSON ([`parameters_json`]) and
//! numbers in tables and text ([`sci`]).

use std::io::Write as _;
use std::path::Path;

use anyhow::Context as _;
use serde::Serialize;

use meterstick_core::scene::SceneParams;

/// `x` in short scientific notation for tables and text (`1.23e-5`; `0` for zero, `n/a` for a
/// quantity that does not exist, NaN or infinite).
#[must_use]
pub fn sci(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else if x.is_finite() {
        format!("{x:.2e}")
    } else {
        "n/a".into()
    }
}

/// The parameters as a JSON map (core field names).
#[must_use]
pub fn parameters_json(spec: &SceneParams) -> serde_json::Map<String, serde_json::Value> {
    spec.fields().map(|(k, v)| (k.to_string(), serde_json::json!(v))).collect()
}

/// Writes pretty JSON.
///
/// # Errors
/// I/O, naming the file.
pub fn write_json<T: Serialize + ?Sized>(path: &Path, v: &T) -> anyhow::Result<()> {
    let text = serde_json::to_string_pretty(v).context("serialising JSON")? + "\n";
    std::fs::write(path, text).with_context(|| format!("writing {}", path.display()))
}

/// Creates the folder `dir` (and its parents).
///
/// # Errors
/// I/O, naming the folder.
pub fn create_dir(dir: &Path) -> anyhow::Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))
}

/// Writes a CSV file: the header line, then one line per item.
///
/// # Errors
/// I/O, naming the file.
pub fn write_lines<I: IntoIterator<Item = String>>(
    path: &Path,
    header: &str,
    lines: I,
) -> anyhow::Result<()> {
    let mut w = std::io::BufWriter::new(
        std::fs::File::create(path).with_context(|| format!("creating {}", path.display()))?,
    );
    let write = || -> std::io::Result<()> {
        writeln!(w, "{header}")?;
        for line in lines {
            writeln!(w, "{line}")?;
        }
        w.flush()
    };
    write().with_context(|| format!("writing {}", path.display()))
}
