//! A run of any scene in the core, of either engine, through the core's one scene interface
//! ([`SceneView`]): stepped to its outcome with Ctrl-C checked, giving what every engine gives
//! ([`ViewRun`]).

use meterstick_core::Real;
use meterstick_core::scene::{MAX_MEASURES, Outcome, SceneView, ViewVisitor};

use crate::progress::{self, CHECK_EVERY_STEPS};
use crate::scenes::{LcpLayout, Precision, SceneParams};
use crate::trajectory::RunOutcome;

/// What a run through [`SceneView`] gives, whichever the engine.
#[derive(Debug, Clone, PartialEq)]
pub struct ViewRun {
    /// How it ended.
    pub outcome: RunOutcome,
    /// Steps taken.
    pub steps: u64,
    /// Simulated time at the end (s).
    pub end_time: f64,
    /// What the scene measures, in f64.
    pub measured: [Option<f64>; MAX_MEASURES],
    /// The trajectory checksum.
    pub checksum: u32,
}

/// Steps a view to its outcome, checking Ctrl-C every [`CHECK_EVERY_STEPS`] steps.
struct ToOutcome;

impl ViewVisitor for ToOutcome {
    type Output = anyhow::Result<ViewRun>;

    fn visit<T: Real>(self, view: &mut dyn SceneView<T>) -> Self::Output {
        let mut steps = 0_u64;
        while view.step() {
            steps += 1;
            if steps.is_multiple_of(CHECK_EVERY_STEPS) {
                progress::check()?;
            }
        }
        Ok(ViewRun {
            outcome: RunOutcome::from(view.outcome().unwrap_or(Outcome::Unfinished)),
            steps,
            end_time: view.time().as_f64(),
            measured: view.measured().map(|m| m.map(Real::as_f64)),
            checksum: view.checksum(),
        })
    }
}

/// Runs `spec`, a scene of either engine, in the core in `precision` (and `layout`, for a scene of
/// one body) to its outcome.
///
/// # Errors
/// Invalid parameters (the core's complaint, in the user's words), or Ctrl-C.
pub fn run_view(spec: &SceneParams, precision: Precision, layout: LcpLayout) -> anyhow::Result<ViewRun> {
    progress::check()?;
    let run = spec
        .build_view::<0, _>(precision, layout, ToOutcome)
        .map_err(|e| anyhow::anyhow!("{}", crate::scenes::flag_error(spec, e)))??;
    progress::check()?;
    Ok(run)
}
