//! [`Checksum`]: a fingerprint of a trajectory, to compare runs on different machines bit for bit.

use super::body::BodyState;
use crate::real::Real;

/// FNV-1a (32-bit) over the bits of the body's state after every step: `x, y, theta, vx, vy,
/// omega`, each as its IEEE bits in little-endian bytes (4 for f32, 8 for f64). Two runs have the
/// same checksum when every step produced the same bits: the firmware prints it, `host-sim scene`
/// and the browser page show it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Checksum(u32);

impl Default for Checksum {
    fn default() -> Self {
        Self::new()
    }
}

impl Checksum {
    /// The FNV-1a offset basis.
    #[must_use]
    pub const fn new() -> Self {
        Self(0x811c_9dc5)
    }

    /// Adds one state.
    pub fn add<T: Real>(&mut self, state: &BodyState<T>) {
        for v in state.to_array() {
            self.add_value(v);
        }
    }

    /// Adds `values` in order (a body in three dimensions: its position, orientation, velocity
    /// and angular velocity).
    pub fn add_values<T: Real>(&mut self, values: &[T]) {
        for &v in values {
            self.add_value(v);
        }
    }

    /// Adds one value, its `T::BYTES` little-endian bytes.
    #[inline]
    fn add_value<T: Real>(&mut self, v: T) {
        let [b0, b1, b2, b3, b4, b5, b6, b7] = v.to_le_bytes_u64();
        self.add_word(u32::from_le_bytes([b0, b1, b2, b3]));
        if T::BYTES == 8 {
            self.add_word(u32::from_le_bytes([b4, b5, b6, b7]));
        }
    }

    /// Adds four bytes, the lowest first: FNV-1a's rounds on a word's bytes, unrolled (a byte
    /// array walked by an iterator cost the boards three times the instructions).
    #[inline]
    fn add_word(&mut self, word: u32) {
        for shift in [0, 8, 16, 24] {
            self.0 ^= (word >> shift) & 0xff;
            self.0 = self.0.wrapping_mul(0x0100_0193);
        }
    }

    /// The value.
    #[must_use]
    pub const fn value(self) -> u32 {
        self.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv1a_of_known_bytes() {
        // FNV-1a of the 4 bytes of 1.0f32 (00 00 80 3f) and of zeros, computed by hand from the
        // definition: h = (h ^ byte) * 16777619, h0 = 2166136261.
        let mut c = Checksum::new();
        c.add(&BodyState::<f32> { x: 1.0, ..BodyState::default() });
        let mut h: u32 = 0x811c_9dc5;
        for byte in [0u8, 0, 0x80, 0x3f].into_iter().chain([0u8; 20]) {
            h = (h ^ u32::from(byte)).wrapping_mul(16_777_619);
        }
        assert_eq!(c.value(), h);
        let mut d = Checksum::new();
        d.add(&BodyState::<f64> { x: 1.0, ..BodyState::default() });
        assert_ne!(d.value(), h, "f64 hashes 8 bytes per value");
    }
}
