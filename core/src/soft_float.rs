//! Single-precision multiplication on the bits, for cores without a floating-point unit whose
//! multiplier has no 64-bit result (Cortex-M0/M0+).
//!
//! There `f32 * f32` is a library call, and `compiler_builtins`' generic one forms the 48-bit
//! product of the significands with a full 64 x 64-bit multiplication (`__aeabi_lmul`): on the
//! emulated Cortex-M0 that multiplication and its call were 46 % of every instruction a scene step
//! executes. [`mul_normal`] forms the product from four 12 x 12-bit partial products, each of
//! which fits the core's 32-bit `muls`, in 32-bit words, and rounds it as IEEE 754 does (to nearest, ties to
//! even), so its result is bit for bit that of any conforming multiplication; it takes the common
//! case only (normal operands, normal product) and leaves the rest (zeros, subnormals,
//! infinities, NaNs, overflow, underflow) to a complete implementation. The firmware installs it
//! as `__aeabi_fmul` on the Cortex-M0 (`firmware/src/soft_float.rs`); its tests compare it with
//! the host's multiplication.

/// `a * b` for binary32 bit patterns `a`, `b`: the product's bits when both are normal and
/// finite and the product is too, rounded to nearest, ties to even (IEEE 754), or when one is a
/// zero and the other finite; `None` in every other case, for a complete implementation to
/// handle.
#[must_use]
#[inline]
pub fn mul_normal(a: u32, b: u32) -> Option<u32> {
    let sign = (a ^ b) & SIGN;
    let ea = (a >> 23) & 0xff;
    let eb = (b >> 23) & 0xff;
    // An exponent field of 0 (zero, subnormal) or 255 (infinity, NaN): a zero times a finite
    // number is a zero of the product's sign; the rest is not taken here.
    if ea.wrapping_sub(1) >= 0xfe || eb.wrapping_sub(1) >= 0xfe {
        let zero = |x: u32| x & !SIGN == 0;
        return ((zero(a) && eb != 0xff) || (zero(b) && ea != 0xff)).then_some(sign);
    }
    let sa = (a & FRACTION) | HIDDEN;
    let sb = (b & FRACTION) | HIDDEN;
    // The 48-bit product of the 24-bit significands as `hi 2^24 + lo`, from 12-bit halves: every
    // partial product and sum fits in 32 bits, and every shift is by a constant (no 64-bit
    // arithmetic, which the core would do in library calls).
    let (ah, al, bh, bl) = (sa >> 12, sa & 0xfff, sb >> 12, sb & 0xfff);
    let mid = ah * bl + al * bh; // < 2^25
    let lo_sum = al * bl + ((mid & 0xfff) << 12); // < 2^25
    let mut hi = ah * bh + (mid >> 12) + (lo_sum >> 24); // in [2^22, 2^24)
    let mut lo = lo_sum & 0xff_ffff;
    // The exponent field of the product, before rounding, is `ea + eb - 127`, plus one when the
    // product of the significands reaches 2; otherwise the product is shifted up one bit.
    let mut e = ea + eb;
    if hi >= HIDDEN {
        e += 1;
    } else {
        hi = (hi << 1) | (lo >> 23);
        lo = (lo << 1) & 0xff_ffff;
    }
    if e.wrapping_sub(128) >= 254 {
        // A subnormal (or zero) product rounds at a coarser place; beyond 2^128 it overflows.
        return None;
    }
    // Round to nearest, ties to even: `lo` is the remainder in units of 2^-24 of the last place.
    let m = hi + ((lo + (hi & 1) + 0x7f_ffff) >> 24);
    // A significand rounded up to 2^24 carries into the exponent field by the addition.
    let bits = ((e - 128) << 23) + m;
    (bits < INFINITY).then_some(sign | bits)
}

/// `a + b` for binary32 bit patterns `a`, `b`: the sum's bits when both are normal and finite
/// and the sum is normal or exactly zero, rounded to nearest, ties to even (IEEE 754), or when one
/// is a zero and the other finite; `None` in every other case, for a complete implementation to
/// handle.
#[must_use]
#[inline]
pub fn add_normal(a: u32, b: u32) -> Option<u32> {
    // The larger magnitude first: the sum has its sign and, before normalisation, its exponent.
    let (a, b) = if a & !SIGN >= b & !SIGN { (a, b) } else { (b, a) };
    let ea = (a >> 23) & 0xff;
    let eb = (b >> 23) & 0xff;
    if ea.wrapping_sub(1) >= 0xfe || eb.wrapping_sub(1) >= 0xfe {
        // A finite number plus a zero is that number (`|a| >= |b|`: the zero is `b`); two zeros
        // sum to -0 only when both are -0.
        if b & !SIGN == 0 && ea != 0xff {
            return Some(if a & !SIGN == 0 { a & b } else { a });
        }
        return None;
    }
    let d = ea - eb;
    if d > 25 {
        // |b| < 2^-25 |a| <= a quarter of a's last place (half of it below a power of two).
        return Some(a);
    }
    // Significands with six bits below the last place, the larger in [2^29, 2^30); the bits of
    // the smaller shifted out are kept as one sticky bit (the result's rounding sees them).
    let ma = ((a & FRACTION) | HIDDEN) << 6;
    let mb = ((b & FRACTION) | HIDDEN) << 6;
    let mb = (mb >> d) | u32::from(mb << (31 - d) << 1 != 0);
    let mut e = ea;
    let mut m;
    if (a ^ b) & SIGN == 0 {
        m = ma + mb; // < 2^31
        if m >= 1 << 30 {
            m = (m >> 1) | (m & 1);
            e += 1;
        }
    } else {
        m = ma - mb;
        if m == 0 {
            return Some(0); // x - x is +0 when rounding to nearest
        }
        // Cancellation of more than one bit happens only when d <= 1, where `mb` is exact.
        while m < 1 << 29 {
            if e == 1 {
                return None; // a subnormal sum
            }
            m <<= 1;
            e -= 1;
        }
    }
    let hi = m >> 6;
    let m = hi + (((m & 0x3f) + (hi & 1) + 0x1f) >> 6);
    let bits = ((e - 1) << 23) + m;
    (bits < INFINITY).then_some((a & SIGN) | bits)
}

const SIGN: u32 = 0x8000_0000;
const HIDDEN: u32 = 0x80_0000;
const FRACTION: u32 = 0x7f_ffff;
const INFINITY: u32 = 0x7f80_0000;

#[cfg(test)]
mod tests {
    use super::{add_normal, mul_normal};
    use proptest::prelude::*;

    /// Where [`add_normal`] answers, its answer is the host's IEEE sum, bit for bit.
    fn adds(a: u32, b: u32) -> bool {
        match add_normal(a, b) {
            Some(bits) => bits == (f32::from_bits(a) + f32::from_bits(b)).to_bits(),
            None => true,
        }
    }

    /// It declines only sums with an operand or a result outside the normal range (a zero sum
    /// of normal operands it answers).
    fn adds_all_but_the_rare(a: u32, b: u32) -> bool {
        let (x, y) = (f32::from_bits(a), f32::from_bits(b));
        let s = x + y;
        let zero_and_finite = |p: f32, q: f32| p == 0.0 && q.is_finite();
        add_normal(a, b).is_some()
            || !((x.is_normal() && y.is_normal() && (s.is_normal() || s == 0.0))
                || zero_and_finite(x, y)
                || zero_and_finite(y, x))
    }

    /// Where [`mul_normal`] answers, its answer is the host's IEEE product, bit for bit.
    fn agrees(a: u32, b: u32) -> bool {
        match mul_normal(a, b) {
            Some(bits) => bits == (f32::from_bits(a) * f32::from_bits(b)).to_bits(),
            None => true,
        }
    }

    /// What it declines is only what it says it declines.
    fn declines_only_the_rare(a: u32, b: u32) -> bool {
        let (x, y) = (f32::from_bits(a), f32::from_bits(b));
        let p = x * y;
        mul_normal(a, b).is_some() || !(x.is_normal() && y.is_normal() && p.is_normal())
            && !((x == 0.0 && y.is_finite()) || (y == 0.0 && x.is_finite()))
            // a product that is normal only after rounding up from below the normal range
            || p.abs().to_bits() == f32::MIN_POSITIVE.to_bits()
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 200_000, ..ProptestConfig::default() })]
        #[test]
        fn random_bit_patterns(a in any::<u32>(), b in any::<u32>()) {
            prop_assert!(agrees(a, b), "{a:08x} * {b:08x}");
            prop_assert!(declines_only_the_rare(a, b), "{a:08x} * {b:08x} declined");
        }

        #[test]
        fn random_sums(a in any::<u32>(), b in any::<u32>()) {
            prop_assert!(adds(a, b), "{a:08x} + {b:08x}");
            prop_assert!(adds_all_but_the_rare(a, b), "{a:08x} + {b:08x} declined");
        }

        /// Operands close in magnitude (cancellation) and far apart (the sticky bit).
        #[test]
        fn sums_near_and_far(a in any::<u32>(), shift in 0u32..40, low in any::<u32>(), negate in any::<bool>()) {
            let exponent = ((a >> 23) & 0xff).saturating_sub(shift) << 23;
            let b = (a & 0x8000_0000) ^ (u32::from(negate) << 31) | exponent | (low & 0x7f_ffff);
            prop_assert!(adds(a, b), "{a:08x} + {b:08x}");
            prop_assert!(adds_all_but_the_rare(a, b), "{a:08x} + {b:08x} declined");
        }

        #[test]
        fn ordinary_magnitudes(x in -1e3f32..1e3, y in -1e3f32..1e3) {
            prop_assert!(adds(x.to_bits(), y.to_bits()));
            prop_assert!(x == 0.0 || add_normal(x.to_bits(), y.to_bits()).is_some());
            prop_assert!(agrees(x.to_bits(), y.to_bits()));
            prop_assert!(x == 0.0 || y == 0.0 || mul_normal(x.to_bits(), y.to_bits()).is_some());
        }
    }

    #[test]
    fn ties_carries_and_the_edges_of_the_range() {
        // Significands whose product is an exact tie (odd and even), a carry out of the top bit,
        // and products at the edges of the normal range.
        let cases: [(f32, f32); 14] = [
            (0.0, -3.0),
            (-0.0, 2.5),
            (1e-40, 0.0),
            (0.0, f32::MAX),
            (1.0 + f32::EPSILON, 1.0 + f32::EPSILON),
            (1.5, 1.0 + f32::EPSILON),
            (3.0, 1.0 + 2.0 * f32::EPSILON),
            (f32::from_bits(0x3fff_ffff), f32::from_bits(0x3fff_ffff)),
            (f32::MAX, 0.5),
            (f32::MAX, 1.0 + f32::EPSILON),
            (f32::MIN_POSITIVE, 2.0),
            (f32::MIN_POSITIVE, 0.5),
            (f32::MIN_POSITIVE, 1.0 - f32::EPSILON / 2.0),
            (-7.25, 0.1),
        ];
        for (x, y) in cases {
            assert!(agrees(x.to_bits(), y.to_bits()), "{x:e} * {y:e}");
        }
        // Sums: ties to even after the sticky bit, carries into the exponent, total cancellation,
        // the smaller operand just inside and just beyond the reach of rounding, overflow.
        let sums: [(f32, f32); 15] = [
            (0.0, -0.0),
            (-0.0, -0.0),
            (-0.0, 1e-40),
            (1.0, f32::EPSILON / 2.0),
            (1.0 + f32::EPSILON, f32::EPSILON / 2.0),
            (1.0, f32::EPSILON / 2.0 + f32::EPSILON / 1024.0),
            (1.0, -f32::EPSILON / 4.0),
            (1.0, -f32::EPSILON / 4.0 - f32::EPSILON / 1024.0),
            (2.0 - f32::EPSILON, f32::EPSILON),
            (3.5, -3.5),
            (1.0, -(1.0 - f32::EPSILON / 2.0)),
            (1.0, f32::from_bits(0x3280_0001)),
            (1.0, f32::from_bits(0x3300_0001)),
            (f32::MAX, f32::MAX),
            (f32::MIN_POSITIVE * 1.5, -f32::MIN_POSITIVE),
        ];
        for (x, y) in sums {
            assert!(adds(x.to_bits(), y.to_bits()) && adds(y.to_bits(), x.to_bits()), "{x:e} + {y:e}");
        }
        // Exhaustive over every significand of one factor against a few of the other.
        for m in (0..1u32 << 23).step_by(97) {
            let x = f32::from_bits(0x3f80_0000 | m);
            for y in [1.0f32 + f32::EPSILON, 1.333_333_4, 1.999_999_9, 1.5] {
                assert!(agrees(x.to_bits(), y.to_bits()), "{x:e} * {y:e}");
                assert!(adds(x.to_bits(), y.to_bits()) && adds(x.to_bits(), (-y).to_bits()), "{x:e} + {y:e}");
            }
        }
    }
}
