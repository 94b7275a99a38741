//! A scene run to its outcome in the implementation chosen: the core ([`super::core_run`]) or the
//! independent reference ([`super::reference_run`]), with Ctrl-C checked before and after.

use indicatif::ProgressBar;

use super::core_run::core_run;
use super::reference_run::run_reference;
use super::{Record, Trajectory};
use crate::progress;
use crate::scenes::{Implementation, SceneParams};

/// Runs `spec` (a scene with two contacts) in `implementation` to its outcome and records it.
///
/// # Errors
/// Invalid parameters, or a scene without two contacts ([`run_k`]).
pub fn run(spec: &SceneParams, implementation: Implementation, record: Record) -> anyhow::Result<Trajectory> {
    run_inner(spec, implementation, record, None)
}

/// Calls `$body` with the const `$k` set to the number of contacts of scene `$kind` (1, 2 or 3):
/// the commands that record a scene are generic over its contacts.
#[macro_export]
macro_rules! with_contacts {
    ($kind:expr, $k:ident => $body:expr) => {
        match $kind.contacts() {
            1 => {
                const $k: usize = 1;
                $body
            }
            3 => {
                const $k: usize = 3;
                $body
            }
            _ => {
                const $k: usize = 2;
                $body
            }
        }
    };
}

/// Runs `spec`, a scene with `K` contacts, in `implementation` to its outcome and records it.
///
/// # Errors
/// Invalid parameters, or a scene with other than `K` contacts.
pub fn run_k<const K: usize>(
    spec: &SceneParams,
    implementation: Implementation,
    record: Record,
) -> anyhow::Result<Trajectory<K>> {
    run_inner(spec, implementation, record, None)
}

/// As [`run`], counting the core's steps on `bar` (the reference's are not counted).
///
/// # Errors
/// As [`run`].
pub fn run_watched<const K: usize>(
    spec: &SceneParams,
    implementation: Implementation,
    record: Record,
    bar: &ProgressBar,
) -> anyhow::Result<Trajectory<K>> {
    run_inner(spec, implementation, record, Some(bar))
}

/// Every run checks for Ctrl-C ([`crate::progress`]) before it starts and every
/// [`progress::CHECK_EVERY_STEPS`] steps; an interrupted run is dropped.
fn run_inner<const K: usize>(
    spec: &SceneParams,
    implementation: Implementation,
    record: Record,
    bar: Option<&ProgressBar>,
) -> anyhow::Result<Trajectory<K>> {
    let contacts = spec.kind().contacts();
    anyhow::ensure!(contacts == K, "scene {} has {contacts} contacts, not {K}", spec.kind());
    progress::check()?;
    let t = match implementation {
        Implementation::Reference => run_reference(spec, record),
        Implementation::Core(precision, layout) => core_run::<K>(spec, precision, layout, record, bar),
    }?;
    progress::check()?;
    Ok(t)
}
