//! A scene of several bodies run in the independent reference (`meterstick_reference::multibody`).

use meterstick_core::scene::{OutcomeKind, SceneKind, SceneParams};

use super::{BodiesCounters, BodiesRow, BodiesRun, ContactRow, SpatialBody};
use crate::progress;
use crate::reference::Sample;
use crate::reference::multibody as reference;
use crate::trajectory::{Measured, RunOutcome};

/// The same scene for the independent reference (its own parameter types: data only).
#[must_use]
pub fn to_reference(spec: &SceneParams) -> Option<reference::Spec> {
    Some(match *spec {
        SceneParams::BlockOnBlock(p) => reference::Spec::BlockOnBlock(reference::BlockOnBlock {
            top_mass: p.top_mass,
            top_width: p.top_width,
            top_height: p.top_height,
            bottom_mass: p.bottom_mass,
            bottom_width: p.bottom_width,
            bottom_height: p.bottom_height,
            force: p.force,
            mu_static: p.mu_static,
            mu_kinetic: p.mu_kinetic,
            mu_floor: p.mu_floor,
            gravity: p.gravity,
            step: p.step,
            stick_speed: p.stick_speed,
            tilt_limit: p.tilt_limit,
            contact_margin: p.contact_margin,
            max_time: p.max_time,
        }),
        SceneParams::Tablecloth(p) => reference::Spec::Tablecloth(reference::Tablecloth {
            board_mass: p.board_mass,
            board_length: p.board_length,
            board_thickness: p.board_thickness,
            block_mass: p.block_mass,
            block_width: p.block_width,
            block_height: p.block_height,
            offset: p.offset,
            force: p.force,
            mu_static: p.mu_static,
            mu_kinetic: p.mu_kinetic,
            mu_floor: p.mu_floor,
            gravity: p.gravity,
            step: p.step,
            stick_speed: p.stick_speed,
            contact_margin: p.contact_margin,
            max_time: p.max_time,
        }),
        SceneParams::Stack(s) => {
            let p = s.params;
            reference::Spec::Stack(reference::Stack {
                blocks: s.block_count()?,
                length: p.length,
                height: p.height,
                mass: p.mass,
                mu_static: p.mu_static,
                mu_kinetic: p.mu_kinetic,
                overhang: p.overhang,
                gravity: p.gravity,
                step: p.step,
                stick_speed: p.stick_speed,
                tilt_limit: p.tilt_limit,
                drop_limit: p.drop_limit,
                contact_margin: p.contact_margin,
                max_time: p.max_time,
            })
        }
        SceneParams::DiscOnBoard(p) => reference::Spec::DiscOnBoard(reference::DiscOnBoard {
            board_mass: p.board_mass,
            board_length: p.board_length,
            board_height: p.board_height,
            disc_mass: p.disc_mass,
            disc_radius: p.disc_radius,
            offset: p.offset,
            force: p.force,
            mu_static: p.mu_static,
            mu_kinetic: p.mu_kinetic,
            mu_floor: p.mu_floor,
            gravity: p.gravity,
            step: p.step,
            stick_speed: p.stick_speed,
            contact_margin: p.contact_margin,
            max_time: p.max_time,
        }),
        _ => return None,
    })
}

fn reference_row(r: &reference::Row) -> BodiesRow {
    BodiesRow {
        t: r.t,
        q: r.q.clone(),
        v: r.v.clone(),
        interface_forces: r.interface_forces.clone(),
        corner_loads: r.corner_loads.clone(),
        spatial: Vec::new(),
        contacts: Vec::new(),
    }
}

/// Runs `spec` in the independent reference to its outcome, keeping every step when `record`.
///
/// # Errors
/// A scene the reference does not have, or its refusal of the parameters.
pub fn run_reference(spec: &SceneParams, record: bool) -> anyhow::Result<BodiesRun> {
    // The reference's scenes of several bodies, else its scenes in three dimensions (which
    // refuses a scene it does not have).
    let Some(r_spec) = to_reference(spec) else {
        return run_spatial_reference(spec, record);
    };
    let kind = spec.kind();
    progress::check()?;
    let sample = if record { Sample::All } else { Sample::None };
    let r = reference::run(&r_spec, sample).map_err(|e| anyhow::anyhow!("reference: {e}"))?;
    progress::check()?;
    let outcome = match r.outcome {
        reference::Outcome::Held => RunOutcome::of(OutcomeKind::Held),
        reference::Outcome::Rode => RunOutcome::of(OutcomeKind::Rode),
        reference::Outcome::Rolled => RunOutcome::of(OutcomeKind::Rolled),
        reference::Outcome::Slid => RunOutcome::of(OutcomeKind::Slid),
        reference::Outcome::Tipped => RunOutcome::of(OutcomeKind::Tipped),
        reference::Outcome::Stayed => RunOutcome::of(OutcomeKind::Stayed),
        reference::Outcome::Fell => RunOutcome::of(OutcomeKind::Fell),
        reference::Outcome::Unfinished => RunOutcome::of(OutcomeKind::Unfinished),
        reference::Outcome::Failed(why) => RunOutcome { class: OutcomeKind::Failed, detail: Some(why) },
    };
    let measures = match kind {
        SceneKind::BlockOnBlock | SceneKind::DiscOnBoard => {
            [r.lower_acceleration, r.upper_acceleration, None]
        }
        SceneKind::Tablecloth => [r.block_displacement, None, None],
        _ => [Some(r.max_speed), None, None],
    };
    Ok(BodiesRun {
        label: "reference f64".into(),
        scene: kind,
        steps: r.steps,
        end_time: r.end_time,
        rows: r.rows.iter().map(reference_row).collect(),
        last: BodiesRow {
            t: r.end_time,
            q: r.q.clone(),
            v: r.v.clone(),
            interface_forces: r.interface_forces.clone(),
            corner_loads: r.corner_loads.clone(),
            spatial: Vec::new(),
            contacts: Vec::new(),
        },
        outcome,
        measured: Measured::of(kind, measures),
        counters: BodiesCounters {
            lcp_rows: r.max_rows,
            ambiguous_steps: r.ambiguous_steps,
            ..BodiesCounters::default()
        },
        checksum: None,
    })
}

/// A scene in three dimensions as the independent reference has it (`meterstick_reference::spatial`).
enum SpatialReference {
    Puck(crate::reference::spatial::Puck),
    Billiard(crate::reference::spatial::Billiard),
    Curling(crate::reference::spatial::Curling),
    MeterStick3d(crate::reference::spatial::MeterStick3d),
    Stack3d(crate::reference::spatial::Stack3d),
}

/// `spec` in the reference's scenes in three dimensions; `None` for a scene it does not have.
fn to_spatial_reference(spec: &SceneParams) -> Option<SpatialReference> {
    use crate::reference::spatial as r;
    Some(match *spec {
        SceneParams::Puck(p) => SpatialReference::Puck(r::Puck {
            radius: p.radius,
            thickness: p.thickness,
            mass: p.mass,
            g: p.gravity,
            angle: p.angle,
            heading: p.heading,
            speed: p.speed,
            mu_s: p.mu_static,
            mu_k: p.mu_kinetic,
            h: p.step,
            stick_speed: p.stick_speed,
            max_time: p.max_time,
        }),
        SceneParams::Billiard(p) => SpatialReference::Billiard(r::Billiard {
            radius: p.radius,
            mass: p.mass,
            g: p.gravity,
            speed: p.speed,
            spin: [p.spin_x, p.spin_y, p.spin_z],
            mu_s: p.mu_static,
            mu_k: p.mu_kinetic,
            h: p.step,
            stick_speed: p.stick_speed,
            max_time: p.max_time,
        }),
        SceneParams::Curling(p) => SpatialReference::Curling(r::Curling {
            ring: p.is_ring(),
            radius: p.radius,
            mass: p.mass,
            points: p.count()?,
            g: p.gravity,
            speed: p.speed,
            spin: p.spin,
            mu: p.mu,
            h: p.step,
            stick_speed: p.stick_speed,
            max_time: p.max_time,
        }),
        SceneParams::MeterStick3d(p) => SpatialReference::MeterStick3d(r::MeterStick3d {
            rod_length: p.rod_length,
            rod_thickness: p.rod_thickness,
            rod_width: p.rod_width,
            rod_mass: p.rod_mass,
            gravity: p.gravity,
            finger1_x: p.finger1_x,
            finger2_x: p.finger2_x,
            finger1_y: p.finger1_y,
            finger2_y: p.finger2_y,
            finger1_velocity: p.finger1_velocity,
            finger2_velocity: p.finger2_velocity,
            heading: p.heading,
            finger_width: p.finger_width,
            mu_static: p.mu_static,
            mu_kinetic: p.mu_kinetic,
            step: p.step,
            stick_speed: p.stick_speed,
            tilt_limit: p.tilt_limit,
            drop_limit: p.drop_limit,
            hold_time: p.hold_time,
            max_time: p.max_time,
        }),
        SceneParams::Stack3d(s) => SpatialReference::Stack3d(stack_3d_reference(&s.params, s.block_count()?)),
        _ => return None,
    })
}

/// The independent reference's stack in three dimensions of `blocks` blocks for the core's
/// parameters `p` (its own parameter type: data only).
#[must_use]
pub fn stack_3d_reference(
    p: &meterstick_core::scene::spatial::Stack3dParams<f64>,
    blocks: usize,
) -> crate::reference::spatial::Stack3d {
    crate::reference::spatial::Stack3d {
        blocks,
        length: p.length,
        width: p.width,
        height: p.height,
        mass: p.mass,
        mu_s: p.mu_static,
        mu_k: p.mu_kinetic,
        overhang: p.overhang,
        heading: p.heading,
        g: p.gravity,
        h: p.step,
        stick_speed: p.stick_speed,
        tilt_limit: p.tilt_limit,
        drop_limit: p.drop_limit,
        margin: p.contact_margin,
        max_time: p.max_time,
    }
}

/// `true` when the independent reference has `spec`'s scene (of several bodies or in three
/// dimensions): [`run_reference`] runs it.
#[must_use]
pub fn has_reference(spec: &SceneParams) -> bool {
    to_reference(spec).is_some() || to_spatial_reference(spec).is_some()
}

/// A scene in three dimensions in the independent reference (`meterstick_reference::spatial`).
fn run_spatial_reference(spec: &SceneParams, record: bool) -> anyhow::Result<BodiesRun> {
    use crate::reference::spatial as r;
    let keep = if record { r::Keep::All } else { r::Keep::StartAndEnd };
    let Some(reference) = to_spatial_reference(spec) else {
        anyhow::bail!("scene {} has no reference", spec.kind());
    };
    progress::check()?;
    // The rod's three points (the pad's two, finger 2's), each kept row's; the other scenes'
    // one point is their row's own.
    let mut rod_points: Vec<[r::RodPoint; r::ROD_POINTS]> = Vec::new();
    let run = match reference {
        SpatialReference::Stack3d(stack) => return run_stack_reference(spec.kind(), &stack, keep),
        SpatialReference::Puck(p) => r::run_puck_keeping(&p, keep),
        SpatialReference::Billiard(b) => r::run_billiard_keeping(&b, keep),
        SpatialReference::Curling(c) => r::run_curling_keeping(&c, keep),
        SpatialReference::MeterStick3d(m) => r::run_meter_stick_3d_keeping(&m, keep).map(|run| {
            rod_points = run.points;
            run.run
        }),
    }
    .map_err(|e| anyhow::anyhow!("reference: {e}"))?;
    progress::check()?;
    let code = |mode: r::Mode| match mode {
        r::Mode::Separated => 0,
        r::Mode::Sticking => 1,
        r::Mode::Sliding => 2,
    };
    let row_at = |k: usize, x: &r::Row| BodiesRow {
        t: x.t,
        q: Vec::new(),
        v: Vec::new(),
        interface_forces: Vec::new(),
        corner_loads: Vec::new(),
        spatial: vec![SpatialBody {
            position: x.position,
            orientation: x.orientation,
            velocity: x.velocity,
            angular: x.angular_velocity,
        }],
        contacts: match rod_points.get(k) {
            Some(points) => points
                .iter()
                .map(|q| ContactRow {
                    mode: code(q.mode),
                    point: q.point,
                    normal_impulse: q.normal_impulse,
                    friction_impulse: q.friction_impulse,
                })
                .collect(),
            None => vec![ContactRow {
                mode: code(x.mode),
                // The contact point: the puck's centre, the ball's lowest point.
                point: match *spec {
                    SceneParams::Billiard(p) => [x.position[0], x.position[1], x.position[2] - p.radius],
                    _ => x.position,
                },
                normal_impulse: x.normal_impulse,
                friction_impulse: x.friction_impulse,
            }],
        },
    };
    let outcome = RunOutcome::of(match run.outcome {
        r::Outcome::Stopped => OutcomeKind::Stopped,
        r::Outcome::Slid => OutcomeKind::Slid,
        r::Outcome::Rolled => OutcomeKind::Rolled,
        r::Outcome::Unfinished => OutcomeKind::Unfinished,
        r::Outcome::Balanced => OutcomeKind::Balanced,
        r::Outcome::Fell => OutcomeKind::Fell,
        r::Outcome::Held => OutcomeKind::Held,
    });
    let end = run.trajectory.len().checked_sub(1).ok_or_else(|| anyhow::anyhow!("reference: no row"))?;
    let last = row_at(end, &run.trajectory[end]);
    Ok(BodiesRun {
        label: "reference f64".into(),
        scene: spec.kind(),
        steps: run.steps,
        end_time: last.t,
        rows: if record {
            run.trajectory.iter().enumerate().map(|(k, x)| row_at(k, x)).collect()
        } else {
            Vec::new()
        },
        last,
        outcome,
        measured: Measured::of(spec.kind(), run.measured),
        counters: BodiesCounters { lcp_rows: 0, ..BodiesCounters::default() },
        checksum: None,
    })
}

/// The stack in three dimensions in the independent reference: each kept row's blocks (no
/// contacts: the reference keeps none of its impulses), its outcome and largest point speed.
fn run_stack_reference(
    kind: SceneKind,
    stack: &crate::reference::spatial::Stack3d,
    keep: crate::reference::spatial::Keep,
) -> anyhow::Result<BodiesRun> {
    use crate::reference::spatial as r;
    let run = r::run_stack_3d_keeping(stack, keep).map_err(|e| anyhow::anyhow!("reference: {e}"))?;
    progress::check()?;
    let rows: Vec<BodiesRow> = run
        .trajectory
        .iter()
        .zip(&run.motion)
        .map(|((t, xs, qs), motion)| BodiesRow {
            t: *t,
            q: Vec::new(),
            v: Vec::new(),
            interface_forces: Vec::new(),
            corner_loads: Vec::new(),
            spatial: xs
                .iter()
                .zip(qs)
                .zip(motion)
                .map(|((x, q), (v, w))| SpatialBody {
                    position: *x,
                    orientation: *q,
                    velocity: *v,
                    angular: *w,
                })
                .collect(),
            contacts: Vec::new(),
        })
        .collect();
    let last = rows.last().cloned().ok_or_else(|| anyhow::anyhow!("reference: no row"))?;
    let outcome = RunOutcome::of(match run.outcome {
        r::Outcome::Fell => OutcomeKind::Fell,
        r::Outcome::Held => OutcomeKind::Held,
        _ => OutcomeKind::Unfinished,
    });
    Ok(BodiesRun {
        label: "reference f64".into(),
        scene: kind,
        steps: run.steps,
        end_time: last.t,
        rows: if keep == r::Keep::All { rows } else { Vec::new() },
        last,
        outcome,
        measured: Measured::of(kind, [Some(run.max_speed), None, None]),
        counters: BodiesCounters::default(),
        checksum: None,
    })
}
