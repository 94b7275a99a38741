//! `host-sim scene`: one run of a scene in the core, summarised on the terminal (outcome, the
//! scene's measured quantities, switch events with the eq. 21 ratio, solver statistics, and the
//! trajectory checksum the firmware and the browser page print for the same run).
#![allow(clippy::format_push_string)]

use std::fmt::Write as _;

use crate::scenes::{SceneArgs, SceneParams};
use crate::trajectory::{Record, run_watched, switches};

/// `host-sim scene` options.
#[derive(Debug, Clone, clap::Args)]
pub struct SceneCmdArgs {
    /// The scene and its parameters (one run: no flag may list several values).
    #[command(flatten)]
    pub scene: SceneArgs,
}

/// Runs the scene the options describe and returns the summary text.
///
/// # Errors
/// Invalid scene parameters (in the user's words), or a flag listing several values.
pub fn run(cmd: &SceneCmdArgs) -> anyhow::Result<String> {
    let specs = cmd.scene.specs(None)?;
    let [(_, spec)] = specs.as_slice() else {
        anyhow::bail!("host-sim scene runs one scene: give each flag one value (host-sim run takes lists)");
    };
    if crate::bodies::runs(spec.kind()) {
        return crate::bodies::summarise(spec, cmd.scene.precision);
    }
    crate::with_contacts!(spec.kind(), K => summarise::<K>(cmd, spec))
}

/// Runs a scene of `K` contacts and summarises it.
fn summarise<const K: usize>(cmd: &SceneCmdArgs, spec: &SceneParams) -> anyhow::Result<String> {
    let implementation = cmd.scene.implementation();
    let planned = (spec.max_time() / spec.step()).ceil() as u64;
    let bar = crate::progress::bar(planned, "steps");
    let traj = run_watched::<K>(spec, implementation, Record::Nothing, &bar)?;
    bar.finish_and_clear();
    let mut out = String::new();
    let params: Vec<String> = spec.fields().map(|(k, v)| format!("{k} = {v}")).collect();
    let _ = writeln!(out, "scene {}: {}", spec.kind(), params.join(", "));
    let _ = writeln!(
        out,
        "{}: outcome {} at t = {:.3} s",
        implementation.of_scene(spec.kind()),
        traj.outcome,
        traj.end_time
    );
    write_measured(&mut out, spec, &traj.measured);
    let c = &traj.counters;
    let _ = writeln!(
        out,
        "steps {}, pivots {} (mean {:.4}/step, max {}), warm starts {}, reduced check fired {} ({} before the fingers met)",
        traj.steps,
        c.pivots,
        c.pivots as f64 / traj.steps.max(1) as f64,
        c.max_pivots,
        c.warm_starts,
        c.reduced_check_fired,
        c.reduced_check_fired_before_meeting
    );
    let _ = writeln!(out, "solves by path: {}", c.paths);
    let friction = crate::scenes::friction_warning(spec, cmd.scene.precision);
    if let Some(warning) = &friction {
        let _ = writeln!(out, "{warning}");
    }
    if let Some(warning) = c.round_off_warning(traj.steps, friction.is_some()) {
        let _ = writeln!(out, "{warning}");
    }
    if let Some(sum) = traj.checksum {
        let _ = writeln!(out, "checksum {sum:08x}");
    }
    let eq21 = switches(&traj);
    let _ = writeln!(
        out,
        "switch events ({}; eq. 21 switches {}, before the fingers stopped):",
        traj.events.len(),
        eq21.len()
    );
    let stop = traj.measured.meeting.map(|m| m.time_s);
    let mut stop_shown = false;
    for e in &traj.events {
        if let Some(s) = stop
            && !stop_shown
            && e.t > s
        {
            let _ = writeln!(out, "  t = {s:7.3} s  the fingers stop");
            stop_shown = true;
        }
        let ratio = eq21
            .iter()
            .find(|s| s.t.to_bits() == e.t.to_bits() && s.finger == e.contact + 1)
            .map(|s| format!("  x_stop/x_start = {:.4}", s.ratio))
            .unwrap_or_default();
        let along: Vec<String> = e.along.iter().map(|a| format!("{a:+.4}")).collect();
        let _ = writeln!(
            out,
            "  t = {:7.3} s  contact {} -> {:9}  along = {} m{ratio}",
            e.t,
            e.contact + 1,
            e.mode.name(),
            along.join(" / ")
        );
    }
    if let Some(s) = stop
        && !stop_shown
    {
        let _ = writeln!(out, "  t = {s:7.3} s  the fingers stop");
    }
    Ok(out)
}

/// The scene's measured quantities, each beside its analytic value where the scene has one.
fn write_measured(out: &mut String, spec: &SceneParams, m: &crate::trajectory::Measured) {
    if let Some(meeting) = m.meeting {
        let _ = writeln!(
            out,
            "fingers met at t = {:.3} s; centre of mass {:+.2} mm from their midpoint",
            meeting.time_s,
            1e3 * meeting.com_offset_m
        );
    }
    if let Some(a) = m.acceleration_m_s2 {
        let exact = if let SceneParams::Incline(p) = spec {
            format!(
                " (g (sin a - mu_k cos a) = {:.6})",
                p.gravity * (p.angle.sin() - p.mu_kinetic * p.angle.cos())
            )
        } else if let SceneParams::Cylinder(p) = spec {
            let law =
                if p.rolls() { "rolling: g sin a / (1 + k)" } else { "sliding: g (sin a - mu_k cos a)" };
            format!(" ({law} = {:.6})", p.analytic_acceleration())
        } else {
            String::new()
        };
        let _ = writeln!(out, "acceleration down the slope {a:.6} m/s^2{exact}");
    }
    if let Some(w) = m.angular_acceleration_rad_s2 {
        let exact = if let SceneParams::Cylinder(p) = spec {
            let law = if p.rolls() {
                format!("rolling: a / r = {:.6}", p.analytic_acceleration() / p.radius)
            } else {
                let c = p.angle.cos();
                format!(
                    "sliding: mu_k g cos a / (k r) = {:.6}",
                    p.mu_kinetic * p.gravity * c / (p.inertia_factor * p.radius)
                )
            };
            format!(" ({law})")
        } else {
            String::new()
        };
        let _ = writeln!(out, "angular acceleration {w:.6} rad/s^2, counter-clockwise{exact}");
    }
    if let Some(j) = m.jam {
        let exact = if let SceneParams::Painleve(p) = spec {
            let (pf, pn) = p.jam_impulses();
            format!(
                " (tangential impact m V / 4 (1 + 3 c^2, 3 s c) = {pf:.6}, {pn:.6}; jams above mu_k = {:.4})",
                p.critical_mu()
            )
        } else {
            String::new()
        };
        let _ = writeln!(
            out,
            "the end jammed at t = {:.6} s: friction impulse {:.6} N s, normal impulse {:.6} N s{exact}",
            j.time_s, j.friction_impulse_n_s, j.normal_impulse_n_s
        );
    }
    if let (Some(h), Some(r)) = (m.wall_release_height_m, m.wall_release_ratio) {
        let _ =
            writeln!(out, "top left the wall at height {h:.5} m = {r:.5} of its start (frictionless: 2/3)");
    }
}
