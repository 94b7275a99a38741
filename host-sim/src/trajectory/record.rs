//! Which rows a run keeps ([`Record`], [`Recorder`]), and the most steps `host-sim run` records.

use super::Row;
use crate::scenes::SceneParams;

/// Which rows a run keeps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Record {
    /// The initial state and every step.
    All,
    /// Rows at times `k dt` only (`k = 0, 1, ...`), the position linearly interpolated between
    /// the steps around each (for comparing runs with different `h` without keeping every step).
    Grid(f64),
    /// No rows.
    Nothing,
}

/// Keeps the rows a [`Record`] asks for.
#[derive(Debug)]
pub struct Recorder<const K: usize = 2> {
    mode: Record,
    rows: Vec<Row<K>>,
    last: Option<Row<K>>,
    next: u64,
}

impl<const K: usize> Recorder<K> {
    /// An empty recorder.
    #[must_use]
    pub fn new(mode: Record) -> Self {
        Self { mode, rows: Vec::new(), last: None, next: 0 }
    }

    /// Offers the row of the initial state or of the next step.
    pub fn push(&mut self, row: Row<K>) {
        match self.mode {
            Record::All => self.rows.push(row),
            Record::Nothing => {}
            Record::Grid(dt) => {
                let prev = self.last.unwrap_or(row);
                // A grid time between two rows is interpolated between them (an f32 run's
                // times `k h` carry rounding; a grid time just past this row waits for the next).
                while (self.next as f64) * dt <= row.t + 1e-9 * dt {
                    let tk = self.next as f64 * dt;
                    let a =
                        if row.t > prev.t { ((tk - prev.t) / (row.t - prev.t)).clamp(0.0, 1.0) } else { 1.0 };
                    let mut q = row.q;
                    for d in 0..3 {
                        q[d] = prev.q[d] + a * (row.q[d] - prev.q[d]);
                    }
                    self.rows.push(Row { t: tk, q, ..row });
                    self.next += 1;
                }
                self.last = Some(row);
            }
        }
    }

    /// The rows kept.
    #[must_use]
    pub fn finish(self) -> Vec<Row<K>> {
        self.rows
    }
}

/// The most steps `host-sim run` records: 2 x 10^6, for one run and for all the runs of a list
/// together ([`check_total_recorded_steps`]). It keeps every step of the core and of the
/// reference of every run in memory until the last run has finished (about 700 bytes a step in
/// all) and writes them as CSV, so a run at the general cap ([`crate::scenes::MAX_STEPS`], 10^8)
/// would need about 70 GB; `host-sim scene` runs up to that cap without recording.
pub const MAX_RECORDED_STEPS: f64 = 2e6;

/// Refuses a run that would record more than [`MAX_RECORDED_STEPS`] steps, in the user's words.
///
/// # Errors
/// The step count `--h` and `--duration` imply is above the cap.
pub fn check_recorded_steps(spec: &SceneParams) -> anyhow::Result<()> {
    let steps = (spec.max_time() / spec.step()).ceil();
    anyhow::ensure!(
        steps <= MAX_RECORDED_STEPS,
        "--h {} s and --duration {} s imply {steps:.3e} steps; host-sim run records every step (about \
         700 bytes each) and takes at most {MAX_RECORDED_STEPS:e} (raise --h or lower --duration; \
         host-sim scene runs up to {:e} steps without recording)",
        crate::scenes::short_number(spec.step()),
        crate::scenes::short_number(spec.max_time()),
        crate::scenes::MAX_STEPS
    );
    Ok(())
}

/// Refuses a list of runs that would record more than [`MAX_RECORDED_STEPS`] steps in all (each
/// run within the cap, [`check_recorded_steps`], but every run's steps are kept until the last
/// has finished, so memory grows with the number of values), in the user's words: `listed` is
/// the list as given (`--angle 10,11,12,13 deg`), `flag` its flag (`angle`).
///
/// # Errors
/// The steps of all the runs together are above the cap.
pub fn check_total_recorded_steps(
    specs: &[(String, SceneParams)],
    listed: &str,
    flag: &str,
) -> anyhow::Result<()> {
    let total: f64 = specs.iter().map(|(_, s)| (s.max_time() / s.step()).ceil()).sum();
    if total <= MAX_RECORDED_STEPS {
        return Ok(());
    }
    let same =
        |f: fn(&SceneParams) -> f64| specs.iter().all(|(_, s)| f(s).to_bits() == f(&specs[0].1).to_bits());
    let runs = match specs.first() {
        Some((_, first)) if same(SceneParams::step) && same(SceneParams::max_time) => format!(
            "runs of --h {} s and --duration {} s",
            crate::scenes::short_number(first.step()),
            crate::scenes::short_number(first.max_time())
        ),
        _ => "runs whose --h and --duration".to_string(),
    };
    anyhow::bail!(
        "{listed}: {} {runs} imply {total:.3e} steps in all; host-sim run keeps every step of every run \
         until the last has finished (about 700 bytes each) and takes at most {MAX_RECORDED_STEPS:e} in all \
         (give fewer values of --{flag}, raise --h or lower --duration, or run the values in separate \
         invocations)",
        specs.len()
    )
}
