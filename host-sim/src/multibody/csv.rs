//! A run's trajectory as CSV.

use super::BodiesRun;

/// Writes a run's trajectory: `t`, then each body's `x, y, theta, vx, vy, omega` (body 0 the
/// lowest), then each pair's interface force on its upper body `fx, fy` and its four candidates'
/// normal and friction forces (N; [`super::BodiesRow::corner_loads`]): `pair{p}_fx, pair{p}_fy`,
/// `pair{p}_c{c}_normal, pair{p}_c{c}_friction` for `c` 0..3.
pub(super) fn write_trajectory(run: &BodiesRun, path: &std::path::Path) -> anyhow::Result<()> {
    use std::fmt::Write as _;
    let first = run.rows.first();
    let (bodies, pairs) = first.map_or((0, 0), |r| (r.q.len(), r.interface_forces.len()));
    let mut header = String::from("t");
    for b in 0..bodies {
        for name in ["x", "y", "theta", "vx", "vy", "omega"] {
            let _ = write!(header, ",{name}{b}");
        }
    }
    for p in 0..pairs {
        let _ = write!(header, ",pair{p}_fx,pair{p}_fy");
        for c in 0..4 {
            let _ = write!(header, ",pair{p}_c{c}_normal,pair{p}_c{c}_friction");
        }
    }
    let lines = run.rows.iter().map(|r| {
        let mut line = format!("{}", r.t);
        for (q, v) in r.q.iter().zip(&r.v) {
            for x in q.iter().chain(v) {
                let _ = write!(line, ",{x}");
            }
        }
        for (force, loads) in r.interface_forces.iter().zip(&r.corner_loads) {
            for x in force.iter().chain(loads.as_flattened()) {
                let _ = write!(line, ",{x}");
            }
        }
        line
    });
    crate::output::write_lines(path, &header, lines)
}
