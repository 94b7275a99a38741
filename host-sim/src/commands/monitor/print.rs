//! What `host-sim monitor` shows while it records: a line per event, and a progress line on
//! stderr when it is a terminal.

use std::time::{Duration, Instant};

use meterstick_link::Report;

use crate::monitor::{Observer, mode_of};

/// Prints one line per event and keeps a progress line on stderr (when it is a terminal).
#[derive(Debug)]
pub struct Printer {
    last_progress: Instant,
    terminal: bool,
}

impl Printer {
    /// A printer; `terminal`: stderr is a terminal (the progress line is shown).
    #[must_use]
    pub fn new(terminal: bool) -> Self {
        Self { last_progress: Instant::now(), terminal }
    }

    /// Clears the progress line.
    pub fn clear(&self) {
        if self.terminal {
            eprint!("\r\x1b[K");
        }
    }

    /// Prints a line (over the progress line).
    pub fn line(&self, s: &str) {
        self.clear();
        println!("{s}");
    }
}

impl Observer for Printer {
    fn report(&mut self, r: &Report) {
        match *r {
            Report::Telemetry { step, time, state, contacts, .. }
                if self.terminal && self.last_progress.elapsed() > Duration::from_millis(100) =>
            {
                self.last_progress = Instant::now();
                eprint!(
                    "\r\x1b[Kt = {time:8.3} s  step {step:7}  x = {:+.4} m  theta = {:+.4} rad  fingers {} / {}",
                    state[0],
                    state[2],
                    mode_of(contacts[0].mode).name(),
                    mode_of(contacts[1].mode).name()
                );
            }
            Report::Switch { step, time, contact, mode, along } => self.line(&format!(
                "t = {time:.3} s (step {step}): finger {} -> {}   (fingers at {:+.4} / {:+.4} m from the centre of mass)",
                contact + 1,
                mode_of(mode).name(),
                along[0],
                along[1]
            )),
            Report::Outcome { outcome, time, steps, checksum } => self.line(&format!(
                "outcome {outcome:?} at t = {time:.3} s after {steps} steps, checksum {checksum:08x}"
            )),
            Report::Margin { worst_cycles, period_cycles, overruns, worst_step } if period_cycles > 0 => {
                self.line(&format!(
                    "real time: worst step {worst_cycles} of {period_cycles} cycles ({:.0} %, step {worst_step}), {overruns} overruns",
                    100.0 * f64::from(worst_cycles) / f64::from(period_cycles)
                ));
            }
            Report::InterfaceSwitch { step, time, interface, mode } => {
                self.line(&format!("t = {time:.3} s (step {step}): interface {interface} -> {mode:?}"));
            }
            Report::Body { step, time, body, state, mode }
                if self.terminal && self.last_progress.elapsed() > Duration::from_millis(100) =>
            {
                self.last_progress = Instant::now();
                eprint!(
                    "\r\x1b[Kt = {time:8.3} s  step {step:7}  block {body}: x = {:+.4} m  theta = {:+.4} rad  on {mode:?}",
                    state[0], state[2]
                );
            }
            Report::Error(e) => self.line(&format!("rig error: {e:?}")),
            Report::State(s) => self.line(&format!("rig state: {s:?}")),
            _ => {}
        }
    }
}
