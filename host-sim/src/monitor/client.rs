//! The rig's parameters over the link: read back, and set.

use anyhow::bail;
use meterstick_core::scene::MeterStickParams;
use meterstick_link::host::{Link, REPLY_TIMEOUT};
use meterstick_link::{Command, ParamId, RejectReason, Report};

/// The rig's meter-stick parameter set, read back with `GetParam` (every [`ParamId`] the meter
/// stick has).
///
/// # Errors
/// A missing reply, or a name the core does not know.
pub fn read_params(link: &mut Link) -> anyhow::Result<MeterStickParams<f32>> {
    let mut p = MeterStickParams::<f32>::default();
    // The meter stick's parameters (the link also names the stack's).
    for id in ParamId::ALL.into_iter().filter(|id| MeterStickParams::<f32>::NAMES.contains(&id.name())) {
        match link.request(&Command::GetParam { id }, REPLY_TIMEOUT)? {
            Report::Param { value, .. } => {
                if !p.set(id.name(), value) {
                    bail!("the rig's parameter {} is not a meter-stick parameter", id.name());
                }
            }
            other => bail!("GetParam {}: unexpected reply {other:?}", id.name()),
        }
    }
    Ok(p)
}

/// A parameter the rig refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Refused {
    /// Which.
    pub id: ParamId,
    /// Why (the core's validation).
    pub reason: RejectReason,
}

/// Sets `values` on the rig in order; a value refused because of another one not yet set
/// (finger outside the rod, crossed fingers, mu_k above mu_s) is tried again after the others.
/// Returns the refusals that remain.
///
/// # Errors
/// A missing reply.
pub fn apply_params(link: &mut Link, values: &[(ParamId, f32)]) -> anyhow::Result<Vec<Refused>> {
    let mut todo: Vec<(ParamId, f32)> = values.to_vec();
    let mut refused = Vec::new();
    for _pass in 0..3 {
        refused.clear();
        let mut again = Vec::new();
        for &(id, value) in &todo {
            match link.request(&Command::SetParam { id, value }, REPLY_TIMEOUT)? {
                Report::Ack { .. } => {}
                Report::Rejected { reason, .. } => {
                    refused.push(Refused { id, reason });
                    again.push((id, value));
                }
                other => bail!("SetParam {}: unexpected reply {other:?}", id.name()),
            }
        }
        if again.is_empty() || again.len() == todo.len() {
            break;
        }
        todo = again;
    }
    Ok(refused)
}
