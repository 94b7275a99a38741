//! `host-sim scene`: one run of the core scene, summarised on the terminal.
#![allow(clippy::format_push_string)] // a short summary built once per run

use meterstick_core::Real;
use meterstick_core::scene::{ContactMode, Outcome, Scene, SceneParams};

use crate::lcp_io::Precision;

/// Scene options shared by the commands that run scenes (SI units).
#[derive(Debug, Clone, clap::Args)]
pub struct SceneArgs {
    /// Finger 1 speed toward finger 2 (m/s).
    #[arg(long, default_value_t = 0.1)]
    pub speed: f64,
    /// Static friction coefficient.
    #[arg(long, default_value_t = 0.6)]
    pub mu_s: f64,
    /// Kinetic friction coefficient (<= mu_s).
    #[arg(long, default_value_t = 0.4)]
    pub mu_k: f64,
    /// Start of finger 1 (moving), x from the rod's centre of mass (m).
    #[arg(long, default_value_t = -0.35, allow_hyphen_values = true)]
    pub x1: f64,
    /// Start of finger 2 (fixed), x from the rod's centre of mass (m).
    #[arg(long, default_value_t = 0.4, allow_hyphen_values = true)]
    pub x2: f64,
    /// Time step h (s).
    #[arg(long, default_value_t = 1e-3)]
    pub h: f64,
    /// Longest simulated time (s).
    #[arg(long, default_value_t = 30.0)]
    pub duration: f64,
    /// Scalar precision of the core.
    #[arg(long, value_enum, default_value = "f32")]
    pub precision: Precision,
    /// LCP size: 6 (reduced) or 8 (the paper's form).
    #[arg(long, default_value_t = 6, value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(6..=8))]
    pub lcp_size: usize,
}

impl SceneArgs {
    /// The core parameters these options describe (the rest at the paper's defaults).
    #[must_use]
    pub fn params<T: Real>(&self) -> SceneParams<T> {
        SceneParams {
            finger_speed: T::of(self.speed),
            mu_static: T::of(self.mu_s),
            mu_kinetic: T::of(self.mu_k),
            finger1_x: T::of(self.x1),
            finger2_x: T::of(self.x2),
            step: T::of(self.h),
            max_time: T::of(self.duration),
            ..SceneParams::paper()
        }
    }
}

fn outcome_name(o: Outcome) -> String {
    match o {
        Outcome::Balanced => "Balanced".into(),
        Outcome::Fell => "Fell".into(),
        Outcome::Unfinished => "Unfinished".into(),
        Outcome::NonFinite => "NonFinite".into(),
        Outcome::SolverFailed(e) => format!("SolverFailed({e})"),
    }
}

fn run_sized<T: Real, const N: usize>(args: &SceneArgs) -> anyhow::Result<String> {
    let params = args.params::<T>();
    let mut scene = Scene::<T, N, 256>::new(params).map_err(|e| anyhow::anyhow!("invalid scene: {e}"))?;
    let outcome = scene.run(|_| {});
    let mut out = format!(
        "scene: v = {} m/s, mu_s = {}, mu_k = {}, fingers {} / {} m, h = {} s, core {} {}x{}\n",
        args.speed,
        args.mu_s,
        args.mu_k,
        args.x1,
        args.x2,
        args.h,
        T::NAME,
        N,
        N
    );
    out += &format!("outcome: {} at t = {:.3} s\n", outcome_name(outcome), scene.time().as_f64());
    if let Some(m) = scene.meeting() {
        out += &format!(
            "fingers met at t = {:.3} s; centre of mass {:+.2} mm from their midpoint\n",
            m.time.as_f64(),
            1e3 * m.com_offset.as_f64()
        );
    }
    let st = scene.stats();
    out += &format!(
        "steps {}, pivots {} (mean {:.4}/step, max {}), warm starts {}, 6x6 check fired {} ({} before the fingers met)\n",
        st.steps,
        st.pivots,
        st.pivots as f64 / st.steps.max(1) as f64,
        st.max_pivots,
        st.warm_starts,
        st.reduced_check_fired,
        st.reduced_check_fired_before_meeting
    );
    out += &format!("switch events ({}; mu_k/mu_s = {:.4}):\n", scene.events().len(), args.mu_k / args.mu_s);
    // Modes before each event's step: in the first step both fingers start to slide at once
    // (the impulsive start), which is not an eq. 21 switch.
    let (mut mode, mut before, mut step_time) =
        ([ContactMode::Sticking; 2], [ContactMode::Sticking; 2], None);
    for e in scene.events() {
        if step_time != Some(e.time.as_f64().to_bits()) {
            step_time = Some(e.time.as_f64().to_bits());
            before = mode;
        }
        let i = e.finger as usize;
        let starts = before[i] == ContactMode::Sticking && e.mode.is_sliding() && before[1 - i].is_sliding();
        let ratio = if starts {
            format!("  x_stop/x_start = {:.4}", (e.along[1 - i].as_f64() / e.along[i].as_f64()).abs())
        } else {
            String::new()
        };
        out += &format!(
            "  t = {:7.3} s  finger {} -> {:9}  x1 = {:+.4} m  x2 = {:+.4} m{ratio}\n",
            e.time.as_f64(),
            i + 1,
            e.mode.name(),
            e.along[0].as_f64(),
            e.along[1].as_f64()
        );
        mode[i] = e.mode;
    }
    Ok(out)
}

/// Runs the scene the options describe and returns the summary text.
///
/// # Errors
/// Invalid scene parameters.
pub fn run(args: &SceneArgs) -> anyhow::Result<String> {
    match (args.precision, args.lcp_size) {
        (Precision::F32, 6) => run_sized::<f32, 6>(args),
        (Precision::F64, 6) => run_sized::<f64, 6>(args),
        (Precision::F32, 8) => run_sized::<f32, 8>(args),
        (Precision::F64, 8) => run_sized::<f64, 8>(args),
        (_, n) => anyhow::bail!("--lcp-size must be 6 or 8, not {n}"),
    }
}
