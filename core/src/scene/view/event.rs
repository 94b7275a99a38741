//! [`EventView`]: a switch event, one contact's change of mode.

use crate::planar::ContactMode;

/// A contact's mode changed after a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EventView<T> {
    /// Time at the end of that step (s).
    pub time: T,
    /// The contact ([`super::SceneView::contact`]'s index).
    pub contact: usize,
    /// Its new mode.
    pub mode: ContactMode,
}
