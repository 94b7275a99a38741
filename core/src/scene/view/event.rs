//! [`EventView`]: a switch event, one contact's change of mode.

use crate::planar::{ContactMode, SwitchEvent};
use crate::real::Real;

/// A contact's mode changed after a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EventView<T> {
    /// Time at the end of that step (s).
    pub time: T,
    /// The contact ([`super::SceneView::contact`]'s index).
    pub contact: usize,
    /// Its new mode.
    pub mode: ContactMode,
    /// Its coordinate along its support at the start of that step (m; a scene of one body:
    /// [`crate::planar::ContactFrame::along`]).
    pub along: T,
}

impl<T: Real, const K: usize> From<&SwitchEvent<T, K>> for EventView<T> {
    /// The event of a scene of one body as the view gives it: the switching contact's own `along`.
    fn from(e: &SwitchEvent<T, K>) -> Self {
        let contact = usize::from(e.contact);
        Self {
            time: e.time,
            contact,
            mode: e.mode,
            along: e.along.get(contact).copied().unwrap_or_else(T::zero),
        }
    }
}
