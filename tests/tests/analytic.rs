//! The incline, the ladder and the meter stick's new motions against laws that need no
//! simulation to trust (`docs/formulation.md`, "Checks that need no simulation to trust"):
//! statics of a block on a slope and of a ladder, the sliding block's acceleration, the
//! frictionless ladder's release at 2/3 of its height, the uniqueness of the motion where the
//! friction is statically indeterminate (checked by enumerating every solution of the step's
//! LCP, independently of the solver), and the meter stick's mirror symmetry.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use meterstick_core::Real;
use meterstick_core::lcp::Lcp;
use meterstick_core::planar::assemble::{StepInputs, assemble};
use meterstick_core::planar::{Body, ContactFrame, ContactMode, Direction, Layout, Pose};
use meterstick_core::scene::{
    Incline, InclineParams, Ladder, LadderParams, MeterStick, MeterStickParams, Outcome, Scene,
};
use meterstick_tests::enumeration::all_solutions;

fn deg(d: f64) -> f64 {
    d.to_radians()
}

fn incline<T: Real, const N: usize>(p: InclineParams<f64>) -> Incline<T, N, 64> {
    let mut s = Incline::<T, N, 64>::new(p.cast()).unwrap();
    s.run(|_| {});
    s
}

/// Held when `tan a <= mu_s` and `tan a < w/h`: the block never moves (to round-off of its
/// position), in both precisions and layouts, at several angles and shapes.
fn check_held<T: Real, const N: usize>() {
    for (angle, w, hgt, mu_s) in
        [(10.0, 0.1, 0.05, 0.6), (30.0, 0.1, 0.05, 0.6), (25.0, 0.3, 0.3, 0.5), (59.0, 1.0, 0.2, 1.7)]
    {
        assert!(deg(angle).tan() <= mu_s && deg(angle).tan() < w / hgt);
        let p = InclineParams {
            angle: deg(angle),
            width: w,
            height: hgt,
            mu_static: mu_s,
            mu_kinetic: 0.3,
            ..InclineParams::default()
        };
        let s = incline::<T, N>(p);
        assert_eq!(s.outcome(), Some(Outcome::Held), "{} {N}x{N} at {angle} deg", T::NAME);
        let start = p.resting_state();
        let st = s.state();
        let moved = (st.x.as_f64() - start.x).hypot(st.y.as_f64() - start.y);
        assert!(
            moved < 256.0 * T::EPS.as_f64() * w.max(hgt),
            "{} at {angle} deg: moved {moved:e} m",
            T::NAME
        );
    }
}

#[test]
fn a_block_sticks_where_statics_holds_it() {
    check_held::<f64, 8>();
    check_held::<f64, 6>();
    check_held::<f32, 6>();
    check_held::<f32, 8>();
}

/// A wide block with `tan a > mu_s` slides with `a = g (sin a - mu_k cos a)`: within 0.5 %
/// (measured: 1e-14 relative in f64, about 1e-5 in f32).
#[test]
fn a_sliding_block_accelerates_at_g_sin_minus_mu_k_cos() {
    for (angle, mu_s, mu_k) in [(35.0, 0.6, 0.4), (50.0, 1.0, 0.8), (20.0, 0.3, 0.1), (30.0, 0.0, 0.0)] {
        let p = InclineParams {
            angle: deg(angle),
            mu_static: mu_s,
            mu_kinetic: mu_k,
            ..InclineParams::default()
        };
        let exact = p.gravity * (deg(angle).sin() - mu_k * deg(angle).cos());
        for (what, a, outcome) in [
            ("f64 8x8", incline::<f64, 8>(p).acceleration(), incline::<f64, 8>(p).outcome()),
            ("f64 6x6", incline::<f64, 6>(p).acceleration(), incline::<f64, 6>(p).outcome()),
            ("f32 6x6", incline::<f32, 6>(p).acceleration().map(f64::from), incline::<f32, 6>(p).outcome()),
        ] {
            assert_eq!(outcome, Some(Outcome::Slid), "{what} at {angle} deg");
            let a = a.unwrap();
            assert!((a / exact - 1.0).abs() < 0.005, "{what} at {angle} deg: a = {a} vs {exact}");
        }
    }
}

/// A tall block with `w/h < tan a < mu_s` tips over its lower edge (and a wide one at the same
/// slope does not).
#[test]
fn a_tall_block_tips_over_its_lower_edge() {
    for (angle, w, hgt) in [(20.0, 0.05, 0.2), (10.0, 0.02, 0.2), (30.0, 0.2, 0.4)] {
        assert!(w / hgt < deg(angle).tan() && deg(angle).tan() < 0.6);
        let p = InclineParams { angle: deg(angle), width: w, height: hgt, ..InclineParams::default() };
        assert_eq!(incline::<f64, 8>(p).outcome(), Some(Outcome::Tipped), "{angle} deg, {w} x {hgt}");
        assert_eq!(incline::<f32, 6>(p).outcome(), Some(Outcome::Tipped), "f32, {angle} deg, {w} x {hgt}");
        let wide = InclineParams { width: 2.0 * hgt * deg(angle).tan().recip(), ..p };
        assert_eq!(incline::<f64, 8>(wide).outcome(), Some(Outcome::Held), "wide at {angle} deg");
    }
}

/// Both corners sticking: the friction split between them is statically indeterminate, so the
/// step's LCP has many solutions. Every one of them (all complementary bases, enumerated
/// independently of the solver) gives the block the same velocity, which is the core's, and the
/// core's answer is one of them.
#[test]
fn indeterminate_friction_still_gives_a_unique_verified_motion() {
    let p = InclineParams { angle: deg(20.0), ..InclineParams::<f64>::default() };
    let body = Body::block(p.mass, p.width, p.height);
    let rest = p.resting_state();
    let pose = Pose { com: [rest.x, rest.y], sin_cos: rest.theta.sin_cos() };
    let plane = p.plane();
    let meterstick_core::planar::Support::Line { position, normal, .. } = plane else { panic!() };
    let corners = body.corners();
    let frames = [corners[0], corners[1]].map(|c| ContactFrame::point_on_line(c, position, normal, &pose));
    let m_inv = body.inverse_mass_per_unit_mass();
    let v_free = [0.0, -p.step * p.gravity, 0.0];
    let input = StepInputs {
        frames: &frames,
        mu: [p.mu_static; 2],
        support_velocity: [[0.0; 2]; 2],
        v_free,
        m_inv,
        h: p.step,
        gravity: p.gravity,
        gap_round_off: 0.0,
    };
    let step = assemble(&Layout::<2, 8>::full(), &input);
    let velocity = |z: &[f64]| {
        let mut v = v_free;
        for (c, zj) in step.columns.iter().zip(z) {
            for k in 0..3 {
                v[k] += m_inv[k] * c[k] * zj;
            }
        }
        v
    };
    let lcp: &Lcp<f64, 8> = &step.lcp;
    let m: Vec<Vec<f64>> = (0..8).map(|i| (0..8).map(|j| lcp.m[(i, j)]).collect()).collect();
    let q: Vec<f64> = (0..8).map(|i| lcp.q[i]).collect();
    let solutions = all_solutions(&m, &q);
    assert!(
        solutions.len() >= 2,
        "expected the indeterminate friction to give several solutions: {solutions:?}"
    );
    let friction_splits: Vec<(f64, f64)> = solutions.iter().map(|z| (z[2] - z[3], z[4] - z[5])).collect();
    let spread = friction_splits.iter().map(|f| f.0).fold(f64::NEG_INFINITY, f64::max)
        - friction_splits.iter().map(|f| f.0).fold(f64::INFINITY, f64::min);
    assert!(spread > 1e-4, "the friction split should differ between solutions: {friction_splits:?}");
    for z in &solutions {
        let v = velocity(z);
        assert!(v.iter().all(|x| x.abs() < 1e-12), "a solution moves the block: v+ = {v:?}, z = {z:?}");
    }
    let core = meterstick_core::lcp::Lemke::<f64, 8>::new().solve(lcp).unwrap();
    assert!(meterstick_core::lcp::is_solution(lcp, &core.z));
    assert!(velocity(core.z.as_slice()).iter().all(|x| x.abs() < 1e-12));
}

/// The ladder stands iff `tan theta >= (1 - mu_f mu_w) / (2 mu_f)`: 2 degrees above the critical
/// angle it holds (never slides), 2 degrees below it falls, for several friction pairs.
#[test]
fn a_ladder_stands_above_its_critical_angle_and_falls_below() {
    for (mu_f, mu_w) in [(0.4, 0.3), (0.5, 0.0), (0.3, 0.5), (0.8, 0.2)] {
        let p =
            LadderParams { mu_floor: mu_f, mu_wall: mu_w, max_time: 5.0, ..LadderParams::<f64>::default() };
        let critical = p.critical_angle();
        assert!((critical.tan() - (1.0 - mu_f * mu_w) / (2.0 * mu_f)).abs() < 1e-12);
        for (offset, expected) in [(2.0, Outcome::Held), (-2.0, Outcome::Fell)] {
            let p = LadderParams { angle: critical + deg(offset), ..p };
            for (what, outcome) in [
                ("f64 8x8", Ladder::<f64, 8, 0>::new(p).unwrap().run(|_| {})),
                ("f64 6x6", Ladder::<f64, 6, 0>::new(p).unwrap().run(|_| {})),
                ("f32 6x6", Ladder::<f32, 6, 0>::new(p.cast()).unwrap().run(|_| {})),
            ] {
                assert_eq!(
                    outcome, expected,
                    "{what}: mu_f = {mu_f}, mu_w = {mu_w}, {offset:+} deg from critical"
                );
            }
        }
    }
}

/// Frictionless, the ladder's top leaves the wall when it has fallen to 2/3 of its initial height:
/// within 1 % at h = 1e-4 s in f64 (measured: -0.10 % from 45 degrees; at h = 1e-3 s -0.86 %), from
/// several angles.
#[test]
fn a_frictionless_ladder_leaves_the_wall_at_two_thirds_of_its_height() {
    for angle in [30.0, 45.0, 60.0, 75.0] {
        let p = LadderParams {
            angle: deg(angle),
            mu_floor: 0.0,
            mu_wall: 0.0,
            step: 1e-4,
            ..LadderParams::<f64>::default()
        };
        let mut six = Ladder::<f64, 6, 0>::new(p).unwrap();
        let mut eight = Ladder::<f64, 8, 0>::new(p).unwrap();
        assert_eq!((six.run(|_| {}), eight.run(|_| {})), (Outcome::Fell, Outcome::Fell));
        for (what, height, start) in [
            ("6x6", six.wall_release_height(), six.start_top_height()),
            ("8x8", eight.wall_release_height(), eight.start_top_height()),
        ] {
            let ratio = height.unwrap() / start;
            assert!((ratio / (2.0 / 3.0) - 1.0).abs() < 0.01, "{what} from {angle} deg: released at {ratio}");
        }
    }
}

/// Finger 2 moving toward finger 1 is the mirror image of finger 1 moving toward finger 2: the
/// same switches at the same steps with the fingers exchanged, the rod's x and angle mirrored.
#[test]
fn finger_2_moving_is_the_mirror_image_of_finger_1_moving() {
    let one = MeterStickParams::<f64> { finger1_x: -0.35, ..MeterStickParams::paper() };
    let two = MeterStickParams::<f64> {
        finger1_x: -0.4,
        finger2_x: 0.35,
        finger1_velocity: 0.0,
        finger2_velocity: -0.1,
        ..MeterStickParams::paper()
    };
    let (mut a, mut b) =
        (MeterStick::<f64, 8, 64>::new(one).unwrap(), MeterStick::<f64, 8, 64>::new(two).unwrap());
    let (mut ra, mut rb) = (Vec::new(), Vec::new());
    assert_eq!(a.run(|r| ra.push(r.state)), Outcome::Balanced);
    assert_eq!(b.run(|r| rb.push(r.state)), Outcome::Balanced);
    assert_eq!(ra.len(), rb.len());
    for (x, y) in ra.iter().zip(&rb) {
        assert!(
            (x.x + y.x).abs() < 1e-12 && (x.theta + y.theta).abs() < 1e-12 && (x.y - y.y).abs() < 1e-12,
            "{x:?} vs {y:?}"
        );
    }
    // The same switches at the same steps, fingers exchanged and slide directions reversed (the
    // events of one step come in contact order, so compare each step's set).
    let mirror = |m: ContactMode| match m {
        ContactMode::Sliding(Direction::Plus) => ContactMode::Sliding(Direction::Minus),
        ContactMode::Sliding(Direction::Minus) => ContactMode::Sliding(Direction::Plus),
        other => other,
    };
    let steps = |events: &[meterstick_core::planar::SwitchEvent<f64, 2>], flip: bool| {
        let mut by_step: Vec<(u64, Vec<(u8, &'static str)>)> = Vec::new();
        for e in events {
            let key = (e.time / 1e-3).round() as u64;
            let (contact, mode) = if flip { (1 - e.contact, mirror(e.mode)) } else { (e.contact, e.mode) };
            match by_step.last_mut() {
                Some((k, v)) if *k == key => v.push((contact, mode.name())),
                _ => by_step.push((key, vec![(contact, mode.name())])),
            }
        }
        for (_, v) in &mut by_step {
            v.sort_unstable();
        }
        by_step
    };
    assert_eq!(steps(a.events(), false), steps(b.events(), true));
    assert!((a.meeting().unwrap().com_offset + b.meeting().unwrap().com_offset).abs() < 1e-12);
}

/// Both fingers moving inward balance the rod too; the reduced model keeps its layout
/// (finger 1 `+d`, finger 2 `-d`) and its check never fires before the meeting.
#[test]
fn both_fingers_moving_inward_balance_the_rod() {
    for (v1, v2) in [(0.05, -0.05), (0.08, -0.02), (0.02, -0.08)] {
        let p = MeterStickParams::<f32> {
            finger1_x: -0.35,
            finger1_velocity: v1,
            finger2_velocity: v2,
            ..MeterStickParams::paper()
        };
        let mut s = MeterStick::<f32, 6, 64>::new(p).unwrap();
        assert_eq!(s.run(|_| {}), Outcome::Balanced, "v1 = {v1}, v2 = {v2}");
        assert!(s.meeting().unwrap().com_offset.abs() < 0.003, "{:?}", s.meeting());
        assert_eq!(s.reduced_check_fired_before_meeting(), 0);
        let f = s.fingers();
        assert!((f[1] - f[0] - p.finger_width).abs() < 1e-6, "the fingers stop w apart: {f:?}");
    }
}

/// A raised finger: the rod starts at rest, tilted, on both tips (the tilt is not a fall), and
/// with no finger moving it stays there carrying its weight by the torque balance about the tips.
#[test]
fn a_raised_finger_tilts_the_resting_rod() {
    let p = MeterStickParams::<f64> {
        finger1_y: 0.05,
        finger1_velocity: 0.0,
        max_time: 1.0,
        ..MeterStickParams::paper()
    };
    let rest = p.resting_state();
    assert!((rest.theta - (-0.05f64 / 0.8).atan()).abs() < 1e-15, "{rest:?}");
    let mut s = MeterStick::<f64, 8, 64>::new(p).unwrap();
    assert_eq!(s.modes(), [ContactMode::Sticking; 2]);
    let mut last = None;
    assert_eq!(s.run(|r| last = Some(*r)), Outcome::Unfinished);
    let r = last.unwrap();
    let moved = (s.state().x - rest.x).hypot(s.state().y - rest.y);
    assert!(moved < 1e-12, "moved {moved:e} m");
    // Forces and torques balance (eq. 19 on a tilted rod): the impulses' vertical parts carry the
    // weight, their horizontal parts cancel, and their moments about the centre of mass (normal
    // and friction, applied at the lower face, t/2 below the axis) add to zero.
    let (sn, cs) = rest.theta.sin_cos();
    let (n, d) = ([-sn, cs], [cs, sn]);
    let mut force = [0.0; 2];
    let mut torque = 0.0;
    for c in &r.contacts {
        let f = [
            n[0] * c.normal_impulse + d[0] * c.friction_impulse,
            n[1] * c.normal_impulse + d[1] * c.friction_impulse,
        ];
        let arm = [cs * c.along + sn * p.rod_thickness / 2.0, sn * c.along - cs * p.rod_thickness / 2.0];
        force = [force[0] + f[0], force[1] + f[1]];
        torque += arm[0] * f[1] - arm[1] * f[0];
    }
    let weight = p.rod_mass * p.gravity * p.step;
    assert!(
        (force[1] / weight - 1.0).abs() < 1e-9 && force[0].abs() < 1e-9 * weight,
        "{force:?} vs {weight}"
    );
    assert!(torque.abs() < 1e-9 * weight * p.rod_length, "torque {torque:e}");
    // Friction holds the rod from sliding down the tilt, within the cone.
    for c in &r.contacts {
        assert!(c.friction_impulse.abs() <= p.mu_static * c.normal_impulse * (1.0 + 1e-12), "{c:?}");
    }
}

/// `host-sim map` of the cylinder over slope angle x inertia ratio `k` (`--inertia-ratio`): on every
/// row the bisected boundary between Rolled (below) and Slid (above) lies at the law's angle,
/// `tan a = mu_s (1 + k) / k` (docs/scenes.md, "cylinder"), in f32 as the firmware runs and in f64.
#[test]
fn the_cylinders_map_boundary_is_the_rolling_law() {
    use meterstick_core::scene::{CylinderParams, OutcomeKind, SceneKind};
    use meterstick_host_sim::map::{Axis, Grid, compute};
    use meterstick_host_sim::scenes::{Implementation, SceneParams};
    let params = CylinderParams::default();
    let base = SceneParams::Cylinder(params);
    let axes = (
        Axis::parse("angle", SceneKind::Cylinder).unwrap(),
        Axis::parse("inertia-ratio", SceneKind::Cylinder).unwrap(),
    );
    let grid = Grid { axes, x: (10.0, 80.0), y: (0.3, 1.0), cells: [15, 5], tolerance: 1e-3, measure: None };
    for implementation in [Implementation::CORE_F32_REDUCED, Implementation::CORE_F64_FULL] {
        let map = compute(&base, &grid, implementation).unwrap();
        let boundaries = &map.summary.boundaries;
        assert_eq!(boundaries.len(), grid.cells[1], "{implementation}: one boundary per row: {boundaries:?}");
        for b in boundaries {
            let law = (params.mu_static * (1.0 + b.y) / b.y).atan().to_degrees();
            assert_eq!(
                (b.below, b.above),
                (OutcomeKind::Rolled, OutcomeKind::Slid),
                "{implementation}: {b:?}"
            );
            assert!(
                (b.x - law).abs() <= b.width + 2e-3,
                "{implementation}, k = {}: {} deg, law {law} deg",
                b.y,
                b.x
            );
        }
    }
}
