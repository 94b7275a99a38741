//! [`EventLog`]: the switch events of a run ([`SwitchEvent`]), kept in a fixed-size buffer.

use heapless::Vec;

use super::contact::ContactMode;
use super::report::StepReport;
use crate::real::Real;

/// A change of one contact's mode.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SwitchEvent<T, const K: usize> {
    /// Time at the end of the step after which the new mode was found (s).
    pub time: T,
    /// The contact (0-based index).
    pub contact: u8,
    /// Its new mode.
    pub mode: ContactMode,
    /// Every contact's coordinate along it at the start of that step ([`super::ContactFrame::along`]).
    pub along: [T; K],
}

/// Up to `E` switch events; events beyond are counted, not kept.
#[derive(Debug, Clone)]
pub struct EventLog<T, const K: usize, const E: usize> {
    events: Vec<SwitchEvent<T, K>, E>,
    dropped: u32,
}

impl<T: Real, const K: usize, const E: usize> Default for EventLog<T, K, E> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Real, const K: usize, const E: usize> EventLog<T, K, E> {
    /// An empty log.
    #[must_use]
    pub const fn new() -> Self {
        Self { events: Vec::new(), dropped: 0 }
    }

    /// Records the switches of one step.
    pub fn record(&mut self, report: &StepReport<T, K>) {
        // A loop over the contacts' indices, not `report.switches()`: unrolled, it leaves the
        // caller's report in registers; the iterator kept it in memory, and the scene's return of
        // the report then read back at once what had just been stored there (an x86 stall).
        for i in 0..K {
            let contact = &report.contacts[i];
            if !contact.switched() {
                continue;
            }
            let event = SwitchEvent {
                time: report.time,
                contact: i as u8,
                mode: contact.mode,
                along: report.along(),
            };
            if self.events.push(event).is_err() {
                self.dropped = self.dropped.saturating_add(1);
            }
        }
    }

    /// The events kept, in order.
    #[must_use]
    pub fn events(&self) -> &[SwitchEvent<T, K>] {
        &self.events
    }

    /// Events that did not fit.
    #[must_use]
    pub const fn dropped(&self) -> u32 {
        self.dropped
    }
}
