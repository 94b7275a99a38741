//! What a step reports of its contacts, and why a step fails: the records the stepper and the
//! contacts' solve (`super::friction`) both hand out.

use super::algebra::Vector;
use super::body::State;
use crate::real::Real;

/// The most friction directions a step tries before it gives up ([`crate::StepError::ConeNotConverged`]):
/// a contact whose tangential response is isotropic and uncoupled from its normal (a sphere, a
/// point under the centre of mass) needs one; the meter stick across its fingers at small
/// headings, whose lines restart (`super`'s module docs, 3), up to 18.
pub const MAX_DIRECTIONS: u32 = 32;

/// The contact's mode after a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Mode {
    /// No normal impulse.
    Separated,
    /// A normal impulse and a slip of at most the stick speed.
    Sticking,
    /// A normal impulse and a slip beyond it; friction opposes the slip.
    Sliding,
}

/// The contact after a step.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SpatialContactReport<T> {
    /// Its mode.
    pub mode: Mode,
    /// Normal impulse, N s.
    pub normal_impulse: T,
    /// Friction impulse on the body, N s, world axes (in the plane).
    pub friction_impulse: Vector<T>,
    /// The contact point's velocity along the plane after the step, m/s, world axes.
    pub slip: Vector<T>,
    /// The friction directions the step tried (1 when the first, along the free slip, held).
    pub directions: u32,
    /// The circular cone's residual of the answer: `|p_t + mu p_n s^|` over `mu p_n` when
    /// sliding (`s^` the slip's direction), `(|p_t| - mu p_n)+` over `mu p_n` when sticking; 0
    /// when separated.
    pub cone_residual: T,
}

impl<T: Real> SpatialContactReport<T> {
    /// No contact: separated, nothing carried.
    pub(super) fn separated() -> Self {
        Self {
            mode: Mode::Separated,
            normal_impulse: T::zero(),
            friction_impulse: [T::zero(); 3],
            slip: [T::zero(); 3],
            directions: 0,
            cone_residual: T::zero(),
        }
    }
}

/// One step's result.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SpatialStepReport<T, const K: usize> {
    /// Time at the end of the step, s.
    pub time: T,
    /// The body after the step.
    pub state: State<T>,
    /// Its contacts, in the order [`super::SpatialStepper::new`] was given their shapes.
    pub contacts: [SpatialContactReport<T>; K],
    /// Lemke pivots of the step's solves (every friction line it tried).
    pub pivots: u32,
}
