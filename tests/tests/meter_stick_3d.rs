//! The meter stick in three dimensions (`meterstick_core::scene::spatial::MeterStick3d`,
//! `docs/scenes.md`, "meter-stick-3d"): at heading 0 the planar scene's run (outcome, switch
//! events, meeting offset, positions), the planar core being an independent formulation of the
//! same physics (its own contact frames, its 2x2-contact LCP, its compensated integration); at
//! other headings the mirror law (a heading and its negative give trajectories mirrored in the
//! rod's vertical plane) and the balance law (the fingers meet under the centre of mass).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::cast_precision_loss, clippy::print_stdout)]

use meterstick_core::Real;
use meterstick_core::planar::ContactMode;
use meterstick_core::scene::spatial::{MeterStick3d, MeterStick3dParams};
use meterstick_core::scene::{MeterStick8, Outcome, Scene};
use meterstick_core::spatial::Mode;

/// The class of a planar contact's mode, as the spatial scene's fingers report theirs.
fn class(mode: ContactMode) -> Mode {
    match mode {
        ContactMode::Separated => Mode::Separated,
        ContactMode::Sticking => Mode::Sticking,
        ContactMode::Sliding(_) => Mode::Sliding,
    }
}

/// Both scenes run in lockstep from the same parameters at heading 0.
struct Lockstep {
    /// The largest distance between the rods' centres of mass over the run (m).
    distance: f64,
    /// The steps after which a finger's mode differs from the planar contact's.
    modes_differ: usize,
    steps: usize,
    outcomes: [Outcome; 2],
    /// The meetings' offsets, spatial then planar.
    meetings: [Option<f64>; 2],
    /// Each switch: time, finger, mode; spatial then planar.
    switches: [Vec<(f64, u8, Mode)>; 2],
}

/// The planar switches that change a contact's class (a reversal of sliding is the planar
/// scene's alone: in three dimensions a slip has a direction in the plane, not a sign).
/// `start` the contacts' modes before the first step.
fn class_changes(start: [Mode; 2], events: impl Iterator<Item = (f64, u8, Mode)>) -> Vec<(f64, u8, Mode)> {
    let mut last = start.map(Some);
    events
        .filter(|&(_, contact, mode)| {
            let slot = &mut last[usize::from(contact)];
            let changed = *slot != Some(mode);
            *slot = Some(mode);
            changed
        })
        .collect()
}

fn lockstep<T: Real>(p: MeterStick3dParams<f64>) -> Lockstep {
    let q: MeterStick3dParams<T> = p.cast();
    let mut spatial = MeterStick3d::<T>::new(q).expect("valid");
    let mut planar = MeterStick8::<T>::new(q.planar()).expect("valid");
    let start = Scene::modes(&planar).map(class);
    assert_eq!(start, spatial.finger_modes(), "the modes before the first step");
    let (mut distance, mut modes_differ, mut steps) = (0.0_f64, 0, 0);
    while let (Some(a), Some(b)) = (spatial.step(), Scene::step(&mut planar)) {
        steps += 1;
        let s = a.state.position;
        let d = [s[0].as_f64() - b.state.x.as_f64(), s[1].as_f64(), s[2].as_f64() - b.state.y.as_f64()];
        distance = distance.max(d.iter().map(|x| x * x).sum::<f64>().sqrt());
        if b.contacts.map(|c| class(c.mode)) != spatial.finger_modes() {
            modes_differ += 1;
        }
    }
    let meeting = |m: Option<meterstick_core::scene::Meeting<T>>| m.map(|m| m.com_offset.as_f64());
    Lockstep {
        distance,
        modes_differ,
        steps,
        outcomes: [spatial.outcome().expect("ended"), planar.outcome().expect("ended")],
        meetings: [meeting(spatial.meeting()), meeting(planar.meeting())],
        switches: [
            spatial.events().iter().map(|e| (e.time.as_f64(), e.finger, e.mode)).collect(),
            class_changes(start, planar.events().iter().map(|e| (e.time.as_f64(), e.contact, class(e.mode)))),
        ],
    }
}

/// At heading 0 the rod's run is the planar scene's: the same outcome, a finger switching when
/// the planar contact does (the same step, the same mode), the fingers meeting at the same offset
/// and the centre of mass on the planar one's path. In f64 within 1e-9 m, every switch at the
/// same step. In f32 the two
/// integrate the positions differently (the planar core sums `x += h v` compensated, the spatial
/// core plainly, each sum rounding by up to half an ulp of the coordinate, `2^-25` m below 0.5
/// m): within that bound over the run's steps, and a switch may fall one step apart.
#[test]
fn heading_zero_is_the_planar_run() {
    for finger1_x in [-0.4, -0.35, -0.2] {
        for finger2_velocity in [0.0, -0.05] {
            let p = MeterStick3dParams::<f64> { finger1_x, finger2_velocity, ..Default::default() };
            for (bits, r) in [(64, lockstep::<f64>(p)), (32, lockstep::<f32>(p))] {
                println!(
                    "f{bits} finger1_x {finger1_x} finger2_velocity {finger2_velocity}: {} steps, largest distance {:.3e} m, \
                     outcomes {:?}, meetings {:?}, switches {}",
                    r.steps,
                    r.distance,
                    r.outcomes,
                    r.meetings,
                    r.switches[0].len()
                );
                let tolerance = if bits == 64 { 1e-9 } else { r.steps as f64 * 2f64.powi(-25) };
                assert!(r.distance <= tolerance, "f{bits}: {} m", r.distance);
                assert_eq!(r.outcomes[0], r.outcomes[1], "f{bits}");
                // In f32 a switch whose test sits within round-off of its threshold may fall a step
                // apart: each switch may then differ for one step.
                let slack = usize::from(bits != 64);
                assert!(r.modes_differ <= slack * r.switches[1].len(), "f{bits}: {}", r.modes_differ);
                let [a, b] = r.meetings.map(|m| m.expect("the fingers met"));
                assert!((a - b).abs() <= tolerance, "f{bits}: meeting offsets {a} {b}");
                assert_eq!(r.switches[0].len(), r.switches[1].len(), "f{bits}: {:?}", r.switches);
                for (x, y) in r.switches[0].iter().zip(&r.switches[1]) {
                    assert!(
                        (x.0 - y.0).abs() <= (slack as f64 + 0.5) * p.step && x.1 == y.1 && x.2 == y.2,
                        "f{bits}: {x:?} {y:?}"
                    );
                }
            }
        }
    }
}

/// A heading and its negative are mirror images across the rod's vertical plane (`y -> -y`): the
/// rod's centre of mass at every step, to the step's round-off grown over the run.
#[test]
fn opposite_headings_mirror_each_other() {
    for heading in [5.0, 10.0, 30.0] {
        let run = |heading: f64| {
            let mut scene = MeterStick3d::<f64>::new(MeterStick3dParams {
                heading: heading.to_radians(),
                ..Default::default()
            })
            .expect("valid");
            let mut path = Vec::new();
            while let Some(r) = scene.step() {
                path.push(r.state.position);
            }
            (path, scene.outcome().unwrap(), scene.meeting().map(|m| m.com_offset))
        };
        let (a, oa, ma) = run(heading);
        let (b, ob, mb) = run(-heading);
        assert_eq!(oa, ob);
        assert_eq!(a.len(), b.len());
        let worst = a
            .iter()
            .zip(&b)
            .map(|(p, q)| (p[0] - q[0]).abs().max((p[1] + q[1]).abs()).max((p[2] - q[2]).abs()))
            .fold(0.0, f64::max);
        let sideways = a.iter().map(|p| p[1].abs()).fold(0.0, f64::max);
        println!(
            "heading {heading}: {oa:?} after {} steps, meeting {ma:?} {mb:?}, mirror {worst:.3e} m, sideways up to {sideways:.3e} m",
            a.len()
        );
        assert!(worst <= 1e-9, "{worst}");
        assert!(sideways > 0.0);
    }
}
