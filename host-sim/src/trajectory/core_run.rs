//! The core's run of a scene of one body, stepped to its outcome and recorded: driven through the
//! core's one scene interface ([`SceneView`], built by `SceneParams::build_view`), so any such
//! scene in any precision and layout is recorded by one generic [`drive`] that names no engine.

use indicatif::ProgressBar;
use meterstick_core::Real;
use meterstick_core::planar::ContactMode;
use meterstick_core::scene::{ContactView, Outcome, Pose, SceneView, Velocity, ViewVisitor};

use super::{ContactRow, Event, Measured, Record, Recorder, Row, SolverCounters, Trajectory};
use crate::progress;
use crate::scenes::{Implementation, LcpLayout, Precision, SceneKind, SceneParams};

/// Runs the core scene in `precision` and `layout` to its outcome and records it.
///
/// # Errors
/// Invalid parameters, or a scene with other than `K` contacts.
pub fn run_core<const K: usize>(
    spec: &SceneParams,
    precision: Precision,
    layout: LcpLayout,
    record: Record,
) -> anyhow::Result<Trajectory<K>> {
    let t = core_run::<K>(spec, precision, layout, record, None)?;
    progress::check()?;
    Ok(t)
}

/// The core's run of `spec`, a scene of `K` contacts (checked before it starts).
pub(super) fn core_run<const K: usize>(
    spec: &SceneParams,
    precision: Precision,
    layout: LcpLayout,
    record: Record,
    bar: Option<&ProgressBar>,
) -> anyhow::Result<Trajectory<K>> {
    let contacts = spec.kind().contacts();
    anyhow::ensure!(contacts == K, "scene {} has {contacts} contacts, not {K}", spec.kind());
    let drive = Drive::<K> {
        implementation: Implementation::Core(precision, layout),
        kind: spec.kind(),
        record,
        bar,
    };
    spec.build_view::<0, _>(precision, layout, drive).map_err(|e| anyhow::anyhow!("invalid scene: {e}"))?
}

/// [`drive`] as a visitor of any scene's view, recording `K` contacts.
struct Drive<'a, const K: usize> {
    implementation: Implementation,
    kind: SceneKind,
    record: Record,
    bar: Option<&'a ProgressBar>,
}

impl<const K: usize> ViewVisitor for Drive<'_, K> {
    type Output = anyhow::Result<Trajectory<K>>;

    fn visit<T: Real>(self, view: &mut dyn SceneView<T>) -> Self::Output {
        drive::<T, K>(view, &self)
    }
}

/// The body's `(x, y, theta)` and `(vx, vy, omega)`, or why it has none: a recording of one body
/// in the plane records body 0's planar pose.
fn planar_body<T: Real>(view: &dyn SceneView<T>) -> anyhow::Result<([f64; 3], [f64; 3])> {
    let body = view.body(0).ok_or_else(|| anyhow::anyhow!("the scene has no body to record"))?;
    match (body.pose, body.velocity) {
        (Pose::Planar { x, y, theta }, Velocity::Planar { vx, vy, omega }) => {
            Ok(([x, y, theta].map(Real::as_f64), [vx, vy, omega].map(Real::as_f64)))
        }
        #[allow(unreachable_patterns)]
        _ => anyhow::bail!("a recording of one body in the plane was given a body in three dimensions"),
    }
}

/// Each contact now, `None` past the view's list.
fn contacts<T: Real, const K: usize>(view: &dyn SceneView<T>) -> [Option<ContactView<T>>; K] {
    core::array::from_fn(|i| view.contact(i))
}

/// Where each support touches the body: the contact point (the body's position plus its lever,
/// summed in f64) moved back by the gap along the normal (a finger's tip; the foot of a corner on
/// a line).
fn touch_points<T: Real, const K: usize>(
    q: [f64; 3],
    contacts: &[Option<ContactView<T>>; K],
) -> [[f64; 2]; K] {
    contacts.map(|c| {
        c.map_or([0.0; 2], |c| {
            let (r, n, gap) = (c.lever.map(Real::as_f64), c.normal.map(Real::as_f64), c.gap.as_f64());
            [q[0] + r[0] - gap * n[0], q[1] + r[1] - gap * n[1]]
        })
    })
}

/// A contact as a row records it (a contact past the view's list: separated, no impulse).
fn contact_row<T: Real>(c: Option<ContactView<T>>) -> ContactRow {
    c.map_or(
        ContactRow { mode: ContactMode::Separated, normal_impulse: 0.0, friction_impulse: 0.0, along: 0.0 },
        |c| ContactRow {
            mode: c.mode,
            normal_impulse: c.normal_impulse.as_f64(),
            friction_impulse: c.friction_impulse.as_f64(),
            along: c.along.as_f64(),
        },
    )
}

/// Steps `view` to its outcome, recording rows and the contacts' switches of mode with `K`
/// contacts (the rows are written once, in place).
///
/// The meter stick's `reduced_check_fired_before_meeting` counts the steps whose reduced layout
/// needed the full one (its `RunStats::reduced_check_fired` grew) while its meeting (its first
/// measured quantity) had no value after the step: the meeting is set in the step the fingers
/// stop, which the scene does not count either.
fn drive<T: Real, const K: usize>(
    view: &mut dyn SceneView<T>,
    d: &Drive<'_, K>,
) -> anyhow::Result<Trajectory<K>> {
    let mut rows = Recorder::new(d.record);
    let (q, v) = planar_body(view)?;
    let now = contacts::<T, K>(view);
    let initial_modes = now.map(|c| c.map_or(ContactMode::Separated, |c| c.mode));
    let mut modes = initial_modes;
    let mut first =
        Row { t: 0.0, q, v, supports: touch_points(q, &now), contacts: [contact_row::<T>(None); K] };
    for (c, m) in first.contacts.iter_mut().zip(initial_modes) {
        c.mode = m;
    }
    rows.push(first);
    let meets = d.kind == SceneKind::MeterStick;
    let (mut fired, mut fired_before_meeting) = (view.summary().reduced_check_fired, 0_u64);
    let mut events = Vec::new();
    let mut steps = 0_u64;
    while view.step() {
        steps += 1;
        if steps.is_multiple_of(progress::CHECK_EVERY_STEPS) {
            if let Some(bar) = d.bar {
                bar.inc(progress::CHECK_EVERY_STEPS);
            }
            if progress::interrupted() {
                break;
            }
        }
        let (q, v) = planar_body(view)?;
        let now = contacts::<T, K>(view);
        let row = Row {
            t: view.time().as_f64(),
            q,
            v,
            supports: touch_points(q, &now),
            contacts: now.map(contact_row),
        };
        for (i, (c, was)) in row.contacts.iter().zip(&mut modes).enumerate() {
            if c.mode != *was {
                *was = c.mode;
                events.push(Event {
                    t: row.t,
                    contact: i,
                    mode: c.mode,
                    along: row.contacts.map(|c| c.along),
                    supports: row.supports,
                });
            }
        }
        if meets {
            let now_fired = view.summary().reduced_check_fired;
            if now_fired > fired && view.measured()[0].is_none() {
                fired_before_meeting += now_fired - fired;
            }
            fired = now_fired;
        }
        rows.push(row);
    }
    let stats = view.summary();
    let mut counters = SolverCounters::from(&stats);
    counters.reduced_check_fired_before_meeting = fired_before_meeting;
    Ok(Trajectory {
        implementation: d.implementation,
        scene: d.kind,
        steps: stats.steps,
        end_time: view.time().as_f64(),
        rows: rows.finish(),
        initial_modes,
        events,
        outcome: view.outcome().unwrap_or(Outcome::Unfinished).into(),
        measured: Measured::of(d.kind, view.measured().map(|v| v.map(Real::as_f64))),
        counters,
        checksum: Some(view.checksum()),
    })
}
