//! The rig's run against the host's core f32 6x6 run of the same parameters.

use serde::Serialize;

use super::Recording;
use crate::scenes::{LcpLayout, Precision, SceneParams};
use crate::trajectory::{Record, Trajectory, check_recorded_steps, run_core};

/// The rig's run against the host's core f32 6x6 run of the same parameters.
#[derive(Debug, Clone, Serialize)]
#[allow(clippy::struct_excessive_bools)] // one verdict per property compared
pub struct RigComparison {
    /// Same outcome.
    pub same_outcome: bool,
    /// Same number of steps.
    pub same_steps: bool,
    /// Same trajectory checksum (bit-identical states at every step).
    pub same_checksum: bool,
    /// Same switch events: count, contact, mode and time (bit-identical f32).
    pub same_events: bool,
    /// The rig's checksum.
    pub rig_checksum: String,
    /// The host's.
    pub host_checksum: String,
    /// Telemetry rows whose state differs from the host's at the same step (must be 0).
    pub rows_differing: usize,
}

impl RigComparison {
    /// Everything agrees.
    #[must_use]
    pub const fn identical(&self) -> bool {
        self.same_outcome
            && self.same_steps
            && self.same_checksum
            && self.same_events
            && self.rows_differing == 0
    }
}

/// Runs the recorded parameters in the host's core (f32, 6x6, every step) and compares.
///
/// # Errors
/// The parameters are invalid on the host.
pub fn compare(rec: &Recording) -> anyhow::Result<(Trajectory, RigComparison)> {
    let spec = SceneParams::MeterStick(rec.params.cast::<f64>());
    // The rig's parameters, not the user's: bounded like `host-sim run`'s before anything runs.
    check_recorded_steps(&spec).map_err(|e| {
        anyhow::anyhow!("the rig's step and max_time: {e}; --no-compare records the rig's run alone")
    })?;
    let host = run_core::<2>(&spec, Precision::F32, LcpLayout::Reduced, Record::All)?;
    let rig = &rec.trajectory;
    let same_events = rig.events.len() == host.events.len()
        && rig
            .events
            .iter()
            .zip(&host.events)
            .all(|(a, b)| a.t.to_bits() == b.t.to_bits() && a.contact == b.contact && a.mode == b.mode);
    // Row k of the host is step k (row 0: the start); the rig's rows carry their time, n h.
    let h = f64::from(rec.params.step);
    let rows_differing = rig
        .rows
        .iter()
        .filter(|r| {
            let k = (r.t / h).round() as usize;
            let bits = |a: [f64; 3]| a.map(f64::to_bits);
            host.rows.get(k).is_none_or(|hr| bits(hr.q) != bits(r.q) || bits(hr.v) != bits(r.v))
        })
        .count();
    let host_sum = host.checksum.unwrap_or(0);
    let cmp = RigComparison {
        same_outcome: rig.outcome.class == host.outcome.class,
        same_steps: rig.steps == host.steps,
        same_checksum: rec.checksum == host_sum,
        same_events,
        rig_checksum: format!("{:08x}", rec.checksum),
        host_checksum: format!("{host_sum:08x}"),
        rows_differing,
    };
    Ok((host, cmp))
}
