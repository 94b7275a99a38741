//! A scene run to its outcome in the implementation chosen: the core ([`super::core_run`]) or the
//! independent reference ([`super::reference_run`]), with Ctrl-C checked before and after.

use indicatif::ProgressBar;

use super::core_run::core_run;
use super::reference_run::run_reference;
use super::{Record, Trajectory};
use crate::progress;
use crate::scenes::{Implementation, SceneKind, SceneParams};

/// Runs `spec` (a scene with two contacts) in `implementation` to its outcome and records it.
///
/// # Errors
/// Invalid parameters, or a scene without two contacts ([`run_k`]).
pub fn run(spec: &SceneParams, implementation: Implementation, record: Record) -> anyhow::Result<Trajectory> {
    run_inner(spec, implementation, record, None)
}

/// Calls `$body` with the const `$k` set to the number of contacts of scene `$kind` (1, 2 or 3):
/// the commands that record a scene of one body are generic over its contacts. Any other count (a
/// scene of several bodies has none, [`SceneKind::contacts`] 0: the commands run those through
/// [`crate::bodies`] before they get here) returns [`UnrecordedContacts`] from the enclosing
/// function, whose error type takes an `anyhow::Error`.
///
/// [`SceneKind::contacts`]: meterstick_core::scene::SceneKind::contacts
#[macro_export]
macro_rules! with_contacts {
    ($kind:expr, $k:ident => $body:expr) => {{
        let kind = $kind;
        match kind.contacts() {
            1 => {
                const $k: usize = 1;
                $body
            }
            2 => {
                const $k: usize = 2;
                $body
            }
            3 => {
                const $k: usize = 3;
                $body
            }
            contacts => {
                return Err($crate::trajectory::UnrecordedContacts { kind, contacts }.into());
            }
        }
    }};
}

/// A scene whose number of contacts no recording of one body is compiled for ([`with_contacts!`]):
/// 1, 2 and 3 are.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct UnrecordedContacts {
    /// The scene.
    pub kind: SceneKind,
    /// Its [`SceneKind::contacts`](meterstick_core::scene::SceneKind::contacts).
    pub contacts: usize,
}

impl std::fmt::Display for UnrecordedContacts {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let Self { kind, contacts } = self;
        write!(f, "scene {kind} has {contacts} contacts: a run of one body records 1, 2 or 3")
    }
}

impl std::error::Error for UnrecordedContacts {}

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

#[cfg(test)]
mod tests {
    use super::*;

    /// The contacts of a scene through [`with_contacts!`], or its error.
    fn contacts_of(kind: SceneKind) -> anyhow::Result<usize> {
        Ok(crate::with_contacts!(kind, K => K))
    }

    /// A scene of 1, 2 or 3 contacts reaches its own count; any other count (a scene of several
    /// bodies has 0) is the typed error, never the two-contact branch.
    #[test]
    fn with_contacts_matches_the_counts_that_exist() {
        for kind in SceneKind::ALL {
            let result = contacts_of(kind);
            match kind.contacts() {
                contacts @ 1..=3 => assert_eq!(result.ok(), Some(contacts), "{kind}"),
                contacts => {
                    let error = result.err();
                    assert_eq!(
                        error.as_ref().and_then(anyhow::Error::downcast_ref::<UnrecordedContacts>),
                        Some(&UnrecordedContacts { kind, contacts }),
                        "{kind}"
                    );
                }
            }
        }
    }
}
