//! The spatial core with several contacts (`meterstick_core::spatial::SpatialStepper<T, K, 4 K>`), each
//! with its own friction line turned to its own slip, against what is independent of the code:
//! - a tripod (three feet on a level table) sliding without turning carries the loads that the
//!   balance of its forces and moments gives (three equations, three feet: determinate), its
//!   feet in front loaded more by `mu H m g` of moment (`H` the centre of mass' height);
//! - a tripod sliding and spinning stops sliding and spinning in the same step (Farkas, Bartels,
//!   Unger & Wolf, PRL 90, 248302 (2003)), and the same launch turned about the vertical gives the
//!   turned trajectory (isotropy with coupled contacts).
//!
//! In f64 and f32.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::cast_precision_loss, clippy::print_stdout)]

use meterstick_core::Real;
use meterstick_core::spatial::{
    Body, Mode, Plane, SpatialSettings, SpatialShape, SpatialStepper, State, about, rotate,
};

const G: f64 = 9.81;
/// The tripod's feet: at radius `R` from its axis, 120 degrees apart.
const R: f64 = 0.1;
const MASS: f64 = 2.0;

/// A tripod: a ring-like body of `MASS` with three feet at radius `R` a height `height` below its
/// centre of mass, heading `heading` (rad) about the vertical, launched along its heading at
/// `speed` and spinning at `spin` about the vertical, on a table of `mu`.
fn tripod<T: Real>(height: f64, heading: f64, speed: f64, spin: f64, mu: f64) -> SpatialStepper<T, 3, 12> {
    let feet: [SpatialShape<T>; 3] = core::array::from_fn(|i| {
        let a = f64::from(u8::try_from(i).unwrap()) * 120.0_f64.to_radians();
        SpatialShape::Point { offset: [T::of(R * a.cos()), T::of(R * a.sin()), T::of(-height)] }
    });
    let (s, c) = heading.sin_cos();
    let state = State {
        position: [T::zero(), T::zero(), T::of(height)],
        orientation: about(&[T::zero(), T::zero(), T::one()], T::of(heading)),
        velocity: [T::of(speed * c), T::of(speed * s), T::zero()],
        angular_velocity: [T::zero(), T::zero(), T::of(spin)],
    };
    // A thin ring's moments: m R^2 / 2 about a diameter, m R^2 about its axis.
    let body = Body {
        mass: T::of(MASS),
        inertia: [T::of(0.5 * MASS * R * R), T::of(0.5 * MASS * R * R), T::of(MASS * R * R)],
    };
    SpatialStepper::new(body, feet, Plane::table(T::zero(), T::of(mu)), SpatialSettings::default(), state)
        .unwrap()
}

/// The loads of three feet at `(x_i, y_i)` under a body of weight `w` whose friction `mu w`
/// opposes its slide along `+x` at height `height` below the centre of mass: `sum N = w`, `sum N
/// y = 0`, `sum N x = mu height w` (no pitch, no roll), by Cramer's rule.
fn balanced_loads(feet: [[f64; 2]; 3], w: f64, mu: f64, height: f64) -> [f64; 3] {
    let m = [[1.0, 1.0, 1.0], feet.map(|f| f[1]), feet.map(|f| f[0])];
    let b = [w, 0.0, mu * height * w];
    let det = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let d = det(m);
    core::array::from_fn(|k| {
        let mut mk = m;
        for (row, bi) in mk.iter_mut().zip(b) {
            row[k] = bi;
        }
        det(mk) / d
    })
}

fn loads<T: Real>(tolerance: f64) {
    let (height, mu, h) = (0.05, 0.4, 1e-3);
    let mut t = tripod::<T>(height, 0.0, 2.0, 0.0, mu);
    let feet = core::array::from_fn(|i| {
        let a = f64::from(u8::try_from(i).unwrap()) * 120.0_f64.to_radians();
        [R * a.cos(), R * a.sin()]
    });
    let law = balanced_loads(feet, MASS * G, mu, height);
    // The first step lands it; the sliding steps after carry the balance.
    t.step().unwrap();
    for _ in 0..100 {
        let r = t.step().unwrap();
        for (i, c) in r.contacts.iter().enumerate() {
            assert_eq!(c.mode, Mode::Sliding, "foot {i}: {c:?}");
            let load = c.normal_impulse.as_f64() / h;
            assert!(
                (load - law[i]).abs() <= tolerance * MASS * G,
                "foot {i}: {load} N, balance {} N",
                law[i]
            );
            // Each foot's friction is `mu` times its load, against the slide: to the load's
            // tolerance, or to the LCP's verification (`1024 eps` of the step's scale, within
            // `4096 eps` of the cone) where that is looser (f32).
            let cone = tolerance.max(4096.0 * T::EPS.as_f64()) * mu * load * h;
            let friction = c.friction_impulse.map(Real::as_f64);
            assert!((friction[0] + mu * load * h).abs() <= cone, "foot {i}: {friction:?}");
            assert!(friction[1].abs() <= cone, "foot {i}: {friction:?}");
        }
    }
    println!("tripod loads {law:?} N (front foot first)");
}

#[test]
fn a_sliding_tripod_carries_the_loads_its_balance_gives() {
    loads::<f64>(1e-9);
    loads::<f32>(1e-5);
}

/// Runs a tripod launched at `speed` with `spin` on its heading until it sticks; returns the step
/// each foot's sliding ended (the centre's speed and spin both below the stick speed's scale) and
/// the final position turned back by `heading`.
fn spin_and_slide<T: Real>(heading: f64, speed: f64, spin: f64) -> (u32, u32, [f64; 3], [f64; 3]) {
    let mut t = tripod::<T>(0.0, heading, speed, spin, 0.3);
    let (mut slide_stop, mut spin_stop) = (None, None);
    for k in 1..=20_000u32 {
        let r = t.step().unwrap();
        let v = r.state.velocity.map(Real::as_f64);
        let w = r.state.angular_velocity.map(Real::as_f64)[2];
        if slide_stop.is_none() && v[0].hypot(v[1]) < 1e-4 {
            slide_stop = Some(k);
        }
        if spin_stop.is_none() && (w * R).abs() < 1e-4 {
            spin_stop = Some(k);
        }
        if r.contacts.iter().all(|c| c.mode == Mode::Sticking) {
            break;
        }
    }
    let back = about(&[T::zero(), T::zero(), T::one()], T::of(-heading));
    let s = t.state();
    let p = rotate(&back, &s.position).map(Real::as_f64);
    let turn = rotate(&back, &rotate(&s.orientation, &[T::one(), T::zero(), T::zero()]));
    (slide_stop.expect("it stops sliding"), spin_stop.expect("it stops spinning"), p, turn.map(Real::as_f64))
}

/// `tolerance` for where the tripod ends (relative to its travel), `turn` for the direction its
/// axis ends in.
fn farkas<T: Real>(tolerance: f64, turn: f64) {
    for (speed, spin) in [(1.0, 5.0), (0.5, 20.0), (2.0, 2.0)] {
        let (slide, spin_end, p0, x0) = spin_and_slide::<T>(0.0, speed, spin);
        println!(
            "tripod at {speed} m/s, {spin} rad/s: slides {slide} steps, spins {spin_end}; ends at {p0:?}"
        );
        assert!(slide.abs_diff(spin_end) <= 2, "sliding stops at step {slide}, spinning at {spin_end}");
        for heading in [0.3, 1.7, -2.5] {
            let (s, w, p, x) = spin_and_slide::<T>(heading, speed, spin);
            assert!(
                s.abs_diff(slide) <= 1 && w.abs_diff(spin_end) <= 1,
                "heading {heading}: {s} / {w} steps"
            );
            let scale = p0[0].hypot(p0[1]).max(R);
            for k in 0..3 {
                assert!((p[k] - p0[k]).abs() <= tolerance * scale, "heading {heading}: {p:?} against {p0:?}");
                assert!((x[k] - x0[k]).abs() <= turn, "heading {heading}: axis {x:?} against {x0:?}");
            }
        }
    }
}

#[test]
fn a_spinning_tripod_stops_sliding_and_spinning_together_in_every_heading() {
    farkas::<f64>(1e-9, 1e-9);
    // In f32 each step's turn rounds the quaternion in its last place: over ~700 steps of
    // spinning, 1.6e-5 of the axis' direction apart (the position stays within 3.2e-6).
    farkas::<f32>(1e-5, 1e-4);
}
