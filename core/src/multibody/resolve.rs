//! The rule of [`crate::rule`] on a multibody step (`docs/formulation.md`, "One answer: the
//! rule"): which steps may have several answers that move the bodies differently ([`SystemDetector`]),
//! and on those the verified solutions a descent over neighbouring bases reaches from the path's
//! answer, the rule's choice kept ([`resolve`], the reference's search). The single body's
//! one-contact test and its threshold (`core/src/planar/resolve.rs`) for each contact with the
//! others' normals held ([`flags`]), in the bodies' `3B` coordinates; the at-rest shortcut as for
//! one body.
//!
//! The bodies' velocities after a step are `v~ + M~ J^T z`; two solutions move the bodies
//! differently only where the contacts do not decide `z`'s effect on them. Two sticking corners of
//! one interface leave only the split of the interface's friction open (four rows of rank three:
//! the friction columns, not the normals, are dependent) and the motion decided: nothing here
//! looks at that. What can leave the motion open is what opens it for one body: a rank-deficient
//! set of active normal rows (a block resting on a board and on the table beside it at once: more
//! vertical normals than the bodies' `vy`, `omega`), or friction whose coupling into the normal
//! rows outweighs their stiffness (a block tipping about a sticking corner at `mu = 2`: the
//! Painleve-type case).
//!
//! The descent's neighbourhoods (one slot's patterns, two slots of one pair) are walked with the
//! slot codec's odometer (`core/src/slot.rs`, `each_basis`), the one the planar rule enumerates
//! every basis with. Enumerating every basis here keeps the same answers on the catalogue's runs
//! but costs a flagged step about 24 times the descent on the M4F (`docs/formulation.md`, "One
//! answer: the rule", 2): the descent stays.

use super::factored::{ContactBlocks, Factored};
use super::geometry::Shape;
use crate::planar::Body;
use crate::planar::resolve::COUPLING;
use crate::real::{Real, max};
use crate::rule::{Answer, Choice, Resolution, Rule};
use crate::slot::{PATTERNS, Pattern, Slot, each_basis};

/// At most this many active contacts are searched ([`resolve`]); a flagged step with more keeps
/// its path's answer.
pub(super) const MAX_CONTACTS: usize = 4;

/// The patterns a contact takes in the descent: the stepper's [`PATTERNS`] without sticking
/// along `-d` (the factored solve turns a sticking contact's negative `p_+d` into `p_-d` itself: the
/// same solution).
const ENUMERATED: [Pattern; 7] =
    [PATTERNS[0], PATTERNS[2], PATTERNS[3], PATTERNS[4], PATTERNS[5], PATTERNS[6], PATTERNS[7]];

/// The rule's data of a system of `B` bodies: the energy's metric, each coordinate's reach.
#[derive(Debug, Clone, Copy)]
pub(super) struct SystemDetector<T, const B: usize> {
    /// `1 / diag(M~) / sum_i (m_i / m_ref)`: the reference's energy `sum_i (m_i |v_i|^2 + J_i
    /// omega_i^2) / m_ref` divided by the bodies' mass in units of `m_ref`, so that the rule's tie
    /// `1e-12 S^2` is the reference's `1e-12 S^2 sum_i m_i / m_ref`.
    metric: [[T; 3]; B],
    /// `(1, 1, r_i)`, `r_i` half body `i`'s diagonal, a disc's radius (the reference's reach).
    reach: [[T; 3]; B],
}

impl<T: Real, const B: usize> SystemDetector<T, B> {
    /// The rule's data of `bodies` of `shapes` whose `M~ = m_ref M^-1` has the diagonal
    /// `inverse_mass`: a box's reach half its diagonal, a disc's its radius.
    pub(super) fn new(bodies: &[Body<T>; B], shapes: &[Shape; B], inverse_mass: &[[T; 3]; B]) -> Self {
        let mut mass_sum = T::zero();
        for m in inverse_mass {
            mass_sum += T::one() / m[0];
        }
        let mut metric = [[T::zero(); 3]; B];
        let mut reach = [[T::one(); 3]; B];
        for i in 0..B {
            for c in 0..3 {
                metric[i][c] = T::one() / (inverse_mass[i][c] * mass_sum);
            }
            let [a, b] = bodies[i].half_extents();
            reach[i][2] = if shapes[i] == Shape::Disc { a } else { (a * a + b * b).sqrt_rounded() };
        }
        Self { metric, reach }
    }

    /// The rule for the step `f`: its speed scale `S` is the largest free velocity's coordinate
    /// (`omega` times its body's reach), as the reference's.
    pub(super) fn rule<const N: usize>(&self, f: &Factored<T, B, N>) -> Rule<T, B> {
        let mut speed = T::zero();
        for (v, r) in f.v_free().iter().zip(&self.reach) {
            speed = max(speed, max(max(v[0].abs_exact(), v[1].abs_exact()), r[2] * v[2].abs_exact()));
        }
        Rule::new(self.metric, self.reach, speed)
    }
}

/// `true` when the step `f` may have several answers that move the bodies differently: the
/// normal block `N = J_n M~ J_n^T` of its `k` active contacts is rank-deficient (a pivot of its
/// `L D L^T` factorisation within `64 eps` of its diagonal entry, or not positive), or friction
/// outweighs a contact's normal stiffness with the other contacts' normals held: with
/// `C_ij = mu_j J_n,i M~ J_d,j^T` (the friction of contact `j` in the normal row of `i`), the largest
/// row sum of `|N^-1 C|` reaches [`COUPLING`]. Row `i` of `N^-1 C` is row `i` of the Schur
/// complement of the others' normals in `C` divided by the one in `N` (the block inverse): the
/// single body's one-contact test `mu |W_n^T M^-1 W_d| >= W_n^T M^-1 W_n`
/// (`core/src/planar/resolve.rs`, `SystemDetector::flags`) for each contact as the others leave it, and
/// exactly that test for `k = 1`. The friction block's own singularity (two sticking corners of
/// one interface) is not looked at: it leaves the split of a force open, not the motion.
///
/// The work, on every step not at rest, is that of the decision and no more: `N` (its lower
/// triangle) and `C` are the step's `blocks` when it formed them for its solve
/// ([`Factored::form_blocks`]), else from its factored columns ([`Factored::contact_blocks`]: each
/// entry the product of the bodies the two columns share, no copy of a column; the same entries
/// either way), and the usual four contacts in a copy whose loop bounds are constants. The same
/// entries (up to a zero's sign, which no comparison here sees) and the same operations on them as
/// the definition above: the same decision.
#[inline(never)] // called only for a step not at rest: out of the resting steps' path
pub(super) fn flags<T: Real, const B: usize, const N: usize>(
    f: &Factored<T, B, N>,
    blocks: Option<&ContactBlocks<T>>,
) -> bool {
    // Four contacts (two interfaces of two corners: block-on-block's step) with every bound a
    // constant; any other count (at most `N / 4 <= 8`) in arrays of eight. The step's blocks
    // when it formed them ([`Factored::form_blocks`]), else from the columns.
    match (f.slots(), blocks) {
        (4, Some(blocks)) if !cfg!(feature = "compact") => coupled::<T, B, N, 4>(f, 4, &blocks.n, &blocks.c),
        (4, None) if !cfg!(feature = "compact") => {
            let (mut n, mut c) = ([[T::zero(); 4]; 4], [[T::zero(); 4]; 4]);
            f.contact_blocks(4, &mut n, &mut c);
            coupled::<T, B, N, 4>(f, 4, &n, &c)
        }
        (k, blocks) => {
            let (mut n, mut c) = ([[T::zero(); 8]; 8], [[T::zero(); 8]; 8]);
            if let Some(blocks) = blocks {
                for i in 0..4 {
                    n[i][..4].copy_from_slice(&blocks.n[i]);
                    c[i][..4].copy_from_slice(&blocks.c[i]);
                }
            } else {
                f.contact_blocks_of_eight(&mut n, &mut c);
            }
            coupled::<T, B, N, 8>(f, k.min(8), &n, &c)
        }
    }
}

/// [`flags`] for `k <= MOST` contacts from their blocks `N` (lower triangle) and `C` (by columns,
/// [`Factored::contact_blocks`]).
#[allow(clippy::inline_always)] // `k` a constant in the four contacts' copy: its loops unrolled
#[inline(always)]
fn coupled<T: Real, const B: usize, const N: usize, const MOST: usize>(
    f: &Factored<T, B, N>,
    k: usize,
    n: &[[T; MOST]; MOST],
    c: &[[T; MOST]; MOST],
) -> bool {
    let k = k.min(MOST);
    let round_off = T::of(64.0) * T::EPS;
    // `N = L D L^T` by rows.
    let mut l = [[T::zero(); MOST]; MOST];
    let mut d = [T::zero(); MOST];
    for i in 0..k {
        for j in 0..i {
            let mut u = n[i][j];
            for m in 0..j {
                u -= l[i][m] * d[m] * l[j][m];
            }
            l[i][j] = u / d[j];
        }
        let diagonal = n[i][i];
        let mut pivot = diagonal;
        for m in 0..i {
            pivot -= l[i][m] * l[i][m] * d[m];
        }
        if pivot.partial_cmp(&(round_off * diagonal)) != Some(core::cmp::Ordering::Greater) {
            return true; // rank-deficient within round-off (or not finite)
        }
        d[i] = pivot;
    }
    // `N^-1 C` column by column (one solve each), its rows' sums of magnitudes.
    let mut rows = [T::zero(); MOST];
    for j in 0..k {
        let mu = f.mu(j);
        if mu == T::zero() {
            continue;
        }
        let mut x = [T::zero(); MOST];
        for i in 0..k {
            let mut y = c[j][i];
            for m in 0..i {
                y -= l[i][m] * x[m];
            }
            x[i] = y;
        }
        for i in (0..k).rev() {
            let mut y = x[i] / d[i];
            for m in i + 1..k {
                y -= l[m][i] * x[m];
            }
            x[i] = y;
            rows[i] += mu * y.abs_exact();
        }
    }
    rows.iter().any(|&r| r >= T::of(COUPLING))
}

/// The rule on the step `f` whose path answered `v_plus`, `z` with the basis `mask`
/// (`docs/formulation.md`, "One answer: the rule"): an answer at rest (its energy within the
/// rule's tie of zero) is the rule's choice as it is, with no other test; otherwise, when
/// [`flags`] says the step may have several answers, [`resolve`]; `None` when the answer is at
/// rest or the step was not flagged. Without the `fallback` feature nothing (and none of the
/// rule's code is linked), as for one body: such a build keeps the path's answer.
#[inline]
pub(super) fn apply<T: Real, const B: usize, const N: usize>(
    detector: &SystemDetector<T, B>,
    f: &Factored<T, B, N>,
    blocks: Option<&ContactBlocks<T>>,
    tolerance: T,
    declined: Option<&DeclinedBases>,
    answer: (&mut [[T; 3]; B], &mut [T; N], &mut u32),
) -> Option<Resolution> {
    if !cfg!(feature = "fallback") {
        return None;
    }
    let rule = detector.rule(f);
    let (v_plus, z, mask) = answer;
    if rule.at_least_energy(v_plus) || !flags(f, blocks) {
        return None;
    }
    Some(resolve(f, blocks, rule, tolerance, declined, v_plus, z, mask))
}

/// The bases a step's paths solved in factored form and saw declined before one answered (the
/// warm basis, the candidates': `stepper/candidates.rs`), which [`resolve`] does not solve again
/// (the same solve of the same basis on the same step). Kept only on a step the rule may search
/// (`k <= MAX_CONTACTS`): there the warm basis, the sliding one, the lifting chain's `k`, the
/// slots' `8 k` and the pairs' (at most two pairs with two slots of `k <= 4`) `2 x 8` are at most
/// [`DECLINED`].
#[derive(Clone, Copy)]
pub(super) struct DeclinedBases {
    bases: [u32; DECLINED],
    count: usize,
}

/// [`DeclinedBases`]' room: `2 + 9 MAX_CONTACTS + 16`.
pub(super) const DECLINED: usize = 2 + 9 * MAX_CONTACTS + 16;

impl DeclinedBases {
    /// None yet.
    pub(super) const fn new() -> Self {
        Self { bases: [0; DECLINED], count: 0 }
    }

    /// Adds the basis `mask`, which declined on a step of `k` slots (nothing on a step the rule
    /// does not search, or beyond the room: the rule then solves it again, as it would anyway).
    #[inline]
    pub(super) fn add(&mut self, mask: u32, k: usize) {
        if k <= MAX_CONTACTS
            && let Some(slot) = self.bases.get_mut(self.count)
        {
            *slot = mask;
            self.count += 1;
        }
    }

    /// Whether the basis `mask` declined.
    fn contains(&self, mask: u32) -> bool {
        self.bases[..self.count.min(DECLINED)].contains(&mask)
    }
}

/// Rounds of the descent ([`resolve`]): the reference's (`reference/src/multibody/step.rs`,
/// `DESCENT_ROUNDS`).
pub(super) const ROUNDS: usize = 8;

/// The basis solves of [`resolve`] at worst on a step of `k <= MAX_CONTACTS` slots of which
/// `pairs_of_slots` pairs of slots belong to one pair of bodies: [`ROUNDS`] rounds of `7 k`
/// single changes and (once widened) `7 x 7` changes of each such pair of slots. Not capped by the
/// `7^k` bases of [`ENUMERATED`]'s patterns: a round's centre is the basis its answer reports
/// (`factored::Answer::mask`), whose slots may hold a pattern outside them, so the bases a descent meets are
/// not only those (`factored`'s test `a_tilted_top_box_on_a_spinning_bottom_one`: 54 on `k = 2`).
#[must_use]
pub(super) const fn most_solves(k: usize, pairs_of_slots: usize) -> usize {
    let n = ENUMERATED.len();
    ROUNDS * (n * k + n * n * pairs_of_slots)
}

/// Every slot's bit in [`changed_slots`].
const ALL_SLOTS: u32 = (1 << MAX_CONTACTS) - 1;

/// The slots (bits, among `k <= MAX_CONTACTS`) in which the bases `a` and `b` differ, each with
/// `a`'s pattern one of [`ENUMERATED`]'s (bit `MAX_CONTACTS`: some slot's is not).
fn changed_slots(a: u32, b: u32, k: usize) -> u32 {
    let mut changed = 0;
    for j in 0..k.min(MAX_CONTACTS) {
        let slot = Slot::full(k, j);
        if slot.bits(Pattern::ALL) & (a ^ b) != 0 {
            changed |= 1 << j;
            if !ENUMERATED.contains(&slot.read(a)) {
                changed |= 1 << MAX_CONTACTS;
            }
        }
    }
    changed
}

/// Applies `rule` to the flagged step `f` whose path answered `v_plus`, `z` with the basis `mask`
/// (at most [`MAX_CONTACTS`] active slots): a descent over neighbouring bases, as the reference's
/// (`docs/formulation.md`, "Several bodies: the rule", 3). From the path's basis (the centre),
/// each slot's pattern replaced in turn by each of [`ENUMERATED`]'s, every verified solution
/// offered to the rule after the path's answer; while a round lowers the energy beyond the rule's
/// tie, again from the rule's choice, at most [`ROUNDS`] rounds. When a round lowers nothing but
/// the solutions offered move the bodies differently, the search is widened once: each two slots
/// of one pair changed together too (an interface that starts or stops sliding changes both its
/// corners), again while that lowers the energy. A basis that an earlier round solved (one slot,
/// or once widened two slots of one pair, away from that round's centre) is not solved again, nor
/// is one the step's paths solved and saw declined (`declined`).
/// When the rule takes another answer, `v_plus`, `z` and `mask` become it. No heap: two `z`
/// arrays and the rounds' centres on the stack.
///
/// **Cost** (a contract): at most [`most_solves`]`(k, pairs)` basis solves, `pairs` the pairs of
/// slots that share a pair of bodies: on two interfaces of two corners (block-on-block, the
/// tablecloth) `8 (28 + 2 x 49) = 1,008` at worst, where every basis of the patterns is `7^4 =
/// 2,401`; a flagged step with one motion stops after its first round (at most `7 k`, 28 solves),
/// an ambiguous one widens once (at most `2 x 49` more a round).
#[cold] // only flagged steps come here: out of the stepper's determinate path
#[inline(never)]
#[allow(clippy::too_many_arguments)] // the step's answer and what its paths solved, passed once
pub(super) fn resolve<T: Real, const B: usize, const N: usize>(
    f: &Factored<T, B, N>,
    blocks: Option<&ContactBlocks<T>>,
    rule: Rule<T, B>,
    tolerance: T,
    declined: Option<&DeclinedBases>,
    v_plus: &mut [[T; 3]; B],
    z: &mut [T; N],
    mask: &mut u32,
) -> Resolution {
    let k = f.slots();
    if k > MAX_CONTACTS {
        return Resolution::default();
    }
    let mut choice = Choice::new(rule, Answer::of(*v_plus, z));
    let mut best: Option<([[T; 3]; B], u32)> = None;
    let mut best_z = [T::zero(); N];
    let (mut found, mut w) = ([T::zero(); N], [T::zero(); N]);
    let same_pair = |a: u32, b: u32| f.pair(a as usize) == f.pair(b as usize);
    // Each round's centre and whether it was widened: a round solved the bases one slot (or,
    // widened, two slots of one pair) away from its centre, each changed slot to one of
    // [`ENUMERATED`]'s patterns.
    let mut centres = [(0u32, false); ROUNDS];
    let (mut centre, mut centre_v) = (*mask, *v_plus);
    let mut widened = false;
    let (mut offers, mut solves) = (0usize, 0usize);
    for round in 0..ROUNDS {
        centres[round] = (centre, widened);
        let energy = rule.energy(&centre_v);
        let earlier = &centres[..round];
        let mut try_basis = |basis: u32| {
            let solved_before = basis == centre
                || earlier.iter().any(|&(c, wide)| {
                    let changed = changed_slots(basis, c, k);
                    changed.count_ones() <= 1
                        || wide && changed.count_ones() == 2 && changed >> MAX_CONTACTS == 0 && {
                            let a = changed.trailing_zeros();
                            same_pair(a, (changed & (changed - 1)).trailing_zeros())
                        }
                });
            if solved_before || declined.is_some_and(|d| d.contains(basis)) {
                return;
            }
            solves += 1;
            if let Ok(a) = f.solve_basis(basis, tolerance, blocks, &mut found, Some(&mut w)) {
                if choice.offer(offers, Answer::of(a.v_plus, &found)) {
                    best = Some((a.v_plus, a.mask));
                    best_z = found;
                }
                offers += 1;
                // The next basis is solved into a zero `z` (a declined one leaves it zero).
                found = [T::zero(); N];
            }
        };
        // The bases one slot away ([`each_basis`] over that slot), then (widened) two slots of
        // one pair away, the later slot the faster digit.
        for j in 0..k {
            each_basis(centre, &[Slot::full(k, j)], &ENUMERATED, |_, basis| try_basis(basis));
        }
        if widened {
            for a in 0..k {
                for b in a + 1..k {
                    if !same_pair(a as u32, b as u32) {
                        continue;
                    }
                    let slots = [Slot::full(k, b), Slot::full(k, a)];
                    each_basis(centre, &slots, &ENUMERATED, |_, basis| {
                        // Both slots changed: one alone is a single change, made above.
                        if changed_slots(basis, centre, k) & ALL_SLOTS == 1 << a | 1 << b {
                            try_basis(basis);
                        }
                    });
                }
            }
        }
        match best {
            Some((v, m)) if rule.lowers(&v, energy) => (centre, centre_v) = (m, v),
            _ if !widened && choice.ambiguous() => widened = true,
            _ => break,
        }
    }
    debug_assert!(solves <= most_solves(k, pairs_of_slots(f, k)), "{solves} solves");
    if choice.chosen().is_some()
        && let Some((v, m)) = best
    {
        (*v_plus, *z, *mask) = (v, best_z, m);
    }
    choice.resolution()
}

/// The pairs of `f`'s first `k` slots that belong to one pair of bodies.
fn pairs_of_slots<T: Real, const B: usize, const N: usize>(f: &Factored<T, B, N>, k: usize) -> usize {
    let mut pairs = 0;
    for a in 0..k {
        for b in a + 1..k {
            pairs += usize::from(f.pair(a) == f.pair(b));
        }
    }
    pairs
}

#[cfg(test)]
#[allow(clippy::expect_used, clippy::float_cmp)] // a test's setup may fail loudly
mod tests {
    //! The rule's choice on steps whose LCP has solutions that move the bodies differently (the
    //! tablecloth at `mu = 2`: the block tipping about its corner on the board, which may stick,
    //! slide or lift), against an enumeration written apart from the factored form: every basis
    //! of the active contacts' eight patterns solved densely from the assembled LCP (its principal
    //! system by nalgebra's LU), verified ([`crate::lcp::verify`]), the least kinetic energy
    //! `sum_i m_i |v_i|^2 + J_i omega_i^2` taken, ties (`1e-12 S^2 sum_i m_i`) by the smallest
    //! `||z||_1`: the reference's rule (`reference/src/multibody/step.rs`).
    use std::vec::Vec;

    use nalgebra::{SMatrix, SVector};

    use super::{SystemDetector, flags, resolve};
    use crate::lcp::{default_tolerance, verify};
    use crate::multibody::factored::Factored;
    use crate::multibody::scenes::{
        BlockOnBlock, BlockOnBlockParams, TABLECLOTH_ROWS, Tablecloth, TableclothParams,
    };
    use crate::planar::resolve::COUPLING;
    use crate::real::Real;
    use crate::slot::{PATTERNS, full_rows};

    const N: usize = TABLECLOTH_ROWS;

    /// One verified solution of the dense enumeration.
    struct Dense {
        z: [f64; N],
        mask: u32,
        v: [[f64; 3]; 2],
        energy: f64,
        sum: f64,
    }

    #[test]
    fn the_rule_takes_the_least_energy_of_every_solution_whatever_the_path_answered() {
        let params =
            TableclothParams::<f64> { mu_static: 2.0, mu_kinetic: 2.0, ..TableclothParams::default() };
        let mut scene = Tablecloth::new(params).expect("valid parameters");
        let (mut ambiguous, mut flagged) = (0, 0);
        for _ in 0..60 {
            let mut stepper = scene.stepper().clone();
            stepper.refill().expect("room for the contacts");
            let f = &stepper.lcp.factored;
            let k = f.slots();
            let bodies = stepper.system().bodies;
            let m_ref = bodies[0].mass;
            let inverse_mass = bodies.map(|b| [m_ref / b.mass, m_ref / b.mass, m_ref / b.inertia]);
            let rule = SystemDetector::new(&bodies, &[super::Shape::Box; 2], &inverse_mass).rule(f);
            let lcp = f.assemble(false);
            let tolerance = default_tolerance::<f64, N>();
            // The dense enumeration: 8^k bases.
            let mut found: Vec<Dense> = Vec::new();
            for code in 0..8usize.pow(k as u32) {
                let mut mask = 0u32;
                let mut digits = code;
                for j in 0..k {
                    let pattern = PATTERNS[digits % 8];
                    digits /= 8;
                    for (bit, row) in full_rows(k, j).into_iter().enumerate() {
                        mask |= u32::from(pattern.bits() >> bit & 1) << row;
                    }
                }
                let basic = |v: usize| (mask >> v) & 1 == 1;
                let a = SMatrix::<f64, N, N>::from_fn(|r, c| match (basic(r), basic(c)) {
                    (true, true) => lcp.m[(r, c)],
                    _ => f64::from(u8::from(r == c)),
                });
                let b = SVector::<f64, N>::from_fn(|r, _| if basic(r) { -lcp.q[r] } else { 0.0 });
                let Some(z) = a.lu().solve(&b) else { continue };
                // Round-off below zero (a zero impulse solved as -1e-20) is zero.
                let z = z.map(|x| if x < 0.0 && x > -1e-12 * lcp.q_norm_inf() { 0.0 } else { x });
                if z.iter().any(|&x| x < 0.0) || !verify(&lcp, &z, tolerance).passed() {
                    continue;
                }
                let z: [f64; N] = z.into();
                let v = f.velocity_after(&z);
                let energy = (0..2)
                    .map(|i| {
                        bodies[i].mass * (v[i][0] * v[i][0] + v[i][1] * v[i][1])
                            + bodies[i].inertia * v[i][2] * v[i][2]
                    })
                    .sum();
                found.push(Dense { z, mask, v, energy, sum: z.iter().sum() });
            }
            // The reference's choice among them.
            let speed = f
                .v_free()
                .iter()
                .zip(&bodies)
                .map(|(v, b)| v[0].abs().max(v[1].abs()).max(0.5 * b.width.hypot(b.height) * v[2].abs()))
                .fold(0.0, f64::max);
            let tie = 1e-12 * speed * speed * (bodies[0].mass + bodies[1].mass);
            let least = found.iter().map(|d| d.energy).fold(f64::INFINITY, f64::min);
            let chosen = found
                .iter()
                .filter(|d| d.energy <= least + tie)
                .min_by(|a, b| a.sum.total_cmp(&b.sum))
                .expect("the step has a solution");
            let differ = |a: &[[f64; 3]; 2], b: &[[f64; 3]; 2]| {
                (0..2).any(|i| {
                    let reach = 0.5 * bodies[i].width.hypot(bodies[i].height);
                    (a[i][0] - b[i][0])
                        .abs()
                        .max((a[i][1] - b[i][1]).abs())
                        .max(reach * (a[i][2] - b[i][2]).abs())
                        > 1e-9 * speed
                })
            };
            let several = found.iter().any(|d| differ(&d.v, &chosen.v));
            ambiguous += u32::from(several);
            flagged += u32::from(flags(f, None));
            if several {
                // Detection: a step with several motions is flagged.
                assert!(flags(f, None), "an ambiguous step not flagged");
                // Whatever solution the path answered, the rule ends on the dense choice.
                for start in &found {
                    let (mut v, mut z, mut mask) = (start.v, start.z, start.mask);
                    let r = resolve(f, None, rule, tolerance, None, &mut v, &mut z, &mut mask);
                    assert!(r.enumerated && r.ambiguous);
                    assert_eq!(r.changed, differ(&start.v, &chosen.v));
                    assert!(!differ(&v, &chosen.v), "rule {v:?}, enumeration {:?}", chosen.v);
                }
            }
            let _ = scene.step().expect("the run goes on");
        }
        // The reference counts 4 such steps in this run (steps 43 to 46); the detection flags them
        // and more (it is a sufficient test), not every step.
        assert_eq!(ambiguous, 4);
        assert!(flagged >= ambiguous && flagged < 60, "{flagged} of 60 steps flagged");
    }

    /// [`flags`] written entry by entry from [`Factored::entry`] with no shortcut: `N` and `C`
    /// formed whole, `N = L D L^T`, one solve per column of `C`, the rows of `|N^-1 C|` summed,
    /// each sum in [`flags`]'s order (the same operations on the same entries: the same decision,
    /// borderline steps included).
    fn flags_by_entries<T: Real, const N: usize>(f: &Factored<T, 2, N>) -> bool {
        let k = f.slots();
        let (mut l, mut d) = ([[T::zero(); 8]; 8], [T::zero(); 8]);
        for i in 0..k {
            for j in 0..i {
                let mut u = f.entry(i, j);
                for m in 0..j {
                    u -= l[i][m] * d[m] * l[j][m];
                }
                l[i][j] = u / d[j];
            }
            let diagonal = f.entry(i, i);
            let mut pivot = diagonal;
            for m in 0..i {
                pivot -= l[i][m] * l[i][m] * d[m];
            }
            if pivot.partial_cmp(&(T::of(64.0) * T::EPS * diagonal)) != Some(core::cmp::Ordering::Greater) {
                return true;
            }
            d[i] = pivot;
        }
        let mut rows = [T::zero(); 8];
        for j in 0..k {
            if f.mu(j) == T::zero() {
                continue;
            }
            let mut x = [T::zero(); 8];
            for i in 0..k {
                x[i] = f.entry(i, k + 2 * j);
                for m in 0..i {
                    x[i] -= l[i][m] * x[m];
                }
            }
            for i in (0..k).rev() {
                x[i] /= d[i];
                for m in i + 1..k {
                    x[i] -= l[m][i] * x[m];
                }
                rows[i] += f.mu(j) * x[i].abs_exact();
            }
        }
        rows.iter().any(|&r| r >= T::of(COUPLING))
    }

    /// One step's check: the blocks [`flags`] reads are [`Factored::entry`]'s exactly (up to a
    /// zero's sign, which `==` does not see), and its decision is [`flags_by_entries`]'s; returns
    /// (active contacts, flagged).
    fn check_step<T: Real + core::fmt::Debug, const N: usize>(f: &Factored<T, 2, N>) -> (usize, bool) {
        let k = f.slots();
        let (mut n, mut c) = ([[T::zero(); 8]; 8], [[T::zero(); 8]; 8]);
        f.contact_blocks(k, &mut n, &mut c);
        for i in 0..k {
            for j in 0..k {
                if j <= i {
                    assert_eq!(n[i][j], f.entry(i, j), "N[{i}][{j}]");
                }
                assert_eq!(c[j][i], f.entry(i, k + 2 * j), "C[{i}][{j}]");
            }
        }
        let flagged = flags(f, None);
        assert_eq!(flagged, flags_by_entries(f), "k = {k}");
        // Four slots: the same decision from the blocks a sliding step forms once.
        let sliding = (0..k).fold(0, |mask, j| mask | crate::slot::Slot::full(k, j).bits(PATTERNS[2]));
        let mut formed = *f;
        formed.form_blocks(sliding);
        if let Some(blocks) = formed.blocks() {
            assert_eq!(k, 4);
            assert_eq!(flags(f, Some(blocks)), flagged, "from the step's blocks");
        }
        (k, flagged)
    }

    /// Steps checked by [`check_step`], flagged, and flagged with four active contacts.
    #[derive(Default, Debug)]
    struct Sweep {
        steps: u32,
        flagged: u32,
        flagged_four: u32,
    }

    impl Sweep {
        fn add(&mut self, (k, flagged): (usize, bool)) {
            self.steps += 1;
            self.flagged += u32::from(flagged);
            self.flagged_four += u32::from(flagged && k == 4);
        }

        /// Checks a run's steps, at most `max_steps`: `next` hands the stepper before a step and
        /// takes the step (`false`: the run ended).
        fn steps<T: Real + core::fmt::Debug, const P: usize, const N: usize>(
            &mut self,
            max_steps: u32,
            mut next: impl FnMut() -> (crate::multibody::SystemStepper<T, 2, P, N>, bool),
        ) {
            for _ in 0..max_steps {
                let (mut stepper, more) = next();
                stepper.refill().expect("room for the contacts");
                self.add(check_step(&stepper.lcp.factored));
                if !more {
                    break;
                }
            }
        }
    }

    /// Block-on-block runs over the pull, the friction between the blocks and the top block's
    /// shape (a tall narrow one tips at high friction), every step checked, `max_steps` at most.
    fn sweep_block_on_block<T: Real + core::fmt::Debug>(max_steps: u32) -> Sweep {
        let mut sweep = Sweep::default();
        for force in [10.0, 30.0, 60.0] {
            for mu in [0.3, 0.5, 1.0, 2.0] {
                for (width, height) in [(0.1, 0.1), (0.04, 0.2)] {
                    let params = BlockOnBlockParams::<T> {
                        force: T::of(force),
                        mu_static: T::of(mu),
                        mu_kinetic: T::of(mu),
                        top_width: T::of(width),
                        top_height: T::of(height),
                        ..BlockOnBlockParams::default()
                    };
                    let mut scene = BlockOnBlock::new(params).expect("valid parameters");
                    sweep.steps(max_steps, || (scene.stepper().clone(), scene.step().is_some()));
                }
            }
        }
        sweep
    }

    /// Tablecloth runs over the pull, the friction on the board and the block's place on it.
    fn sweep_tablecloth<T: Real + core::fmt::Debug>(max_steps: u32) -> Sweep {
        let mut sweep = Sweep::default();
        for force in [10.0, 20.0, 50.0] {
            for mu in [0.5, 2.0, 3.0] {
                for offset in [0.1, 0.3] {
                    let params = TableclothParams::<T> {
                        force: T::of(force),
                        mu_static: T::of(mu),
                        mu_kinetic: T::of(mu),
                        offset: T::of(offset),
                        ..TableclothParams::default()
                    };
                    let mut scene = Tablecloth::new(params).expect("valid parameters");
                    sweep.steps(max_steps, || (scene.stepper().clone(), scene.step().is_some()));
                }
            }
        }
        sweep
    }

    #[test]
    fn the_detection_decides_as_the_whole_blocks_do_over_forces_frictions_and_shapes() {
        for (name, sweep) in [
            ("block-on-block f64", sweep_block_on_block::<f64>(300)),
            ("block-on-block f32", sweep_block_on_block::<f32>(300)),
            ("tablecloth f64", sweep_tablecloth::<f64>(150)),
            ("tablecloth f32", sweep_tablecloth::<f32>(150)),
        ] {
            std::println!("{name}: {sweep:?}");
            // Both decisions taken: steps flagged (four contacts among them) and steps not.
            assert!(sweep.flagged_four > 0 && sweep.flagged < sweep.steps, "{name}: {sweep:?}");
        }
    }

    #[test]
    fn the_detection_decides_as_the_whole_blocks_do() {
        // Block-on-block (default: four contacts sliding, never flagged).
        let mut scene = BlockOnBlock::new(BlockOnBlockParams::<f64>::default()).expect("valid parameters");
        let mut four = 0;
        for _ in 0..200 {
            let mut stepper = scene.stepper().clone();
            stepper.refill().expect("room for the contacts");
            let (k, flagged) = check_step(&stepper.lcp.factored);
            assert!(!flagged);
            four += u32::from(k == 4);
            if scene.step().is_none() {
                break;
            }
        }
        assert!(four > 100, "{four} steps of four contacts");
        // The tablecloth at `mu = 2` (flagged steps 43 to 46).
        let params =
            TableclothParams::<f64> { mu_static: 2.0, mu_kinetic: 2.0, ..TableclothParams::default() };
        let mut scene = Tablecloth::new(params).expect("valid parameters");
        let mut flagged = 0;
        for _ in 0..60 {
            let mut stepper = scene.stepper().clone();
            stepper.refill().expect("room for the contacts");
            flagged += u32::from(check_step(&stepper.lcp.factored).1);
            let _ = scene.step().expect("the run goes on");
        }
        assert!(flagged >= 4, "{flagged} flagged steps");
    }
}
