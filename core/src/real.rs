//! The scalar type the core is generic over: `f32` (microcontroller) and `f64` (host).
//!
//! [`Real`] extends [`nalgebra::RealField`] with the few things the core needs that
//! must behave identically on every target:
//! * the machine epsilon as a constant, used to scale every tolerance;
//! * `sin`/`cos`, `sqrt` and `atan` computed by the crate's own code or the `libm` crate (`sqrt`
//!   on a Cortex-M with hardware floats by its FPU, correctly rounded as `libm`'s), never the
//!   platform's C library, so a host build and a Cortex-M build of the same f32 scene
//!   perform the same IEEE operations and produce bit-identical trajectories (the firmware
//!   issue checks this with a checksum). Rust never contracts `a * b + c` into a fused
//!   multiply-add on its own, so a polynomial evaluates identically on every target.
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
    /// Size in bytes (4 or 8).
    const BYTES: usize;
    /// Converts from `f64`, rounding to nearest.
    #[must_use]
    fn of(x: f64) -> Self;
    /// Converts to `f64` (exact for both types).
    fn as_f64(self) -> f64;
    /// Converts to `f32`, rounding to nearest (used for compact diagnostics).
    fn as_f32(self) -> f32;
    /// `(sin x, cos x)`, identical on every target (`sin_cos_f32` in this module for f32, `libm::sincos`
    /// for f64).
    #[must_use]
    fn sin_cos_portable(self) -> (Self, Self);
    /// `sqrt x` correctly rounded (IEEE 754's one answer), identical on every target: `libm`'s,
    /// or on a Cortex-M with hardware floats (`eabihf`) in f32 the FPU's `vsqrt.f32`, which IEEE
    /// requires to give the same bits in 14 cycles where `libm`'s software root takes hundreds of
    /// instructions.
    #[must_use]
    fn sqrt_rounded(self) -> Self;
    /// `atan x` computed by `libm`, identical on every target.
    #[must_use]
    fn atan_libm(self) -> Self;
    /// A step count as a scalar, rounding to nearest (exact up to 2^24 in f32). `u32`, not
    /// `u64`: on Cortex-M a `u32` converts in one instruction, a `u64` through a library call.
    #[must_use]
    fn of_count(n: u32) -> Self;
    /// `|x|` by clearing the sign bit (exact; no library call).
    #[must_use]
    fn abs_exact(self) -> Self;
    /// `true` when the value is neither infinite nor NaN.
    fn finite(self) -> bool;
    /// The IEEE bits in little-endian bytes, zero-padded to 8 (the first [`Self::BYTES`] count).
    fn to_le_bytes_u64(self) -> [u8; 8];
    /// `2^k` with `2^k <= x < 2^(k+1)`, for a positive normal `x` (the mantissa bits cleared: exact,
    /// no library call).
    #[must_use]
    fn power_of_two_below(self) -> Self;
}

impl Real for f32 {
    const EPS: Self = f32::EPSILON;
    const TINY: Self = f32::MIN_POSITIVE;
    const NAME: &'static str = "f32";
    const BYTES: usize = 4;
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
    fn sin_cos_portable(self) -> (Self, Self) {
        sin_cos_f32(self)
    }
    #[inline]
    fn sqrt_rounded(self) -> Self {
        #[cfg(all(target_arch = "arm", target_abi = "eabihf"))]
        {
            let root: u32;
            // SAFETY: the value crosses in a core register, `s0` (declared clobbered) holds it for
            // `vsqrt.f32`; nothing touches memory, the stack or the condition flags (only the
            // FPSCR's cumulative exception bits, which nothing here reads).
            #[allow(unsafe_code)]
            unsafe {
                core::arch::asm!(
                    "vmov s0, {x}",
                    "vsqrt.f32 s0, s0",
                    "vmov {root}, s0",
                    x = in(reg) self.to_bits(),
                    root = lateout(reg) root,
                    out("s0") _,
                    options(pure, nomem, nostack, preserves_flags)
                );
            }
            f32::from_bits(root)
        }
        #[cfg(not(all(target_arch = "arm", target_abi = "eabihf")))]
        libm::sqrtf(self)
    }
    #[inline]
    fn atan_libm(self) -> Self {
        libm::atanf(self)
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
    #[inline]
    fn to_le_bytes_u64(self) -> [u8; 8] {
        u64::from(self.to_bits()).to_le_bytes()
    }
    #[inline]
    fn power_of_two_below(self) -> Self {
        f32::from_bits(self.to_bits() & 0xff80_0000)
    }
}

impl Real for f64 {
    const EPS: Self = f64::EPSILON;
    const TINY: Self = f64::MIN_POSITIVE;
    const NAME: &'static str = "f64";
    const BYTES: usize = 8;
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
    fn sin_cos_portable(self) -> (Self, Self) {
        libm::sincos(self)
    }
    #[inline]
    fn sqrt_rounded(self) -> Self {
        libm::sqrt(self)
    }
    #[inline]
    fn atan_libm(self) -> Self {
        libm::atan(self)
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
    #[inline]
    fn to_le_bytes_u64(self) -> [u8; 8] {
        self.to_bits().to_le_bytes()
    }
    #[inline]
    fn power_of_two_below(self) -> Self {
        f64::from_bits(self.to_bits() & 0xfff0_0000_0000_0000)
    }
}

/// `(sin x, cos x)` in f32 arithmetic alone for `|x| <= pi/4`, `libm::sincosf` beyond.
///
/// `libm::sincosf` evaluates its polynomials in f64, which a Cortex-M4F (single-precision
/// FPU) runs in software: about 1,100 instructions per call, more than the rest of a scene
/// step. The rod's angle stays below the tilt limit while a run lasts (0.35 rad by
/// default), so the scene lives in the reduced range; larger angles go to `libm`.
/// `|x| < 2^-12` gives `(x, 1)`, the correctly rounded values (as in `libm`); otherwise musl's
/// kernels `__sindf` and `__cosdf` (minimax polynomials for `[-pi/4, pi/4]`, same coefficients)
/// evaluated in f32 instead of f64: the sine's correction summed before its one addition to
/// `x`, the cosine's leading `1 - x^2/2` with its rounding error carried (as in musl's f64
/// `__cos`). Error against the f64 values on a dense grid of the range (unit test): 0.78 ulp
/// (sin) and 0.77 ulp (cos); `libm`'s f64 evaluation is within about 0.5.
///
/// Without `host-tuned` out of line: one copy per program (inlined, it is copied into every
/// caller: flash); with it inlined (a call per step costs time there, not flash).
#[cfg_attr(not(feature = "host-tuned"), inline(never))]
#[cfg_attr(feature = "host-tuned", inline)]
#[must_use]
pub(crate) fn sin_cos_f32(x: f32) -> (f32, f32) {
    // musl `__sindf.c` / `__cosdf.c`, rounded to f32.
    const S1: f32 = -0.166_666_666_416_265_24_f64 as f32;
    const S2: f32 = 0.008_333_329_385_889_463_f64 as f32;
    const S3: f32 = -0.000_198_393_348_360_966_32_f64 as f32;
    const S4: f32 = 0.000_002_718_311_493_989_822_f64 as f32;
    const C0: f32 = -0.499_999_997_251_031_f64 as f32;
    const C1: f32 = 0.041_666_623_323_739_06_f64 as f32;
    const C2: f32 = -0.001_388_676_377_460_993_f64 as f32;
    const C3: f32 = 0.000_024_390_448_796_277_41_f64 as f32;
    let a = x.abs_exact();
    if a < 1.0 / 4096.0 {
        return (x, 1.0);
    }
    if a > core::f32::consts::FRAC_PI_4 || a.is_nan() {
        // Through an opaque pointer: inlined into this opt-level-3 function, `libm`'s size-optimised
        // `sincosf` was re-expanded to 1.6 KB more flash on a Cortex-M4F; it is the cold path.
        let libm_sincosf: fn(f32) -> (f32, f32) = core::hint::black_box(libm::sincosf);
        return libm_sincosf(x);
    }
    let z = x * x;
    let w = z * z;
    let s = z * x;
    // One rounding at the end (musl adds the `S3`, `S4` terms last, which in f32 rounds twice
    // near `x`'s magnitude: 1.27 ulp at x = pi/6).
    let sin = x + s * ((S1 + z * S2) + w * (S3 + z * S4));
    // `1 + C0 z` with `C0 = -1/2` (its f32 rounding), and the rounding error of `1 - z/2`
    // (exactly `(1 - v) - z/2`, Sterbenz) carried into the sum, as musl's f64 `__cos` does.
    let half_z = -C0 * z;
    let v = 1.0 - half_z;
    let tail = w * C1 + (w * z) * (C2 + z * C3);
    let cos = v + (((1.0 - v) - half_z) + tail);
    (sin, cos)
}

/// `x - x`: exactly `+0` when `x` is finite, NaN when it is not. Added to a value, it carries the
/// finiteness of `x` into it at the cost of two operations and no branch.
#[inline]
#[allow(clippy::eq_op)] // `x - x` is the point
pub(crate) fn zero_if_finite<T: Real>(x: T) -> T {
    x - x
}

/// Whether every value added is finite, accumulated the cheapest way for the target: with a
/// floating-point unit (the host, the page, a Cortex-M4F or M33F, whose single-precision unit
/// serves the f32 the firmware computes in), [`FiniteSum`]; without one (a Cortex-M0, where a
/// subtraction is a library call), [`FiniteBits`]. The answer is the same.
#[cfg(not(all(target_os = "none", not(target_abi = "eabihf"))))]
pub(crate) type AllFinite<T> = FiniteSum<T>;
/// Whether every value added is finite: [`FiniteBits`] on a core without a floating-point unit.
#[cfg(all(target_os = "none", not(target_abi = "eabihf")))]
pub(crate) type AllFinite<T> = FiniteBits<T>;

/// Whether every value added is finite, as `sum (x - x)`: exactly `+0` while every `x` is finite
/// (`x - x` cannot overflow), NaN from the first one that is not (infinity minus infinity, or a
/// NaN), and NaN stays NaN. Two operations and no branch per value.
#[derive(Debug, Clone, Copy)]
#[cfg_attr(all(target_os = "none", not(target_abi = "eabihf")), allow(dead_code))]
pub(crate) struct FiniteSum<T>(T);

#[cfg_attr(all(target_os = "none", not(target_abi = "eabihf")), allow(dead_code))]
impl<T: Real> FiniteSum<T> {
    /// Nothing added yet: holds.
    #[inline]
    pub(crate) fn new() -> Self {
        Self(T::zero())
    }
    /// Adds `x`.
    #[inline]
    pub(crate) fn add(&mut self, x: T) {
        self.0 += zero_if_finite(x);
    }
    /// `true` when every value added is finite.
    #[inline]
    pub(crate) fn holds(self) -> bool {
        self.0.finite()
    }
}

/// Whether every value added is finite, as a conjunction of [`Real::finite`]'s bit tests.
#[derive(Debug, Clone, Copy)]
#[cfg_attr(not(all(target_os = "none", not(target_abi = "eabihf"))), allow(dead_code))]
pub(crate) struct FiniteBits<T>(bool, core::marker::PhantomData<T>);

#[cfg_attr(not(all(target_os = "none", not(target_abi = "eabihf"))), allow(dead_code))]
impl<T: Real> FiniteBits<T> {
    /// Nothing added yet: holds.
    #[inline]
    pub(crate) fn new() -> Self {
        Self(true, core::marker::PhantomData)
    }
    /// Adds `x`.
    #[inline]
    pub(crate) fn add(&mut self, x: T) {
        self.0 &= x.finite();
    }
    /// `true` when every value added is finite.
    #[inline]
    pub(crate) fn holds(self) -> bool {
        self.0
    }
}

/// `q += dq` with Kahan's compensated summation (eq. 14's `q+ = q + h v+`, every engine):
/// `carry` holds what the last sums lost and is subtracted from this one, so that a `1e-7` m
/// increment on a 1 m coordinate is not rounded away step after step.
#[inline]
pub(crate) fn compensated_add<T: Real>(q: &mut T, carry: &mut T, dq: T) {
    let increment = dq - *carry;
    let sum = *q + increment;
    *carry = (sum - *q) - increment;
    *q = sum;
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

#[cfg(test)]
mod tests {
    use super::{FiniteBits, FiniteSum, Real, sin_cos_f32};

    /// `|got - exact|` in units of the f32 ulp of `exact`'s binade, `2^(floor(log2 |exact|) - 23)`.
    fn ulps(got: f32, exact: f64) -> f64 {
        if exact == 0.0 {
            return if got == 0.0 { 0.0 } else { f64::INFINITY };
        }
        let ulp = 2f64.powi(exact.abs().log2().floor() as i32 - 23);
        (f64::from(got) - exact).abs() / ulp
    }

    #[test]
    fn sin_cos_f32_within_one_ulp_over_the_kernel_range() {
        let mut worst = (0.0f64, 0.0f64);
        let mut at = (0.0f32, 0.0f32);
        let n = 1 << 20;
        for k in 0..=n {
            // Dense in [-pi/4, pi/4], plus the kernel's edges exactly.
            let x = (-core::f32::consts::FRAC_PI_4) + (k as f32) * (core::f32::consts::FRAC_PI_2 / n as f32);
            let x = x.clamp(-core::f32::consts::FRAC_PI_4, core::f32::consts::FRAC_PI_4);
            let (s, c) = sin_cos_f32(x);
            let xd = f64::from(x);
            let (us, uc) = (ulps(s, xd.sin()), ulps(c, xd.cos()));
            if us > worst.0 {
                (worst.0, at.0) = (us, x);
            }
            if uc > worst.1 {
                (worst.1, at.1) = (uc, x);
            }
        }
        for x in [1.0 / 4096.0, -1.0 / 4096.0, 0.000_25, 1e-3, -0.1, 0.35, -0.35] {
            let (s, c) = sin_cos_f32(x);
            worst.0 = worst.0.max(ulps(s, f64::from(x).sin()));
            worst.1 = worst.1.max(ulps(c, f64::from(x).cos()));
        }
        assert!(worst.0 <= 1.0 && worst.1 <= 1.0, "worst errors (sin, cos) in ulps: {worst:?} at x = {at:?}");
    }

    #[test]
    fn sin_cos_f32_outside_the_kernel_and_special_values() {
        assert_eq!(sin_cos_f32(0.0), (0.0, 1.0));
        assert_eq!(sin_cos_f32(1e-30), (1e-30, 1.0));
        for x in [0.8f32, -1.0, 3.0, 100.0, -1e6] {
            assert_eq!(sin_cos_f32(x), libm::sincosf(x), "{x}");
        }
        let (s, c) = sin_cos_f32(f32::NAN);
        assert!(s.is_nan() && c.is_nan());
        let (s, c) = sin_cos_f32(f32::INFINITY);
        assert!(s.is_nan() && c.is_nan());
    }

    /// Both ways of [`AllFinite`] against a test of each value ([`Real::finite`]): the extremes
    /// of the range, subnormals and signed zeros hold (`x - x` does not overflow); one infinity
    /// or NaN (quiet or signalling, either sign) anywhere among finite values is caught.
    #[test]
    fn all_finite_agrees_with_a_test_of_each_value() {
        fn check<T: Real>(values: &[T]) {
            let expected = values.iter().all(|v| v.finite());
            let (mut sum, mut bits) = (FiniteSum::new(), FiniteBits::new());
            for &v in values {
                sum.add(v);
                bits.add(v);
            }
            assert_eq!(sum.holds(), expected, "sum of {values:?}");
            assert_eq!(bits.holds(), expected, "bits of {values:?}");
        }
        let finite = [0.0f32, -0.0, 1.0, -3.5, f32::MAX, f32::MIN, f32::MIN_POSITIVE, 1e-45, -1e-45];
        let bad = [f32::INFINITY, f32::NEG_INFINITY, f32::NAN, -f32::NAN, f32::from_bits(0x7f80_0001)];
        check(&finite);
        check::<f32>(&[]);
        for b in bad {
            for at in 0..=finite.len() {
                let mut values = finite.to_vec();
                values.insert(at, b);
                check(&values);
            }
        }
        let finite64 = [0.0f64, -0.0, f64::MAX, f64::MIN, 5e-324];
        check(&finite64);
        for b in [f64::INFINITY, f64::NEG_INFINITY, f64::NAN, f64::from_bits(0x7ff0_0000_0000_0001)] {
            check(&[finite64[0], b, finite64[2]]);
        }
    }
}
