//! The trajectory CSV (`core.csv`, `reference.csv`) and the events CSV (`core-events.csv`, ...).

use std::path::Path;

use super::Trajectory;
use crate::output::write_lines;

/// The trajectory CSV's header for `k` contacts: `t,x,y,theta,vx,vy,omega`, then each contact's
/// `support<i>_x,support<i>_y`, `mode<i>`, `pn<i>`, `pf<i>`, `along<i>` (each group over the
/// contacts; two contacts: `...,support2_y,mode1,mode2,pn1,pn2,pf1,pf2,along1,along2`).
#[must_use]
pub fn csv_header(k: usize) -> String {
    use std::fmt::Write as _;
    let mut h = String::from("t,x,y,theta,vx,vy,omega");
    for i in 1..=k {
        let _ = write!(h, ",support{i}_x,support{i}_y");
    }
    for group in ["mode", "pn", "pf", "along"] {
        for i in 1..=k {
            let _ = write!(h, ",{group}{i}");
        }
    }
    h
}

/// Writes the trajectory CSV ([`csv_header`]; SI units, impulses in N s).
///
/// # Errors
/// I/O, naming the file.
pub fn write_csv<const K: usize>(traj: &Trajectory<K>, path: &Path) -> anyhow::Result<()> {
    use std::fmt::Write as _;
    let lines = traj.rows.iter().map(|r| {
        let mut line = format!("{},{},{},{},{},{},{}", r.t, r.q[0], r.q[1], r.q[2], r.v[0], r.v[1], r.v[2]);
        for s in &r.supports {
            let _ = write!(line, ",{},{}", s[0], s[1]);
        }
        for c in &r.contacts {
            let _ = write!(line, ",{}", c.mode.name());
        }
        for c in &r.contacts {
            let _ = write!(line, ",{}", c.normal_impulse);
        }
        for c in &r.contacts {
            let _ = write!(line, ",{}", c.friction_impulse);
        }
        for c in &r.contacts {
            let _ = write!(line, ",{}", c.along);
        }
        line
    });
    write_lines(path, &csv_header(K), lines)
}

/// Writes the events CSV: `t,kind,contact,mode,along1,...,along<K>`, one row per mode switch
/// (`kind` `switch`, contact 1 to K) and, for the meter stick, one for the fingers' stop (`kind`
/// `stop`, contact and mode empty), in time order.
///
/// # Errors
/// I/O, naming the file.
pub fn write_events_csv<const K: usize>(traj: &Trajectory<K>, path: &Path) -> anyhow::Result<()> {
    let mut lines: Vec<(f64, String)> = traj
        .events
        .iter()
        .map(|e| {
            let along: Vec<String> = e.along.iter().map(f64::to_string).collect();
            (e.t, format!("{},switch,{},{},{}", e.t, e.contact + 1, e.mode.name(), along.join(",")))
        })
        .collect();
    if let Some(m) = traj.measured.meeting {
        // After the switches of the stopping step: they were found on it.
        let at = lines.partition_point(|(t, _)| *t <= m.time_s);
        lines.insert(at, (m.time_s, format!("{},stop,,{}", m.time_s, ",".repeat(K))));
    }
    let header: Vec<String> = (1..=K).map(|i| format!("along{i}")).collect();
    write_lines(path, &format!("t,kind,contact,mode,{}", header.join(",")), lines.into_iter().map(|(_, l)| l))
}

#[cfg(test)]
mod tests {
    use super::csv_header;

    /// Two contacts give the columns `core.csv` always had (`docs/host-sim.md`, "The main job").
    #[test]
    fn the_header_of_two_contacts_is_the_old_one() {
        assert_eq!(
            csv_header(2),
            "t,x,y,theta,vx,vy,omega,support1_x,support1_y,support2_x,support2_y,\
             mode1,mode2,pn1,pn2,pf1,pf2,along1,along2"
        );
        assert!(csv_header(3).ends_with(
            "support3_x,support3_y,mode1,mode2,mode3,pn1,pn2,pn3,pf1,pf2,pf3,along1,along2,along3"
        ));
    }
}
