//! What a [`super::Stepper`] moves ([`Model`]: the body, its contacts, the [`Settings`]) and the
//! checks of its set-up ([`validate`]): every value finite and in range, `mu_k <= mu_s`, each
//! support able to carry its contact's feature (`docs/formulation.md`, "The body", "Contacts").

use super::body::{Body, BodyState};
use super::contact::{Contact, Feature, Support};
use crate::params::{Check, ParamError, check_fields};
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

impl<T: Real> Body<T> {
    /// The body's fields as [`validate`] checks them ([`check_fields`]): `width`, `mass` and
    /// `inertia` positive, `height` not negative (a rod may be a line).
    pub(crate) fn fields(&self) -> [(&'static str, T, Check); 4] {
        [
            ("width", self.width, Check::Positive),
            ("height", self.height, Check::NonNegative),
            ("mass", self.mass, Check::Positive),
            ("inertia", self.inertia, Check::Positive),
        ]
    }
}

impl<T: Real> Settings<T> {
    /// The settings' fields as [`validate`] checks them ([`check_fields`]): `step` positive,
    /// `gravity` and `stick_speed` not negative.
    pub(crate) fn fields(&self) -> [(&'static str, T, Check); 3] {
        [
            ("step", self.step, Check::Positive),
            ("gravity", self.gravity, Check::NonNegative),
            ("stick_speed", self.stick_speed, Check::NonNegative),
        ]
    }
}

/// A contact's friction coefficients: both finite and not negative, `mu_kinetic <= mu_static`.
///
/// # Errors
/// [`ParamError::NonFinite`] or [`ParamError::Negative`] naming `mu_static` or `mu_kinetic`,
/// [`ParamError::KineticAboveStatic`].
pub(crate) fn check_friction<T: Real>(mu_static: T, mu_kinetic: T) -> Result<(), ParamError> {
    check_fields(&[
        ("mu_static", mu_static, Check::NonNegative),
        ("mu_kinetic", mu_kinetic, Check::NonNegative),
    ])?;
    if mu_kinetic > mu_static { Err(ParamError::KineticAboveStatic) } else { Ok(()) }
}

/// The set-up checks of [`super::Stepper::new`].
pub(crate) fn validate<T: Real, const K: usize>(
    model: &Model<T, K>,
    start: &BodyState<T>,
    supports: &[Support<T>; K],
) -> Result<(), ParamError> {
    let ([width, height, mass, inertia], [step, gravity, stick_speed]) =
        (model.body.fields(), model.settings.fields());
    check_fields(&[width, height, mass, inertia, step, gravity, stick_speed])?;
    for (i, c) in model.contacts.iter().enumerate() {
        check_friction(c.mu_static, c.mu_kinetic)?;
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
