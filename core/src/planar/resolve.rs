//! The rule of [`crate::rule`] on a planar step (`docs/formulation.md`, "One answer: the rule"):
//! which steps may have several answers ([`Detector`]), and on those every solution the factored
//! form reaches, the rule's choice kept ([`resolve`]).
//!
//! A step's LCP can have solutions that move the body differently only when its contacts do not
//! decide the motion: a rank-deficient set of active normal wrenches (three tips under one rod:
//! three columns `[0, 1, x_i]` of rank 2; any four contacts in the plane), or friction whose
//! coupling into the normal rows outweighs them (the Painleve-type case: a sliding contact's
//! normal row `W_n^T M^-1 (W_n + mu W_d)` can change sign). The [`Detector`] decides from the
//! model once whether either can happen at all (a meter stick on two tips at `mu = 0.6` never
//! gets past that one test), and then per step from the step's frames.
//!
//! The enumeration walks the bases with the slot codec's odometer ([`each_basis`]), the one the
//! multibody rule's descent walks its neighbourhoods with (`core/src/multibody/resolve.rs`). One
//! body enumerates where several bodies descend: the descent on these steps moves the three-fingers
//! reduced runs' checksums and has no answer to start from where the paths failed
//! ([`solve_by_rule`]); `docs/formulation.md`, "One answer: the rule", 2, has the figures.

use super::candidates::RULE_ORDER;
use super::contact::{Contact, Feature};
use super::factored::{FactoredLcp, slot_of};
use super::inputs::{StepInputs, dot3};
use super::strategy::{SolvePath, Solved};
use crate::lcp::Basis;
use crate::real::{Real, max};
use crate::rule::{Answer, Choice, Resolution, Rule};
use crate::slot::{Slot, each_basis};

/// Friction coupling at or above this fraction of a normal row's own stiffness flags a step
/// ([`Detector::flags`]). For one contact 1 is exact: below it a sliding contact's normal row
/// cannot change sign (Painleve's paradox needs `mu |W_n^T M^-1 W_d| > W_n^T M^-1 W_n`).
pub(crate) const COUPLING: f64 = 1.0;

/// With two or three active contacts, the coupling is compared with this many times the lower
/// bound of the normal block's least eigenvalue ([`Detector::flags`]; the bound is within a factor
/// 2 of the eigenvalue for two contacts). Measured with every step enumerated: the ladder's
/// determinate fall sits at a coupling of about that bound (flagged half its steps at 1, none at
/// 2), the meter stick's ambiguous steps at `mu = 1000` at 18 times it and more.
const COUPLING_SEVERAL: f64 = 2.0;

/// At most this many active contacts are enumerated (`8^4` bases); a step with more keeps
/// its path's answer.
const MAX_CONTACTS: usize = 4;

/// Whether a step may have several answers. The model's part is one flag: the rule's metric
/// and reach are the step's ([`Self::rule`]), so that a model the rule never applies to (every
/// model without the `fallback` feature) carries nothing else for it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Detector {
    /// Some step of the model may: `K >= 3` contacts (their normals can be rank-deficient), or
    /// a bound of the friction coupling over every pose reaches [`COUPLING`].
    possible: bool,
}

impl Detector {
    /// The detector of a body with `diag(M^-1)` per unit mass `m_inv` and half extents `half`
    /// under `contacts`. The coupling bound: contact `i`'s normal row has `W_n,i^T M^-1 W_n,i >= 1`
    /// and `|W_n,i^T M^-1 W_d,j| <= l_ij + (m/J) |r_i x n_i| |r_j x d_j|`, with `l_ij = 0` for two
    /// points under the lower face (one normal, one tangent) and 1 otherwise; `|r x n| <= width/2`,
    /// `|r x d| = height/2` under the lower face, `<= |p_x| + |p_y|` both for a point `p`, and
    /// `0`, `R` for a round body.
    ///
    /// Without the `fallback` feature nothing is ever flagged (and no code of the rule is
    /// linked): the rule's choice may need the full layout, and a build without it (the 6x6-only
    /// rig builds, whose flash is counted) takes its solver's answer.
    pub(crate) fn new<T: Real, const K: usize>(
        contacts: &[Contact<T>; K],
        m_inv: [T; 3],
        half: [T; 2],
    ) -> Self {
        if !cfg!(feature = "fallback") {
            return Self { possible: false };
        }
        let levers = |c: &Contact<T>| match c.feature {
            Feature::LowerFace => (half[0], half[1]),
            Feature::Point(p) => (p[0].abs_exact() + p[1].abs_exact(), p[0].abs_exact() + p[1].abs_exact()),
            Feature::Round(r) => (T::zero(), r.abs_exact()),
        };
        let mut bound = T::zero();
        for ci in contacts {
            let (normal_lever, _) = levers(ci);
            let mut row = T::zero();
            for cj in contacts {
                let (_, tangent_lever) = levers(cj);
                let linear = if matches!((ci.feature, cj.feature), (Feature::LowerFace, Feature::LowerFace)) {
                    T::zero()
                } else {
                    T::one()
                };
                row += max(cj.mu_static, cj.mu_kinetic) * (linear + m_inv[2] * normal_lever * tangent_lever);
            }
            bound = max(bound, row);
        }
        Self { possible: K >= 3 || bound >= T::of(COUPLING) }
    }

    /// `true` when some step of the model may have several answers.
    #[inline]
    pub(crate) const fn possible(self) -> bool {
        self.possible
    }

    /// `true` when the step `inputs` may have several answers: its active normal wrenches are
    /// rank-deficient (four or more; three whose normal block's determinant is round-off), or the
    /// largest friction coupling of a normal row, `sum_j mu_j |W_n,i^T M^-1 W_d,j|`, reaches
    /// [`COUPLING`] times `W_n^T M^-1 W_n` (one contact) or [`COUPLING_SEVERAL`] times a lower
    /// bound of the normal block's least eigenvalue (two or three: for two fingers under a rod it
    /// falls as the fingers close in).
    #[inline(never)] // called only for a model that may have such steps: out of the others' step
    pub(crate) fn flags<T: Real, const K: usize>(inputs: &StepInputs<'_, T, K>) -> bool {
        let frames = inputs.frames;
        let m_inv = &inputs.m_inv;
        let scaled = |c: &[T; 3]| [c[0] * m_inv[0], c[1] * m_inv[1], c[2] * m_inv[2]];
        let mut normals = [[T::zero(); 3]; 3];
        let mut count = 0;
        let mut coupling = T::zero();
        for f in frames {
            if !f.active {
                continue;
            }
            let Some(slot) = normals.get_mut(count) else {
                return true; // four wrenches in three dimensions
            };
            *slot = f.wn;
            count += 1;
            let mn = scaled(&f.wn);
            let mut row = T::zero();
            for (g, &mu) in frames.iter().zip(&inputs.mu) {
                if g.active {
                    row += mu * dot3(&g.wt, &mn).abs_exact();
                }
            }
            coupling = max(coupling, row);
        }
        // The normal block `N = W_n^T M^-1 W_n` of the `k` active contacts: its least eigenvalue
        // is at least `det N / (tr N / (k - 1))^(k - 1)` (the others' product is at most that).
        let n = |i: usize, j: usize| dot3(&normals[i % 3], &scaled(&normals[j % 3]));
        let (least, factor) = match count {
            0 => return false,
            1 => (n(0, 0), COUPLING),
            2 => {
                let (a, b, c) = (n(0, 0), n(0, 1), n(1, 1));
                ((a * c - b * b) / (a + c), COUPLING_SEVERAL)
            }
            _ => {
                let e =
                    [[n(0, 0), n(0, 1), n(0, 2)], [n(1, 0), n(1, 1), n(1, 2)], [n(2, 0), n(2, 1), n(2, 2)]];
                let det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1])
                    - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0])
                    + e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
                let half_trace = (e[0][0] + e[1][1] + e[2][2]) * T::of(0.5);
                let round_off = T::of(64.0) * T::EPS * half_trace * half_trace * half_trace;
                if det <= round_off {
                    return true; // rank-deficient (three tips under one rod)
                }
                (det / (half_trace * half_trace), COUPLING_SEVERAL)
            }
        };
        coupling >= T::of(factor) * least
    }

    /// The rule for the step `inputs` of a body of size `size` (`D`): the kinetic energy's metric
    /// per unit mass `1 / diag(M^-1)` = `(1, 1, J/m)`, the reach `(1, 1, D/2)` that turns `omega`
    /// into a speed, and the speed scale `S`, the fastest support's speed and the free velocity's
    /// (`omega` times `D/2`), as the reference's.
    pub(crate) fn rule<T: Real, const K: usize>(inputs: &StepInputs<'_, T, K>, size: T) -> Rule<T, 1> {
        Self::rule_of(&inputs.m_inv, &inputs.v_free, &inputs.support_velocity, size)
    }

    /// The rule's velocity tolerance ([`Rule::velocity_tolerance`]) for the step of free
    /// velocity `v_free` and supports' velocities `support_velocity` of a body of size `size`,
    /// without the rule's metric (three divisions).
    #[cfg_attr(not(feature = "fallback"), allow(dead_code))]
    pub(crate) fn velocity_tolerance<T: Real, const K: usize>(
        v_free: &[T; 3],
        support_velocity: &[[T; 2]; K],
        size: T,
    ) -> T {
        Rule::<T, 1>::velocity_tolerance_at(speed_scale(v_free, support_velocity, size))
    }

    /// [`Self::rule`] from its parts: `diag(M^-1)` per unit mass, the free velocity and the
    /// supports' velocities over the step.
    pub(crate) fn rule_of<T: Real, const K: usize>(
        m_inv: &[T; 3],
        v_free: &[T; 3],
        support_velocity: &[[T; 2]; K],
        size: T,
    ) -> Rule<T, 1> {
        let metric = [T::one() / m_inv[0], T::one() / m_inv[1], T::one() / m_inv[2]];
        let reach = [T::one(), T::one(), size * T::of(0.5)];
        Rule::new([metric], [reach], speed_scale(v_free, support_velocity, size))
    }
}

/// The rule's speed scale `S` of a step: the fastest support's speed and the free velocity's,
/// `omega` times `D/2` (the reference's).
fn speed_scale<T: Real, const K: usize>(v: &[T; 3], support_velocity: &[[T; 2]; K], size: T) -> T {
    let mut speed = max(max(v[0].abs_exact(), v[1].abs_exact()), size * T::of(0.5) * v[2].abs_exact());
    for u in support_velocity {
        speed = max(speed, max(u[0].abs_exact(), u[1].abs_exact()));
    }
    speed
}

/// Applies `rule` to the step `factored` whose path answered `sol` (`z`, `w`). An answer at the
/// least energy any solution can have (zero, within the tie: the body at rest relative to the
/// energy's frame) is the rule's choice as it is. Otherwise every solution [`each_solution`]
/// finds that `admissible` accepts (`z`, `w`, `v+`: a reduced layout's check) is offered to the
/// rule in a fixed order after the path's answer. When the rule takes another, `sol`, `z` and
/// `w` become it.
#[cold] // only flagged steps come here: out of the stepper's determinate path
#[inline(never)]
pub(crate) fn resolve<T: Real, const K: usize, const N: usize>(
    factored: &FactoredLcp<T, K, N>,
    rule: Rule<T, 1>,
    tolerance: T,
    sol: &mut Solved<T, N>,
    z: &mut [T; N],
    w: &mut [T; N],
    admissible: impl Fn(&[T; N], &[T; N], &[T; 3]) -> bool,
) -> Resolution {
    if rule.at_least_energy(&[sol.v_plus]) {
        return Resolution::default();
    }
    let mut choice = Choice::new(rule, Answer::of([sol.v_plus], z));
    let mut best: Option<BasisSolution<T, N>> = None;
    each_solution(factored, tolerance, Some(sol.basis), |code, found| {
        if admissible(&found.z, &found.w, &found.v_plus)
            && choice.offer(code, Answer::of([found.v_plus], &found.z))
        {
            best = Some(*found);
        }
    });
    if choice.chosen().is_some()
        && let Some(found) = best
    {
        (*z, *w) = (found.z, found.w);
        (sol.basis, sol.v_plus, sol.residual) = (found.basis, found.v_plus, found.residual);
    }
    choice.resolution()
}

/// The rule's choice among the solutions [`each_solution`] finds that `admissible` accepts, for a
/// step whose solver found none (Lemke's method failed on a step that may have several answers):
/// `None` when there are none either. `z`, `w` receive it.
#[cold]
#[inline(never)]
pub(crate) fn solve_by_rule<T: Real, const K: usize, const N: usize>(
    factored: &FactoredLcp<T, K, N>,
    rule: Rule<T, 1>,
    tolerance: T,
    z: &mut [T; N],
    w: &mut [T; N],
    admissible: impl Fn(&[T; N], &[T; N], &[T; 3]) -> bool,
) -> Option<(Solved<T, N>, Resolution)> {
    let mut choice: Option<Choice<T, 1>> = None;
    let mut first: Option<BasisSolution<T, N>> = None;
    let mut best: Option<BasisSolution<T, N>> = None;
    each_solution(factored, tolerance, None, |code, found| {
        if !admissible(&found.z, &found.w, &found.v_plus) {
            return;
        }
        let answer = Answer::of([found.v_plus], &found.z);
        match &mut choice {
            None => {
                choice = Some(Choice::new(rule, answer));
                first = Some(*found);
            }
            Some(c) => {
                if c.offer(code, answer) {
                    best = Some(*found);
                }
            }
        }
    });
    let c = choice?;
    let found = if c.chosen().is_some() { best } else { first }?;
    (*z, *w) = (found.z, found.w);
    let sol = Solved {
        v_plus: found.v_plus,
        basis: found.basis,
        pivots: 0,
        warm_start_used: false,
        residual: found.residual,
        path: SolvePath::Candidate,
    };
    Some((sol, Resolution { enumerated: true, ambiguous: c.ambiguous(), changed: false }))
}

/// One basis' verified solution.
#[derive(Debug, Clone, Copy)]
pub(crate) struct BasisSolution<T, const N: usize> {
    basis: Basis<N>,
    z: [T; N],
    w: [T; N],
    v_plus: [T; 3],
    residual: T,
}

/// Calls `found` with every verified solution of `factored` over the bases of the active
/// contacts' patterns ([`RULE_ORDER`], `8^k` for `k <= MAX_CONTACTS` active contacts, the others
/// off; a pattern along a direction a contact does not keep has no basis), in a fixed order
/// ([`each_basis`]: contact by contact, the first the fastest digit), except the basis `skip`;
/// with the basis' number. Nothing for more than `MAX_CONTACTS` active contacts.
fn each_solution<T: Real, const K: usize, const N: usize>(
    factored: &FactoredLcp<T, K, N>,
    tolerance: T,
    skip: Option<Basis<N>>,
    mut found: impl FnMut(usize, &BasisSolution<T, N>),
) {
    let mut active = [Slot::new(0, [None, None], 0); MAX_CONTACTS];
    let mut count = 0;
    for i in 0..K {
        if (factored.inactive >> i) & 1 == 0 {
            let Some(slot) = active.get_mut(count) else { return };
            *slot = slot_of::<K, N>(factored.tangents(), i);
            count += 1;
        }
    }
    let mut solution = BasisSolution {
        basis: Basis::all_w(),
        z: [T::zero(); N],
        w: [T::zero(); N],
        v_plus: [T::zero(); 3],
        residual: T::zero(),
    };
    each_basis(0, active.get(..count).unwrap_or(&[]), &RULE_ORDER, |code, mask| {
        let basis = Basis::<N>::from_z_mask(mask);
        if skip == Some(basis) {
            return;
        }
        if let Ok((v_plus, residual)) =
            factored.solve_basis_into(basis, tolerance, &mut solution.z, &mut solution.w)
        {
            (solution.basis, solution.v_plus, solution.residual) = (basis, v_plus, residual);
            found(code, &solution);
        }
    });
}
