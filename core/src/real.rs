//! The scalar type the core is generic over: `f32` (microcontroller) and `f64` (host).
//!
//! [`Real`] extends [`nalgebra::RealField`] with the few things the core needs that
//! must behave identically on every target:
//! * the machine epsilon as a constant, used to scale every tolerance;
//! * `sin`/`cos` and `sqrt` through the `libm` crate, never the platform's C library, so a host build
//!   and a Cortex-M build of the same f32 scene perform the same IEEE operations and
//!   produce bit-identical trajectories (the firmware issue checks this with a checksum).
//!
//! The trait is sealed: only `f32` and `f64` implement it.

use nalgebra::RealField;

mod sealed {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
}

/// A floating-point scalar the core can compute in: `f32` or `f64`.
pub trait Real: RealField + Copy + sealed::Sealed {
    /// Machine epsilon of the type (`f32::EPSILON` or `f64::EPSILON`).
    const EPS: Self;
    /// The smallest positive normal value, used as a floor for scales that may be zero.
    const TINY: Self;
    /// Short name of the type, `"f32"` or `"f64"`.
    const NAME: &'static str;
    /// Converts from `f64`, rounding to nearest.
    #[must_use]
    fn of(x: f64) -> Self;
    /// Converts to `f64` (exact for both types).
    fn as_f64(self) -> f64;
    /// Converts to `f32`, rounding to nearest (used for compact diagnostics).
    fn as_f32(self) -> f32;
    /// `(sin x, cos x)` computed by `libm`, identical on every target.
    #[must_use]
    fn sin_cos_libm(self) -> (Self, Self);
    /// `sqrt x` computed by `libm` (correctly rounded), identical on every target.
    #[must_use]
    fn sqrt_libm(self) -> Self;
    /// A step count as a scalar, rounding to nearest (exact up to 2^24 in f32). `u32`, not
    /// `u64`: on Cortex-M a `u32` converts in one instruction, a `u64` through a library call.
    #[must_use]
    fn of_count(n: u32) -> Self;
    /// `|x|` by clearing the sign bit (exact; no library call).
    #[must_use]
    fn abs_exact(self) -> Self;
    /// `true` when the value is neither infinite nor NaN.
    fn finite(self) -> bool;
}

impl Real for f32 {
    const EPS: Self = f32::EPSILON;
    const TINY: Self = f32::MIN_POSITIVE;
    const NAME: &'static str = "f32";
    #[inline]
    fn of(x: f64) -> Self {
        x as f32
    }
    #[inline]
    fn as_f64(self) -> f64 {
        f64::from(self)
    }
    #[inline]
    fn as_f32(self) -> f32 {
        self
    }
    #[inline]
    fn sin_cos_libm(self) -> (Self, Self) {
        libm::sincosf(self)
    }
    #[inline]
    fn sqrt_libm(self) -> Self {
        libm::sqrtf(self)
    }
    #[inline]
    fn of_count(n: u32) -> Self {
        n as f32
    }
    #[inline]
    fn abs_exact(self) -> Self {
        f32::from_bits(self.to_bits() & 0x7fff_ffff)
    }
    #[inline]
    fn finite(self) -> bool {
        self.is_finite()
    }
}

impl Real for f64 {
    const EPS: Self = f64::EPSILON;
    const TINY: Self = f64::MIN_POSITIVE;
    const NAME: &'static str = "f64";
    #[inline]
    fn of(x: f64) -> Self {
        x
    }
    #[inline]
    fn as_f64(self) -> f64 {
        self
    }
    #[inline]
    fn as_f32(self) -> f32 {
        self as f32
    }
    #[inline]
    fn sin_cos_libm(self) -> (Self, Self) {
        libm::sincos(self)
    }
    #[inline]
    fn sqrt_libm(self) -> Self {
        libm::sqrt(self)
    }
    #[inline]
    fn of_count(n: u32) -> Self {
        f64::from(n)
    }
    #[inline]
    fn abs_exact(self) -> Self {
        f64::from_bits(self.to_bits() & 0x7fff_ffff_ffff_ffff)
    }
    #[inline]
    fn finite(self) -> bool {
        self.is_finite()
    }
}

/// `max(a, b)` for partially ordered scalars (NaN-free inputs).
#[inline]
pub(crate) fn max<T: Real>(a: T, b: T) -> T {
    if a > b { a } else { b }
}

/// `min(a, b)` for partially ordered scalars (NaN-free inputs).
#[inline]
pub(crate) fn min<T: Real>(a: T, b: T) -> T {
    if a < b { a } else { b }
}
