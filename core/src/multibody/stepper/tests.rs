//! [`SystemStepper::new`] refuses a system it cannot step, each by its [`ParamError`], before any
//! step: every field of its contract broken once, the rest valid.

use super::*;
use crate::multibody::RestsOn;

/// Two boxes, one on the other, on a floor, pulled: the valid system every case breaks once.
fn pulled_pair() -> (System<f64, 2, 2>, [BodyState<f64>; 2]) {
    let block = Body::block(1.0, 0.2, 0.1);
    let system = System {
        bodies: [block; 2],
        table: Table::floor(),
        pairs: [Pair::boxed(0, RestsOn::Table, 0.5, 0.4), Pair::boxed(1, RestsOn::Body(0), 0.5, 0.4)],
        forces: [[5.0, 0.0], [0.0; 2]],
        settings: SystemSettings {
            base: crate::planar::Settings { step: 1e-3, gravity: 9.81, stick_speed: 1e-5 },
            margin: 1e-3,
        },
    };
    (system, [BodyState::at_rest(0.0, 0.05, 0.0), BodyState::at_rest(0.0, 0.15, 0.0)])
}

/// `pulled_pair` changed by `change`: `SystemStepper::new`'s error, `None` when it builds.
fn refusal(change: impl FnOnce(&mut System<f64, 2, 2>, &mut [BodyState<f64>; 2])) -> Option<ParamError> {
    let (mut system, mut states) = pulled_pair();
    change(&mut system, &mut states);
    SystemStepper::<f64, 2, 2, 24>::new(system, states).err()
}

#[test]
fn the_valid_system_builds_and_steps() {
    assert_eq!(refusal(|_, _| {}), None);
    let (system, states) = pulled_pair();
    let mut stepper = SystemStepper::<f64, 2, 2, 24>::new(system, states).expect("valid");
    assert!(stepper.step().is_ok());
}

#[test]
fn a_body_without_a_positive_finite_mass_inertia_or_size_is_refused() {
    assert_eq!(refusal(|s, _| s.bodies[1].mass = -1.0), Some(ParamError::NotPositive("mass")));
    assert_eq!(refusal(|s, _| s.bodies[0].mass = 0.0), Some(ParamError::NotPositive("mass")));
    assert_eq!(refusal(|s, _| s.bodies[1].mass = f64::NAN), Some(ParamError::NonFinite("mass")));
    assert_eq!(refusal(|s, _| s.bodies[1].inertia = 0.0), Some(ParamError::NotPositive("inertia")));
    assert_eq!(refusal(|s, _| s.bodies[0].inertia = f64::INFINITY), Some(ParamError::NonFinite("inertia")));
    assert_eq!(refusal(|s, _| s.bodies[1].width = -0.2), Some(ParamError::NotPositive("width")));
    // A planar body's height may be 0 (a rod as a line); a box's may not.
    assert_eq!(refusal(|s, _| s.bodies[1].height = 0.0), Some(ParamError::NotPositive("height")));
    assert_eq!(
        refusal(|s, _| s.bodies[1].inertia = 1e-310),
        Some(ParamError::InertiaOutOfRange { mass: "mass", size: "width" })
    );
}

/// `M~` is per body 0's mass: a ratio whose quotient leaves `T`'s range is refused.
#[test]
fn masses_whose_ratio_leaves_the_range_are_refused() {
    let ratio = |s: &mut System<f64, 2, 2>, _: &mut _| {
        s.bodies[0] = Body::block(1e300, 0.2, 0.1);
        s.bodies[1] = Body::block(1e-20, 0.2, 0.1);
    };
    assert_eq!(refusal(ratio), Some(ParamError::OutOfRange("mass")));
}

#[test]
fn a_step_that_is_not_positive_and_finite_is_refused() {
    assert_eq!(refusal(|s, _| s.settings.base.step = -1e-3), Some(ParamError::NotPositive("step")));
    assert_eq!(refusal(|s, _| s.settings.base.step = 0.0), Some(ParamError::NotPositive("step")));
    assert_eq!(refusal(|s, _| s.settings.base.step = f64::NAN), Some(ParamError::NonFinite("step")));
    assert_eq!(refusal(|s, _| s.settings.base.gravity = -9.81), Some(ParamError::Negative("gravity")));
    assert_eq!(refusal(|s, _| s.settings.base.stick_speed = -1.0), Some(ParamError::Negative("stick_speed")));
    assert_eq!(refusal(|s, _| s.settings.margin = -1e-3), Some(ParamError::Negative("margin")));
    assert_eq!(refusal(|s, _| s.settings.margin = f64::INFINITY), Some(ParamError::NonFinite("margin")));
}

#[test]
fn friction_outside_zero_to_mu_static_is_refused() {
    assert_eq!(refusal(|s, _| s.pairs[1].mu_kinetic = 0.6), Some(ParamError::KineticAboveStatic));
    assert_eq!(refusal(|s, _| s.pairs[0].mu_static = -0.1), Some(ParamError::Negative("mu_static")));
    assert_eq!(refusal(|s, _| s.pairs[1].mu_kinetic = -0.1), Some(ParamError::Negative("mu_kinetic")));
    assert_eq!(refusal(|s, _| s.pairs[1].mu_static = f64::NAN), Some(ParamError::NonFinite("mu_static")));
    // Frictionless and `mu_k = mu_s` are valid.
    assert_eq!(refusal(|s, _| s.pairs[1] = Pair::boxed(1, RestsOn::Body(0), 0.0, 0.0)), None);
    assert_eq!(refusal(|s, _| s.pairs[1].mu_kinetic = 0.5), None);
}

#[test]
fn a_table_forces_or_states_that_are_not_finite_are_refused() {
    assert_eq!(refusal(|s, _| s.table.hi = Some(f64::NAN)), Some(ParamError::NonFinite("table")));
    assert_eq!(
        refusal(|s, _| s.table = Table { lo: Some(0.5), hi: Some(-0.5) }),
        Some(ParamError::OutOfRange("table"))
    );
    assert_eq!(refusal(|s, _| s.table = Table { lo: Some(-0.5), hi: Some(0.5) }), None);
    assert_eq!(refusal(|s, _| s.forces[1][1] = f64::INFINITY), Some(ParamError::NonFinite("forces")));
    assert_eq!(refusal(|_, st| st[1].omega = f64::NAN), Some(ParamError::NonFiniteState));
}

#[test]
fn pairs_naming_no_body_are_refused() {
    assert_eq!(refusal(|s, _| s.pairs[1].upper = 2), Some(ParamError::OutOfRange("pairs")));
    assert_eq!(refusal(|s, _| s.pairs[1].lower = RestsOn::Body(1)), Some(ParamError::OutOfRange("pairs")));
}

/// The step's checks are the constructor's: `f32` refuses the same way.
#[test]
fn f32_refuses_as_f64() {
    let (system, states) = pulled_pair();
    let mut system = System {
        bodies: system.bodies.map(|b| Body::block(b.mass as f32, b.width as f32, b.height as f32)),
        table: Table::floor(),
        pairs: system.pairs.map(|p| Pair::boxed(p.upper, p.lower, 0.5_f32, 0.4)),
        forces: [[5.0, 0.0], [0.0; 2]],
        settings: SystemSettings {
            base: crate::planar::Settings { step: 1e-3, gravity: 9.81, stick_speed: 1e-5 },
            margin: 1e-3,
        },
    };
    let states = states.map(|s| BodyState::at_rest(s.x as f32, s.y as f32, 0.0));
    assert!(SystemStepper::<f32, 2, 2, 24>::new(system, states).is_ok());
    system.settings.base.step = -1e-3;
    assert_eq!(
        SystemStepper::<f32, 2, 2, 24>::new(system, states).err(),
        Some(ParamError::NotPositive("step"))
    );
}
