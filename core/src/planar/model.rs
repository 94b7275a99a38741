//! What a [`super::Stepper`] moves ([`Model`]: the body, its contacts, the [`Settings`]) and the
//! checks of its set-up ([`validate`]): every value finite and in range, `mu_k <= mu_s`, each
//! support able to carry its contact's feature (`docs/formulation.md`, "The body", "Contacts").

use super::body::{Body, BodyState};
use super::contact::{Contact, Feature, Support};
use crate::params::ParamError;
use crate::real::Real;

/// The stepper's numbers, besides the body and its contacts.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Settings<T> {
    /// Time step `h` (s, > 0).
    pub step: T,
    /// Gravity `g` along `-y` (m/s^2, >= 0).
    pub gravity: T,
    /// A touching contact whose slip speed is at most this sticks (m/s, >= 0).
    pub stick_speed: T,
}

/// What the stepper moves: the body, its contacts and the numbers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Model<T, const K: usize> {
    /// The body.
    pub body: Body<T>,
    /// Its contacts, in the order of the LCP's variables.
    pub contacts: [Contact<T>; K],
    /// Step, gravity, thresholds.
    pub settings: Settings<T>,
}

/// The set-up checks of [`super::Stepper::new`].
pub(crate) fn validate<T: Real, const K: usize>(
    model: &Model<T, K>,
    start: &BodyState<T>,
    supports: &[Support<T>; K],
) -> Result<(), ParamError> {
    use crate::params::{Check, check_fields};
    let (b, s) = (&model.body, &model.settings);
    check_fields(&[
        ("width", b.width, Check::Positive),
        ("height", b.height, Check::NonNegative),
        ("mass", b.mass, Check::Positive),
        ("inertia", b.inertia, Check::Positive),
        ("step", s.step, Check::Positive),
        ("gravity", s.gravity, Check::NonNegative),
        ("stick_speed", s.stick_speed, Check::NonNegative),
    ])?;
    for (i, c) in model.contacts.iter().enumerate() {
        check_fields(&[
            ("mu_static", c.mu_static, Check::NonNegative),
            ("mu_kinetic", c.mu_kinetic, Check::NonNegative),
        ])?;
        if c.mu_kinetic > c.mu_static {
            return Err(ParamError::KineticAboveStatic);
        }
        if let Feature::Point(p) = c.feature
            && !(p[0].finite() && p[1].finite())
        {
            return Err(ParamError::NonFinite("feature"));
        }
        if let Feature::Round(radius) = c.feature {
            check_fields(&[("radius", radius, Check::Positive)])?;
        }
        let sup = &supports[i];
        if !sup.fits(&c.feature) {
            return Err(ParamError::SupportMismatch(i as u8));
        }
        let mut values = [
            sup.position()[0],
            sup.position()[1],
            sup.velocity()[0],
            sup.velocity()[1],
            T::zero(),
            T::zero(),
        ];
        if let Support::Line { normal, .. } = sup {
            values[4] = normal[0];
            values[5] = normal[1];
        }
        if !values.iter().all(|v| v.finite()) {
            return Err(ParamError::NonFinite("support"));
        }
        if !sup.is_well_formed() {
            return Err(ParamError::OutOfRange("support")); // a line's normal not a unit vector
        }
    }
    if !start.is_finite() {
        return Err(ParamError::NonFiniteState);
    }
    Ok(())
}
