//! A run's trajectory as CSV.

use super::BodiesRow;

/// Writes a run's trajectory: `t`, then each body's `x, y, theta, vx, vy, omega` (body 0 the
/// lowest), then each pair's interface force on its upper body `fx, fy` and its four candidates'
/// normal and friction forces (N; [`super::BodiesRow::corner_loads`]): `pair{p}_fx, pair{p}_fy`,
/// `pair{p}_c{c}_normal, pair{p}_c{c}_friction` for `c` 0..3. A body in three dimensions: `x, y,
/// z`, its orientation `qw, qx, qy, qz` and as Euler angles `roll, pitch, yaw` (z-y-x, degrees),
/// `vx, vy, vz, wx, wy, wz`; then each contact's `c{i}_mode` (0 separated, 1 sticking, 2 sliding),
/// point `c{i}_x, c{i}_y, c{i}_z`, normal impulse `c{i}_normal` and friction impulse
/// `c{i}_friction_x, _y, _z` (N s), as many as the row with the most has (a row with fewer leaves
/// the rest empty: the stack in three dimensions' contacts come and go). Rows without interface forces (a rig's telemetry,
/// `host-sim monitor --scene stack`) have no pair columns.
pub(crate) fn write_trajectory(rows: &[BodiesRow], path: &std::path::Path) -> anyhow::Result<()> {
    use std::fmt::Write as _;
    let first = rows.first();
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
    let spatial = first.map_or(0, |r| r.spatial.len());
    // The most contacts a row has: a scene whose contacts come and go (the stack in three
    // dimensions) leaves the cells of the slots a row does not fill empty.
    let contacts = rows.iter().map(|r| r.contacts.len()).max().unwrap_or(0);
    for b in 0..spatial {
        for name in SPATIAL_COLUMNS {
            let _ = write!(header, ",{name}{b}");
        }
    }
    for c in 0..contacts {
        for name in ["mode", "x", "y", "z", "normal", "friction_x", "friction_y", "friction_z"] {
            let _ = write!(header, ",c{c}_{name}");
        }
    }
    let lines = rows.iter().map(|r| {
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
        for b in &r.spatial {
            let euler = euler_deg(b.orientation);
            for x in
                b.position.iter().chain(&b.orientation).chain(&euler).chain(&b.velocity).chain(&b.angular)
            {
                let _ = write!(line, ",{x}");
            }
        }
        for c in &r.contacts {
            let _ = write!(line, ",{}", c.mode);
            for x in c.point.iter().chain([&c.normal_impulse]).chain(&c.friction_impulse) {
                let _ = write!(line, ",{x}");
            }
        }
        for _ in r.contacts.len()..contacts {
            line.push_str(",,,,,,,,");
        }
        line
    });
    crate::output::write_lines(path, &header, lines)
}

/// A body in three dimensions' columns, each followed by the body's number.
const SPATIAL_COLUMNS: [&str; 16] =
    ["x", "y", "z", "qw", "qx", "qy", "qz", "roll", "pitch", "yaw", "vx", "vy", "vz", "wx", "wy", "wz"];

/// The unit quaternion `[w, x, y, z]` as z-y-x Euler angles `[roll, pitch, yaw]` (degrees): the
/// body turned by yaw about `z`, then pitch about its `y`, then roll about its `x`.
#[must_use]
pub fn euler_deg([w, x, y, z]: [f64; 4]) -> [f64; 3] {
    let roll = (2.0 * (w * x + y * z)).atan2(1.0 - 2.0 * (x * x + y * y));
    let pitch = (2.0 * (w * y - z * x)).clamp(-1.0, 1.0).asin();
    let yaw = (2.0 * (w * z + x * y)).atan2(1.0 - 2.0 * (y * y + z * z));
    [roll, pitch, yaw].map(f64::to_degrees)
}

#[cfg(test)]
mod tests {
    use super::euler_deg;

    /// A turn about each axis alone reads as that angle alone (a quarter turn; pitch half of one,
    /// a quarter being the angles' singular point).
    #[test]
    fn turns_about_one_axis_read_as_their_angle() {
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let (c, s) = (22.5_f64.to_radians().cos(), 22.5_f64.to_radians().sin());
        for (q, want) in [
            ([h, h, 0.0, 0.0], [90.0, 0.0, 0.0]),
            ([c, 0.0, s, 0.0], [0.0, 45.0, 0.0]),
            ([h, 0.0, 0.0, h], [0.0, 0.0, 90.0]),
            ([1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0]),
        ] {
            let got = euler_deg(q);
            for (g, w) in got.iter().zip(want) {
                assert!((g - w).abs() < 1e-9, "{q:?}: {got:?}, want {want:?}");
            }
        }
    }
}
