//! The load of a flat base (`meterstick_core::spatial`, "The load"; `docs/formulation.md`, "The load:
//! the least norm"): four or more coplanar points of one rigid body leave its normal load open, and
//! the core takes the least-norm one, the load elasticity gives equally stiff points (Menabrea):
//! - a ring of `n` feet sliding without turning, its centre of mass a height `H` above them,
//!   carries `N_i = W (1 / n + 2 mu H x_i / (n R^2))` (the least `sum N_i^2` with `sum N = W`,
//!   `sum N y = 0`, `sum N x = mu H W`: affine in the feet's positions); uniform when `H = 0`;
//! - every foot's friction is `mu N_i` against its slip, the circular cone held.
//!
//! In f64 and f32.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, clippy::cast_precision_loss)]

use meterstick_core::Real;
use meterstick_core::spatial::{
    Body, Mode, Plane, SpatialSettings, SpatialShape, SpatialStepper, State, about,
};

const G: f64 = 9.81;
const R: f64 = 0.1;
const MASS: f64 = 2.0;

/// A ring of `n` feet (`n <= 8`) at radius `R`, `height` below the centre of mass, turned by `turn`
/// about the vertical, sliding along `+x` at `speed` and spinning at `spin`.
fn ring<T: Real>(
    n: usize,
    height: f64,
    turn: f64,
    speed: f64,
    spin: f64,
    mu: f64,
) -> SpatialStepper<T, 8, 32> {
    let feet: [SpatialShape<T>; 8] = core::array::from_fn(|i| {
        if i >= n {
            return SpatialShape::Unused;
        }
        let a = std::f64::consts::TAU * i as f64 / n as f64;
        SpatialShape::Point { offset: [T::of(R * a.cos()), T::of(R * a.sin()), T::of(-height)] }
    });
    let state = State {
        position: [T::zero(), T::zero(), T::of(height)],
        orientation: about(&[T::zero(), T::zero(), T::one()], T::of(turn)),
        velocity: [T::of(speed), T::zero(), T::zero()],
        angular_velocity: [T::zero(), T::zero(), T::of(spin)],
    };
    let body = Body {
        mass: T::of(MASS),
        inertia: [T::of(0.5 * MASS * R * R), T::of(0.5 * MASS * R * R), T::of(MASS * R * R)],
    };
    SpatialStepper::new(body, feet, Plane::table(T::zero(), T::of(mu)), SpatialSettings::default(), state)
        .unwrap()
}

fn menabrea<T: Real>(tolerance: f64) {
    let (mu, h) = (0.4, 1e-3);
    for n in [4, 5, 6, 8] {
        for height in [0.0, 0.03] {
            for turn in [0.0, 0.37, 1.1, 2.9] {
                let mut t = ring::<T>(n, height, turn, 2.0, 0.0, mu);
                for k in 0..50 {
                    let r = t
                        .step()
                        .unwrap_or_else(|e| panic!("{n} feet, H {height}, turn {turn}, step {k}: {e:?}"));
                    let w = MASS * G;
                    for (i, c) in r.contacts.iter().enumerate().take(n) {
                        assert_eq!(c.mode, Mode::Sliding, "{n} feet, foot {i}: {c:?}");
                        let x = R * (std::f64::consts::TAU * i as f64 / n as f64 + turn).cos();
                        let law = w * (1.0 / n as f64 + 2.0 * mu * height * x / (n as f64 * R * R));
                        let load = c.normal_impulse.as_f64() / h;
                        assert!(
                            (load - law).abs() <= tolerance * w,
                            "{n} feet, H {height}, turn {turn}, foot {i}: {load} N, Menabrea {law} N"
                        );
                        let friction = c.friction_impulse.map(Real::as_f64);
                        let cone = tolerance.max(4096.0 * T::EPS.as_f64()) * mu * w * h;
                        assert!((friction[0] + mu * load * h).abs() <= cone, "foot {i}: {friction:?}");
                        assert!(friction[1].abs() <= cone, "foot {i}: {friction:?}");
                        assert!(c.cone_residual.as_f64() <= 4096.0 * T::EPS.as_f64(), "{c:?}");
                    }
                }
            }
        }
    }
}

#[test]
fn a_sliding_flat_base_carries_the_least_norm_load() {
    menabrea::<f64>(1e-9);
    menabrea::<f32>(1e-5);
}
