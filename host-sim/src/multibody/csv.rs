//! A run's trajectory as CSV.

use super::BodiesRun;

/// Writes a run's trajectory: `t`, then each body's `x, y, theta, vx, vy, omega` (body 0 the
/// lowest).
pub(super) fn write_trajectory(run: &BodiesRun, path: &std::path::Path) -> anyhow::Result<()> {
    use std::fmt::Write as _;
    let bodies = run.rows.first().map_or(0, |r| r.q.len());
    let mut header = String::from("t");
    for b in 0..bodies {
        for name in ["x", "y", "theta", "vx", "vy", "omega"] {
            let _ = write!(header, ",{name}{b}");
        }
    }
    let lines = run.rows.iter().map(|r| {
        let mut line = format!("{}", r.t);
        for (q, v) in r.q.iter().zip(&r.v) {
            for x in q.iter().chain(v) {
                let _ = write!(line, ",{x}");
            }
        }
        line
    });
    crate::output::write_lines(path, &header, lines)
}
