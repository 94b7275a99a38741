//! `host-sim lcp`: one LCP read from a file ([`crate::lcp_io`]), solved, as one JSON object.

use std::path::PathBuf;

use crate::lcp_io;

/// `host-sim lcp` options.
#[derive(Debug, Clone, clap::Args)]
pub struct LcpArgs {
    /// The LCP file.
    pub file: PathBuf,
    /// Scalar precision of the core solver.
    #[arg(long, value_parser = crate::scenes::precision_parser(), default_value = "f64")]
    pub precision: lcp_io::Precision,
}

/// Reads, solves, and returns the JSON line.
///
/// # Errors
/// An unreadable, oversized or malformed file, or `n` outside `1..=16`.
pub fn run(args: &LcpArgs) -> anyhow::Result<String> {
    let data = lcp_io::read_file(&args.file)?;
    let report = lcp_io::solve(&data, args.precision)?;
    Ok(format!("{}\n", serde_json::to_string(&report)?))
}
