//! Runs compared: the eq. 21 switches of a meter-stick run, and the deviation between two runs.

use meterstick_core::planar::ContactMode;
use serde::Serialize;

use super::Trajectory;

/// One eq. 21 switch: a sticking finger starts to slide while the other slides.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Switch {
    /// Time (s).
    pub t: f64,
    /// The finger that starts to slide (1 or 2).
    pub finger: usize,
    /// Its distance from the centre of mass (m).
    pub x_start: f64,
    /// The other (sliding) finger's distance (m).
    pub x_stop: f64,
    /// `x_stop / x_start`, to compare with `mu_k / mu_s` (eq. 21).
    pub ratio: f64,
}

/// The eq. 21 switches of a run: a contact that was sticking starts to slide while the other was
/// sliding before that step (modes before a step: the run's initial modes, then its events), and
/// strictly before the fingers stopped: a change at or after the stop is caused by the stop (the
/// moving finger halts under a rod that slides on), not by eq. 21's force balance (at 0.01 m/s
/// such a change had "ratio" 1.30 and dominated the summary's worst error). The stop is an event of
/// its own kind in the events CSV.
#[must_use]
pub fn switches<const K: usize>(run: &Trajectory<K>) -> Vec<Switch> {
    if K != 2 {
        return Vec::new(); // eq. 21 is a relation between two fingers
    }
    let stop = run.measured.meeting.map(|m| m.time_s);
    let mut mode = run.initial_modes;
    let mut before = mode;
    let mut step_time = None;
    let mut out = Vec::new();
    for e in &run.events {
        if step_time != Some(e.t.to_bits()) {
            step_time = Some(e.t.to_bits());
            before = mode;
        }
        let i = e.contact;
        if i >= K {
            continue;
        }
        let before_stop = stop.is_none_or(|s| e.t < s);
        if before_stop
            && before[i] == ContactMode::Sticking
            && e.mode.is_sliding()
            && before[1 - i].is_sliding()
        {
            out.push(Switch {
                t: e.t,
                finger: i + 1,
                x_start: e.along[i].abs(),
                x_stop: e.along[1 - i].abs(),
                ratio: (e.along[1 - i] / e.along[i]).abs(),
            });
        }
        mode[i] = e.mode;
    }
    out
}

/// Largest `|a - b|` of the centre of mass (m) and of the angle (rad) over the steps both runs
/// have (same `h`: row `k` is time `k h` in both).
#[must_use]
pub fn max_deviation<const K: usize>(a: &Trajectory<K>, b: &Trajectory<K>) -> (f64, f64) {
    let mut com: f64 = 0.0;
    let mut angle: f64 = 0.0;
    for (ra, rb) in a.rows.iter().zip(&b.rows) {
        com = com.max((ra.q[0] - rb.q[0]).hypot(ra.q[1] - rb.q[1]));
        angle = angle.max((ra.q[2] - rb.q[2]).abs());
    }
    (com, angle)
}
