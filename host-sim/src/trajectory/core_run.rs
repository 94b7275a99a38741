//! The core's run of a scene (scalar `T`, LCP size `N`), stepped to its outcome and recorded.

use indicatif::ProgressBar;
use meterstick_core::Real;
use meterstick_core::planar::{Checksum, ContactMode, StepReport};
use meterstick_core::scene::{Cylinder, Incline, Ladder, MeterStick, Outcome, Painleve, Scene, ThreeFingers};

use super::{ContactRow, Event, Measured, Record, Recorder, Row, SolverCounters, Trajectory};
use crate::lcp_io::Precision;
use crate::progress;
use crate::scenes::{Implementation, LcpSize, SceneKind, SceneParams};

fn invalid(e: meterstick_core::ParamError) -> anyhow::Error {
    anyhow::anyhow!("invalid scene: {e}")
}

/// Runs the core scene (scalar `T`, LCP size `N`) to its outcome and records it.
///
/// # Errors
/// Invalid parameters.
pub fn run_core<T: Real, const N: usize>(spec: &SceneParams, record: Record) -> anyhow::Result<Trajectory> {
    let t = run_inner_core::<T, N, 2>(spec, record)?;
    progress::check()?;
    Ok(t)
}

fn run_inner_core<T: Real, const N: usize, const K: usize>(
    spec: &SceneParams,
    record: Record,
) -> anyhow::Result<Trajectory<K>> {
    let contacts = spec.kind().info().contacts;
    anyhow::ensure!(contacts == K, "scene {} has {contacts} contacts, not {K}", spec.kind());
    core_run::<T, N, K>(spec, record, None)
}

/// The core's run of `spec` (its contacts are `K`: checked by the callers). `N` is the LCP size of
/// a two-contact scene (6 reduced, 8 full); other scenes run their own reduced or full layout
/// (three fingers 9 or 12, the cylinder 3 or 4).
pub(super) fn core_run<T: Real, const N: usize, const K: usize>(
    spec: &SceneParams,
    record: Record,
    bar: Option<&ProgressBar>,
) -> anyhow::Result<Trajectory<K>> {
    let implementation =
        Implementation::Core(if T::NAME == "f32" { Precision::F32 } else { Precision::F64 }, size_of(N));
    Ok(match *spec {
        SceneParams::MeterStick(p) => {
            let mut s = MeterStick::<T, N, 0>::new(p.cast()).map_err(invalid)?;
            let mut t = drive::<T, _, 2, K>(&mut s, implementation, SceneKind::MeterStick, record, bar);
            t.counters.reduced_check_fired_before_meeting = s.reduced_check_fired_before_meeting();
            t
        }
        SceneParams::Incline(p) => {
            let mut s = Incline::<T, N, 0>::new(p.cast()).map_err(invalid)?;
            drive::<T, _, 2, K>(&mut s, implementation, SceneKind::Incline, record, bar)
        }
        SceneParams::Ladder(p) => {
            let mut s = Ladder::<T, N, 0>::new(p.cast()).map_err(invalid)?;
            drive::<T, _, 2, K>(&mut s, implementation, SceneKind::Ladder, record, bar)
        }
        // The one- and three-contact scenes in their own reduced or full layout.
        SceneParams::ThreeFingers(p) if N == 6 => {
            let mut s = ThreeFingers::<T, 9, 0>::new(p.cast()).map_err(invalid)?;
            drive::<T, _, 3, K>(&mut s, implementation, SceneKind::ThreeFingers, record, bar)
        }
        SceneParams::ThreeFingers(p) => {
            let mut s = ThreeFingers::<T, 12, 0>::new(p.cast()).map_err(invalid)?;
            drive::<T, _, 3, K>(&mut s, implementation, SceneKind::ThreeFingers, record, bar)
        }
        SceneParams::Cylinder(p) if N == 6 => {
            let mut s = Cylinder::<T, 3, 0>::new(p.cast()).map_err(invalid)?;
            drive::<T, _, 1, K>(&mut s, implementation, SceneKind::Cylinder, record, bar)
        }
        SceneParams::Cylinder(p) => {
            let mut s = Cylinder::<T, 4, 0>::new(p.cast()).map_err(invalid)?;
            drive::<T, _, 1, K>(&mut s, implementation, SceneKind::Cylinder, record, bar)
        }
        SceneParams::Painleve(p) if N == 6 => {
            let mut s = Painleve::<T, 3, 0>::new(p.cast()).map_err(invalid)?;
            drive::<T, _, 1, K>(&mut s, implementation, SceneKind::Painleve, record, bar)
        }
        SceneParams::Painleve(p) => {
            let mut s = Painleve::<T, 4, 0>::new(p.cast()).map_err(invalid)?;
            drive::<T, _, 1, K>(&mut s, implementation, SceneKind::Painleve, record, bar)
        }
    })
}

fn size_of(n: usize) -> LcpSize {
    if n == 6 { LcpSize::Reduced } else { LcpSize::Full }
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
