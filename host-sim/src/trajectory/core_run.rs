//! The core's run of a scene, stepped to its outcome and recorded: a [`SceneVisitor`] of the
//! core's registry (`SceneParams::build`), so any scene in any precision and layout is driven by
//! one generic [`drive`].

use indicatif::ProgressBar;
use meterstick_core::Real;
use meterstick_core::planar::{Checksum, ContactMode, StepReport};
use meterstick_core::scene::{MeterStick, Outcome, Scene, SceneVisitor};

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
    spec.build::<0, _>(precision, layout, drive).map_err(|e| anyhow::anyhow!("invalid scene: {e}"))
}

/// [`drive`] as a visitor of the core's registry, recording `K` contacts.
struct Drive<'a, const K: usize> {
    implementation: Implementation,
    kind: SceneKind,
    record: Record,
    bar: Option<&'a ProgressBar>,
}

impl<const K: usize> SceneVisitor for Drive<'_, K> {
    type Output = Trajectory<K>;

    fn visit<T: Real, const KS: usize, const N: usize, S: Scene<T, KS>>(self, mut scene: S) -> Trajectory<K> {
        let d = self;
        drive::<T, _, KS, K>(&mut scene, d.implementation, d.kind, d.record, d.bar)
    }

    /// The meter stick also counts the reduced check's firings before the fingers met.
    fn visit_meter_stick<T: Real, const N: usize, const E: usize>(
        self,
        mut scene: MeterStick<T, N, E>,
    ) -> Trajectory<K> {
        let d = self;
        let mut t = drive::<T, _, 2, K>(&mut scene, d.implementation, d.kind, d.record, d.bar);
        t.counters.reduced_check_fired_before_meeting = scene.reduced_check_fired_before_meeting();
        t
    }
}

/// Where each support touches the body: the contact point `com + r` moved back by the gap along
/// the normal (a finger's tip; the foot of a corner on a line).
fn touch_points<T: Real, S: Scene<T, KS>, const KS: usize, const K: usize>(scene: &S) -> [[f64; 2]; K] {
    let s = scene.state();
    let mut out = [[0.0; 2]; K];
    for (o, f) in out.iter_mut().zip(scene.frames()) {
        let (r, n, gap) = (f.r.map(Real::as_f64), f.normal().map(Real::as_f64), f.gap.as_f64());
        *o = [s.x.as_f64() + r[0] - gap * n[0], s.y.as_f64() + r[1] - gap * n[1]];
    }
    out
}

/// Steps `scene` (`KS` contacts) to its outcome, recording rows and events with `K` contacts
/// (`K = KS`, checked before the run starts; the rows are written once, in place).
fn drive<T: Real, S: Scene<T, KS>, const KS: usize, const K: usize>(
    scene: &mut S,
    implementation: Implementation,
    kind: SceneKind,
    record: Record,
    bar: Option<&ProgressBar>,
) -> Trajectory<K> {
    let modes = scene.modes();
    let initial_modes: [ContactMode; K] =
        core::array::from_fn(|i| modes.get(i).copied().unwrap_or(ContactMode::Separated));
    let mut rows = Recorder::new(record);
    let s = *scene.state();
    let contact0 =
        ContactRow { mode: ContactMode::Separated, normal_impulse: 0.0, friction_impulse: 0.0, along: 0.0 };
    let mut first = Row {
        t: 0.0,
        q: [s.x, s.y, s.theta].map(Real::as_f64),
        v: s.velocity().map(Real::as_f64),
        supports: touch_points(scene),
        contacts: [contact0; K],
    };
    for (c, m) in first.contacts.iter_mut().zip(initial_modes) {
        c.mode = m;
    }
    rows.push(first);
    let mut events = Vec::new();
    let mut checksum = Checksum::new();
    let mut steps = 0_u64;
    while let Some(r) = scene.step() {
        steps += 1;
        if steps.is_multiple_of(progress::CHECK_EVERY_STEPS) {
            if let Some(bar) = bar {
                bar.inc(progress::CHECK_EVERY_STEPS);
            }
            if progress::interrupted() {
                break;
            }
        }
        checksum.add(&r.state);
        let supports = touch_points(scene);
        let row = row_of::<T, KS, K>(&r, supports);
        for (i, mode) in r.switches() {
            events.push(Event { t: row.t, contact: i, mode, along: row.contacts.map(|c| c.along), supports });
        }
        rows.push(row);
    }
    let mut counters = SolverCounters::from(scene.stats());
    counters.reduced_check_fired_before_meeting = 0;
    Trajectory {
        implementation,
        scene: kind,
        steps: scene.stats().steps,
        end_time: scene.time().as_f64(),
        rows: rows.finish(),
        initial_modes,
        events,
        outcome: scene.outcome().unwrap_or(Outcome::Unfinished).into(),
        measured: Measured::of(kind, scene.measured().map(|v| v.map(Real::as_f64))),
        counters,
        checksum: Some(checksum.value()),
    }
}

fn row_of<T: Real, const KS: usize, const K: usize>(
    r: &StepReport<T, KS>,
    supports: [[f64; 2]; K],
) -> Row<K> {
    let s = &r.state;
    Row {
        t: r.time.as_f64(),
        q: [s.x, s.y, s.theta].map(Real::as_f64),
        v: s.velocity().map(Real::as_f64),
        supports,
        contacts: core::array::from_fn(|i| {
            r.contacts.get(i).map_or(
                ContactRow {
                    mode: ContactMode::Separated,
                    normal_impulse: 0.0,
                    friction_impulse: 0.0,
                    along: 0.0,
                },
                |c| ContactRow {
                    mode: c.mode,
                    normal_impulse: c.normal_impulse.as_f64(),
                    friction_impulse: c.friction_impulse.as_f64(),
                    along: c.along.as_f64(),
                },
            )
        }),
    }
}
