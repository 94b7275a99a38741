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
    let ea = (a >> 23) & 0xff;
    let eb = (b >> 23) & 0xff;
    // An exponent field of 0 (zero, subnormal) or 255 (infinity, NaN): a zero times a finite
    // number is a zero of the product's sign; the rest is not taken here.
    if ea.wrapping_sub(1) >= 0xfe || eb.wrapping_sub(1) >= 0xfe {
        let zero = |x: u32| x << 1 == 0;
        let finite = |e: u32| e != 0xff;
        return ((zero(a) && finite(eb)) || (zero(b) && finite(ea))).then_some((a ^ b) & 0x8000_0000);
    }
    let sa = (a & 0x7f_ffff) | 0x80_0000;
    let sb = (b & 0x7f_ffff) | 0x80_0000;
    // The 48-bit product of the 24-bit significands as `hi 2^24 + lo`, from 12-bit halves: every
    // partial product and sum fits in 32 bits, and every shift is by a constant (no 64-bit
    // arithmetic, which the core would do in library calls).
    let (ah, al, bh, bl) = (sa >> 12, sa & 0xfff, sb >> 12, sb & 0xfff);
    let mid = ah * bl + al * bh; // < 2^25
    let lo_sum = al * bl + ((mid & 0xfff) << 12); // < 2^25
    let hi = ah * bh + (mid >> 12) + (lo_sum >> 24); // in [2^22, 2^24)
    let lo = lo_sum & 0xff_ffff;
    // Keep the top 24 bits of the product, round on the rest.
    let top = hi >> 23; // 1 when the product is in [2^47, 2^48)
    let biased = ea + eb + top; // the product's exponent field plus 127
    if biased <= 127 {
        return None; // a subnormal (or zero) product rounds at a coarser place
    }
    let (mut m, rem, half) =
        if top == 1 { (hi, lo, 1 << 23) } else { ((hi << 1) | (lo >> 23), lo & 0x7f_ffff, 1 << 22) };
    let mut e = biased - 127;
    if rem > half || (rem == half && m & 1 == 1) {
        m += 1;
        if m == 1 << 24 {
            m >>= 1;
            e += 1;
        }
    }
    if e >= 0xff {
        return None; // overflow
    }
    Some(((a ^ b) & 0x8000_0000) | (e << 23) | (m & 0x7f_ffff))
}

#[cfg(test)]
mod tests {
    use super::mul_normal;
    use proptest::prelude::*;

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
        fn ordinary_magnitudes(x in -1e3f32..1e3, y in -1e3f32..1e3) {
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
        // Exhaustive over every significand of one factor against a few of the other.
        for m in (0..1u32 << 23).step_by(97) {
            let x = f32::from_bits(0x3f80_0000 | m);
            for y in [1.0f32 + f32::EPSILON, 1.333_333_4, 1.999_999_9, 1.5] {
                assert!(agrees(x.to_bits(), y.to_bits()), "{x:e} * {y:e}");
            }
        }
    }
}
