//! Scene options shared by the commands that run scenes, and `host-sim scene`: one run of the
//! core scene, summarised on the terminal.
#![allow(clippy::format_push_string)] // a short summary built once per run

use meterstick_core::scene::SceneParams;

use crate::lcp_io::Precision;
use crate::trajectory::{Record, Trajectory, run_core, switches};

/// Scene options (SI units: m, s, kg, m/s^2). Defaults: the paper's scene.
#[derive(Debug, Clone, clap::Args)]
pub struct SceneArgs {
    /// Static friction coefficient (>= 0).
    #[arg(long, default_value_t = 0.6, allow_hyphen_values = true)]
    pub mu_s: f64,
    /// Kinetic friction coefficient (0 <= mu_k <= mu_s).
    #[arg(long, default_value_t = 0.4, allow_hyphen_values = true)]
    pub mu_k: f64,
    /// Start of finger 1 (moving), x from the rod's centre of mass (m, within +-L/2).
    #[arg(long, default_value_t = -0.4, allow_hyphen_values = true)]
    pub x1: f64,
    /// Start of finger 2 (fixed), x from the rod's centre of mass (m, > x1 + finger width).
    #[arg(long, default_value_t = 0.4, allow_hyphen_values = true)]
    pub x2: f64,
    /// Time step h (s, > 0).
    #[arg(long, default_value_t = 1e-3, allow_hyphen_values = true)]
    pub h: f64,
    /// Longest simulated time (s, > 0); a run that has not ended by then is "Unfinished".
    #[arg(long, default_value_t = 30.0, allow_hyphen_values = true)]
    pub duration: f64,
    /// Rod mass (kg, > 0).
    #[arg(long, default_value_t = 0.2, allow_hyphen_values = true)]
    pub mass: f64,
    /// Rod length L (m, > 0).
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    pub length: f64,
    /// Rod thickness (m, > 0).
    #[arg(long, default_value_t = 0.005, allow_hyphen_values = true)]
    pub thickness: f64,
    /// Finger width (m, >= 0): finger 1 stops when the tips are this far apart.
    #[arg(long, default_value_t = 0.01, allow_hyphen_values = true)]
    pub finger_width: f64,
    /// Gravity (m/s^2, >= 0).
    #[arg(long, default_value_t = 9.81, allow_hyphen_values = true)]
    pub gravity: f64,
    /// A finger in contact sticks when its slip speed relative to the rod is at most this
    /// (m/s, >= 0).
    #[arg(long, default_value_t = 1e-5, allow_hyphen_values = true)]
    pub stick_speed: f64,
    /// Scalar precision of the core.
    #[arg(long, value_enum, default_value = "f32")]
    pub precision: Precision,
    /// LCP size of the core: 6 (reduced, as the firmware) or 8 (the paper's form).
    #[arg(long, default_value_t = 6, value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(6..=8))]
    pub lcp_size: usize,
}

impl SceneArgs {
    /// The parameters these options describe for finger speed `speed` (m/s), validated.
    ///
    /// # Errors
    /// The first invalid parameter, or an LCP size other than 6 or 8.
    pub fn params(&self, speed: f64) -> anyhow::Result<SceneParams<f64>> {
        anyhow::ensure!(matches!(self.lcp_size, 6 | 8), "--lcp-size must be 6 or 8, not {}", self.lcp_size);
        let p = SceneParams {
            finger_speed: speed,
            mu_static: self.mu_s,
            mu_kinetic: self.mu_k,
            finger1_x: self.x1,
            finger2_x: self.x2,
            step: self.h,
            max_time: self.duration,
            rod_mass: self.mass,
            rod_length: self.length,
            rod_thickness: self.thickness,
            finger_width: self.finger_width,
            gravity: self.gravity,
            stick_speed: self.stick_speed,
            ..SceneParams::paper()
        };
        p.validate().map_err(|e| anyhow::anyhow!("invalid scene: {e}"))?;
        Ok(p)
    }

    /// The core's label for these options, e.g. `core f32 6x6`.
    #[must_use]
    pub fn core_label(&self) -> String {
        format!("core {} {n}x{n}", self.precision.name(), n = self.lcp_size)
    }
}

/// Runs the core in the given precision and LCP size (6 or 8).
///
/// # Errors
/// Invalid parameters or size.
pub fn run_configured(
    precision: Precision,
    lcp_size: usize,
    params: &SceneParams<f64>,
    record: Record,
) -> anyhow::Result<Trajectory> {
    match (precision, lcp_size) {
        (Precision::F32, 6) => run_core::<f32, 6>(params, record),
        (Precision::F64, 6) => run_core::<f64, 6>(params, record),
        (Precision::F32, 8) => run_core::<f32, 8>(params, record),
        (Precision::F64, 8) => run_core::<f64, 8>(params, record),
        (_, n) => anyhow::bail!("--lcp-size must be 6 or 8, not {n}"),
    }
}

/// `host-sim scene` options.
#[derive(Debug, Clone, clap::Args)]
pub struct SceneCmd {
    /// Finger 1 speed toward finger 2 (m/s, >= 0).
    #[arg(long, default_value_t = 0.1, allow_hyphen_values = true)]
    pub speed: f64,
    /// The scene.
    #[command(flatten)]
    pub scene: SceneArgs,
}

/// Runs the scene the options describe and returns the summary text.
///
/// # Errors
/// Invalid scene parameters.
pub fn run(cmd: &SceneCmd) -> anyhow::Result<String> {
    let args = &cmd.scene;
    let params = args.params(cmd.speed)?;
    let traj = run_configured(args.precision, args.lcp_size, &params, Record::Nothing)?;
    let mut out = format!(
        "scene: v = {} m/s, mu_s = {}, mu_k = {}, fingers {} / {} m, h = {} s, {}\n",
        cmd.speed, args.mu_s, args.mu_k, args.x1, args.x2, args.h, traj.label
    );
    out += &format!("outcome: {} at t = {:.3} s\n", traj.outcome, traj.end_time);
    if let Some((t, offset)) = traj.meeting {
        out += &format!(
            "fingers met at t = {t:.3} s; centre of mass {:+.2} mm from their midpoint\n",
            1e3 * offset
        );
    }
    let c = &traj.counters;
    out += &format!(
        "steps {}, pivots {} (mean {:.4}/step, max {}), warm starts {}, 6x6 check fired {} ({} before the fingers met)\n",
        traj.steps,
        c.pivots,
        c.pivots as f64 / traj.steps.max(1) as f64,
        c.max_pivots,
        c.warm_starts,
        c.reduced_check_fired,
        c.reduced_check_fired_before_meeting
    );
    out += &format!("switch events ({}; mu_k/mu_s = {:.4}):\n", traj.events.len(), args.mu_k / args.mu_s);
    let eq21 = switches(&traj);
    for e in &traj.events {
        let ratio = eq21
            .iter()
            .find(|s| s.t.to_bits() == e.t.to_bits() && s.finger == e.finger + 1)
            .map(|s| format!("  x_stop/x_start = {:.4}", s.ratio))
            .unwrap_or_default();
        out += &format!(
            "  t = {:7.3} s  finger {} -> {:9}  x1 = {:+.4} m  x2 = {:+.4} m{ratio}\n",
            e.t,
            e.finger + 1,
            e.mode.name(),
            e.along[0],
            e.along[1]
        );
    }
    Ok(out)
}
