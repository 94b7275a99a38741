//! The stack in three dimensions (docs/scenes.md, "stack-3d"): `n` blocks over a table's edge,
//! their overhangs at a heading to it, written from the docs' text with this crate's algebra and
//! its own Lemke's method (`crate::multibody::lcp`); nothing of `meterstick-core`.
//!
//! # A step
//!
//! Each block `b` (mass `m_b`, `I_w,b^-1 = R diag(1 / I) R^T`) moves freely to `v~ = v + h g`,
//! `omega~ = omega`. Each active contact `c` (docs' "Contacts": a point `P`, a unit normal `n` on its
//! upper block, the gap `psi`) has the tangents `t1 = some_perpendicular(n)`, `t2 = n x t1`, and for
//! each direction `e` of the three the row `J_e V = e . ((v_u + omega_u x r_u) - (v_l + omega_l x r_l))`
//! (`r = P - x` of each of its bodies; the table has none). `W = J M^-1 J^T` over all the rows; the
//! free velocities `u = J V~`, the normal rows' with the gap's bias (`super::step::bias`).
//!
//! **Sticking or separated.** The impulse `p` (N s) of every contact that carries a load stops its
//! slip; one that does not carries nothing. For a set `L` of loaded contacts, the tangential
//! impulses follow from the normal ones, `p_t = -W_tt^+ (u_t + W_tn p_n)` (`W_tt` over `L`'s
//! tangential rows, its pseudo-inverse: a null direction of `W_tt` moves no velocity, `x^T W_tt x
//! = |M^-1/2 J_t^T x|^2`), and the normal impulses of every active contact solve the LCP of the
//! Schur complement, `w = (W_nn - W_nt W_tt^+ W_tn) p_n + (u_n - W_nt W_tt^+ u_t)`, by Lemke's
//! method; `L` is then the contacts whose `p_n` is positive, until it repeats (at most
//! [`LOAD_SETS`] sets). Four coplanar points of an interface leave the loads open: the answer
//! is then replaced by the least-norm solution of the loaded rows (`W_LL p = -u_L`, by the
//! singular value decomposition, `super::dense`) when its normal impulses are all `>= 0`: the
//! load rule of `docs/formulation.md`, "The load: the least norm". Every answer is checked
//! (normal rows complementary, loaded slips zero, each `|p_t| <= mu p_n`); one whose friction
//! would leave the cone (a contact that slides) is refused, [`super::Error::Sliding`]: the
//! holding stack and its first tipping stay within these cases, a sliding one is beyond them.
//!
//! Then `v+ = v~ + M^-1 J^T p`, the orientation by `super::step::turned` (the momentum held over
//! the step), `x+ = x + h v+`.

use super::algebra::{
    M3, Quat, V3, ZERO, apply, congruent, cross, dot, length, matrix_of, minus, plus, times,
};
use super::dense::Svd;
use super::step::{bias, turned};
use super::{Error, Keep, MAX_STEPS, Outcome, Rule};

/// The load sets a step tries at most (`L` above).
pub const LOAD_SETS: usize = 16;

/// The stack's parameters (docs/scenes.md, "stack-3d"; SI units, `heading` in radians).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stack3d {
    /// `n`: 2 to 5.
    pub blocks: usize,
    /// `L`, m.
    pub length: f64,
    /// `W`, m.
    pub width: f64,
    /// `hb`, m.
    pub height: f64,
    /// `m`, kg, each block.
    pub mass: f64,
    pub mu_s: f64,
    pub mu_k: f64,
    /// `s`.
    pub overhang: f64,
    /// `psi`, rad.
    pub heading: f64,
    pub g: f64,
    pub h: f64,
    pub stick_speed: f64,
    pub tilt_limit: f64,
    pub drop_limit: f64,
    pub margin: f64,
    pub max_time: f64,
}

impl Default for Stack3d {
    /// The docs' defaults.
    fn default() -> Self {
        Self {
            blocks: 3,
            length: 0.2,
            width: 0.1,
            height: 0.05,
            mass: 1.0,
            mu_s: 0.5,
            mu_k: 0.5,
            overhang: 0.98,
            heading: 0.0,
            g: 9.81,
            h: 1e-3,
            stick_speed: 1e-5,
            tilt_limit: 0.1,
            drop_limit: 0.01,
            margin: 1e-3,
            max_time: 10.0,
        }
    }
}

/// A finished run of the stack.
#[derive(Debug, Clone, PartialEq)]
pub struct StackRun {
    /// Held or Fell.
    pub outcome: Outcome,
    /// Steps taken.
    pub steps: u64,
    /// The largest `|v| + reach |omega|` over the steps and the blocks (`reach` half a block's
    /// diagonal), m/s.
    pub max_speed: f64,
    /// After `k` steps (row 0 the start; with [`Keep::StartAndEnd`] the start and the end): the
    /// time and each block's centre of mass and orientation.
    pub trajectory: Vec<(f64, Vec<V3>, Vec<Quat>)>,
    /// Each of `trajectory`'s rows' blocks' velocity and angular velocity (m/s, rad/s, world).
    pub motion: Vec<Vec<(V3, V3)>>,
    /// The table's load over the last step (N s): the sum of its contacts' normal impulses.
    pub table_impulse: f64,
}

/// A block's state (world frame, `z` up).
#[derive(Debug, Clone, Copy)]
pub struct Block {
    /// Centre of mass, m.
    pub x: V3,
    /// Orientation, the unit quaternion `[w, x, y, z]` from the block's frame to the world's.
    pub q: Quat,
    /// Velocity, m/s.
    pub v: V3,
    /// Angular velocity, rad/s, world axes.
    pub omega: V3,
}

/// An active contact: its upper block, its lower one (`None`: the table), the point, the unit
/// normal on the upper block, the gap.
#[derive(Debug, Clone, Copy)]
pub struct Contact {
    /// The upper block's index.
    pub upper: usize,
    /// The lower block's index, `None` for the table.
    pub lower: Option<usize>,
    /// Where the impulse acts, world, m.
    pub point: V3,
    /// Unit, world: the push on the upper block.
    pub normal: V3,
    /// The gap along `normal`, m.
    pub gap: f64,
}

impl Stack3d {
    /// The docs' validity rules.
    ///
    /// # Errors
    /// [`Error::Invalid`] naming the first field that breaks one.
    pub fn validate(&self) -> Result<(), Error> {
        let bad = |field, rule| Err(Error::Invalid { field, rule });
        let fields = [
            ("length", self.length, true),
            ("width", self.width, true),
            ("height", self.height, true),
            ("mass", self.mass, true),
            ("mu_s", self.mu_s, false),
            ("mu_k", self.mu_k, false),
            ("overhang", self.overhang, false),
            ("heading", self.heading, false),
            ("g", self.g, false),
            ("h", self.h, true),
            ("stick_speed", self.stick_speed, false),
            ("tilt_limit", self.tilt_limit, true),
            ("drop_limit", self.drop_limit, true),
            ("margin", self.margin, false),
            ("max_time", self.max_time, true),
        ];
        for (field, value, positive) in fields {
            if !value.is_finite() {
                return bad(field, Rule::NotFinite);
            }
            if positive && value <= 0.0 {
                return bad(field, Rule::NotPositive);
            }
            if !positive && value < 0.0 && field != "heading" {
                return bad(field, Rule::Negative);
            }
        }
        if self.mu_k > self.mu_s {
            return bad("mu_k", Rule::KineticAboveStatic);
        }
        if self.h > self.max_time {
            return bad("h", Rule::StepAboveMaxTime);
        }
        if !(2..=5).contains(&self.blocks) {
            return bad("blocks", Rule::OutOfRange);
        }
        if self.overhang / (2.0 * self.blocks as f64) >= 1.0 {
            return bad("overhang", Rule::OutOfRange);
        }
        if self.heading.abs() > 60f64.to_radians() * (1.0 + 1e-12) {
            return bad("heading", Rule::OutOfRange);
        }
        Ok(())
    }

    /// Half extents along the block's own axes.
    fn half(&self) -> V3 {
        [0.5 * self.length, 0.5 * self.width, 0.5 * self.height]
    }

    /// The principal moments of a block.
    fn moments(&self) -> V3 {
        let k = self.mass / 12.0;
        let (a, b, c) = (self.length, self.width, self.height);
        [k * (b * b + c * c), k * (a * a + c * c), k * (a * a + b * b)]
    }

    /// The start: the harmonic offsets along `d`, each block turned by `psi` about `z`.
    #[must_use]
    pub fn start(&self) -> Vec<Block> {
        let n = self.blocks;
        let d = [self.heading.cos(), self.heading.sin(), 0.0];
        let q = [(0.5 * self.heading).cos(), 0.0, 0.0, (0.5 * self.heading).sin()];
        let mut right = 0.0;
        (0..n)
            .map(|i| {
                right += self.overhang * 0.5 * self.length / (n - i) as f64;
                let along = right - 0.5 * self.length;
                let x = plus(times(along, d), [0.0, 0.0, (i as f64 + 0.5) * self.height]);
                Block { x, q, v: ZERO, omega: ZERO }
            })
            .collect()
    }
}

/// A block's corner `(sx, sy, sz)` (each `+1` or `-1`) in the world.
fn corner(b: &Block, half: V3, s: [f64; 3]) -> V3 {
    plus(b.x, apply(&matrix_of(b.q), [s[0] * half[0], s[1] * half[1], s[2] * half[2]]))
}

/// The block's own `z` in the world.
fn up(b: &Block) -> V3 {
    let r = matrix_of(b.q);
    [r[0][2], r[1][2], r[2][2]]
}

const SIGNS: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];

/// A vertex of an overlap polygon in the lower face's coordinates `(s, t)`, and whether it is
/// one of the upper face's corners (not a clipped point).
type Vertex = ([f64; 2], bool);

/// The polygon `poly` clipped to the half-plane `a . (s, t) <= b` (Sutherland & Hodgman): its
/// points inside, those within `band` of the line counting as on it (kept, no crossing beside
/// them), and where its edges cross the line from beyond `band` on one side to beyond it on the
/// other.
fn clip(poly: &[Vertex], a: [f64; 2], b: f64, band: f64) -> Vec<Vertex> {
    let f = |v: &Vertex| a[0] * v.0[0] + a[1] * v.0[1] - b;
    let mut out = Vec::new();
    for (i, cur) in poly.iter().enumerate() {
        let prev = &poly[(i + poly.len() - 1) % poly.len()];
        let (fp, fc) = (f(prev), f(cur));
        if (fp < -band && fc > band) || (fp > band && fc < -band) {
            let t = fp / (fp - fc);
            out.push((
                [prev.0[0] + t * (cur.0[0] - prev.0[0]), prev.0[1] + t * (cur.0[1] - prev.0[1])],
                false,
            ));
        }
        if fc <= band {
            out.push(*cur);
        }
    }
    out
}

/// The active contacts of docs/scenes.md, "stack-3d", "Contacts": each pair's overlap of the
/// upper block's bottom face, projected along the lower face's normal, with the lower face (the
/// table's `x <= 0`), a vertex within `64 eps (L + W)` of a side on it, coinciding vertices one
/// (the upper face's corner where one is); at each vertex the upper face's height over the lower one along its
/// normal. A vertex that is the upper face's corner is that corner on the lower face (the lower
/// face's normal); any other (the lower face's corner, the table's edge, where two edges cross)
/// is the lower body's point on the upper face (the upper face's normal, turned up).
#[must_use]
pub fn contacts(p: &Stack3d, blocks: &[Block]) -> Vec<Contact> {
    let half = p.half();
    let merge = 64.0 * f64::EPSILON * (p.length + p.width);
    let mut out = Vec::new();
    for (upper, b) in blocks.iter().enumerate() {
        let lower = upper.checked_sub(1).map(|l| &blocks[l]);
        // The lower face's centre, axes and normal.
        let (centre, axes) = match lower {
            Some(l) => {
                let r = matrix_of(l.q);
                let col = |j: usize| [r[0][j], r[1][j], r[2][j]];
                (plus(l.x, times(half[2], col(2))), [col(0), col(1), col(2)])
            }
            None => (ZERO, [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]),
        };
        let n_lower = axes[2];
        let n_upper = up(b);
        let bottom = corner(b, half, [0.0, 0.0, -1.0]);
        let face: Vec<Vertex> = SIGNS
            .iter()
            .map(|s| {
                let c = minus(corner(b, half, [s[0], s[1], -1.0]), centre);
                ([dot(c, axes[0]), dot(c, axes[1])], true)
            })
            .collect();
        let mut poly = match lower {
            Some(_) => {
                [([1.0, 0.0], half[0]), ([-1.0, 0.0], half[0]), ([0.0, 1.0], half[1]), ([0.0, -1.0], half[1])]
                    .iter()
                    .fold(face, |poly, &(a, limit)| clip(&poly, a, limit, merge))
            }
            None => clip(&face, [1.0, 0.0], 0.0, merge),
        };
        // Coinciding vertices are one, the upper face's corner where one of them is.
        poly.dedup_by(|later, kept| {
            let same = (later.0[0] - kept.0[0]).hypot(later.0[1] - kept.0[1]) <= merge;
            if same && later.1 && !kept.1 {
                *kept = *later;
            }
            same
        });
        if poly.len() > 1
            && (poly[0].0[0] - poly[poly.len() - 1].0[0]).hypot(poly[0].0[1] - poly[poly.len() - 1].0[1])
                <= merge
        {
            let last = poly.pop().unwrap_or(poly[0]);
            if last.1 && !poly[0].1 {
                poly[0] = last;
            }
        }
        for ([s, t], is_corner) in poly {
            let on_lower = plus(centre, plus(times(s, axes[0]), times(t, axes[1])));
            let across = dot(n_upper, n_lower);
            if across <= 0.0 {
                continue;
            }
            // The upper face over `on_lower`, along the lower face's normal.
            let lambda = dot(n_upper, minus(bottom, on_lower)) / across;
            let (point, normal, gap) = if is_corner {
                (plus(on_lower, times(lambda, n_lower)), n_lower, lambda)
            } else {
                (on_lower, n_upper, lambda * across)
            };
            if gap <= p.margin {
                out.push(Contact { upper, lower: upper.checked_sub(1), point, normal, gap });
            }
        }
    }
    out
}

/// Runs the stack to its outcome, keeping the rows `keep` asks for.
///
/// # Errors
/// [`Error::Invalid`], [`Error::TooManySteps`], [`Error::Sliding`] (a step beyond the cases this
/// reference answers), [`Error::Unsolved`], [`Error::NonFinite`].
pub fn run_stack_3d_keeping(p: &Stack3d, keep: Keep) -> Result<StackRun, Error> {
    p.validate()?;
    let steps_f = (p.max_time / p.h).ceil();
    if steps_f > MAX_STEPS as f64 {
        return Err(Error::TooManySteps { steps: steps_f });
    }
    let mut blocks = p.start();
    let start_z: Vec<f64> = blocks.iter().map(|b| b.x[2]).collect();
    let reach = 0.5 * (p.length * p.length + p.width * p.width + p.height * p.height).sqrt();
    let row = |t: f64, bs: &[Block]| (t, bs.iter().map(|b| b.x).collect(), bs.iter().map(|b| b.q).collect());
    let motion_of = |bs: &[Block]| bs.iter().map(|b| (b.v, b.omega)).collect::<Vec<_>>();
    let mut trajectory = vec![row(0.0, &blocks)];
    let mut motion = vec![motion_of(&blocks)];
    let (mut steps, mut max_speed) = (0u64, 0.0f64);
    let mut table_impulse;
    let outcome = loop {
        let (next, table) = step(p, &blocks).map_err(|e| e.at(steps + 1))?;
        steps += 1;
        blocks = next;
        table_impulse = table;
        let t = steps as f64 * p.h;
        if blocks.iter().any(|b| !b.x.iter().chain(&b.q).chain(&b.v).chain(&b.omega).all(|x| x.is_finite())) {
            return Err(Error::NonFinite { step: steps });
        }
        for b in &blocks {
            max_speed = max_speed.max(length(b.v) + reach * length(b.omega));
        }
        if keep == Keep::All {
            trajectory.push(row(t, &blocks));
            motion.push(motion_of(&blocks));
        }
        let fell = blocks
            .iter()
            .zip(&start_z)
            .any(|(b, z0)| up(b)[2].clamp(-1.0, 1.0).acos() > p.tilt_limit || z0 - b.x[2] > p.drop_limit);
        if fell {
            break Outcome::Fell;
        }
        if t >= p.max_time {
            break Outcome::Held;
        }
    };
    if keep != Keep::All {
        trajectory.push(row(steps as f64 * p.h, &blocks));
        motion.push(motion_of(&blocks));
    }
    Ok(StackRun { outcome, steps, max_speed, trajectory, motion, table_impulse })
}

/// Why a step has no answer here.
enum StepFailure {
    Sliding,
    Unsolved,
}

impl StepFailure {
    fn at(self, step: u64) -> Error {
        match self {
            Self::Sliding => Error::Sliding { step },
            Self::Unsolved => Error::Unsolved { step },
        }
    }
}

/// One step (module docs): the blocks after it and the table's normal impulse. Every loaded
/// contact sticks here, so every step's friction coefficient is `mu_s`.
fn step(p: &Stack3d, blocks: &[Block]) -> Result<(Vec<Block>, f64), StepFailure> {
    let (h, gravity) = (p.h, [0.0, 0.0, -p.g]);
    let moments = p.moments();
    let inverse: Vec<M3> =
        blocks.iter().map(|b| congruent(&matrix_of(b.q), moments.map(|i| 1.0 / i))).collect();
    let v_free: Vec<(V3, V3)> = blocks.iter().map(|b| (plus(b.v, times(h, gravity)), b.omega)).collect();
    let cs = contacts(p, blocks);
    let k = cs.len();
    // Rows `3 c + a`: `a = 0` the normal, 1 and 2 the tangents.
    let dirs: Vec<[V3; 3]> = cs
        .iter()
        .map(|c| {
            let t1 = super::algebra::some_perpendicular(c.normal);
            [c.normal, t1, cross(c.normal, t1)]
        })
        .collect();
    // Each row's action on each block it touches: (block, linear, angular) with the sign.
    let action = |c: &Contact, e: V3| -> Vec<(usize, V3, V3)> {
        let mut a = vec![(c.upper, e, cross(minus(c.point, blocks[c.upper].x), e))];
        if let Some(l) = c.lower {
            a.push((l, times(-1.0, e), cross(minus(c.point, blocks[l].x), times(-1.0, e))));
        }
        a
    };
    let rows: Vec<Vec<(usize, V3, V3)>> =
        (0..3 * k).map(|r| action(&cs[r / 3], dirs[r / 3][r % 3])).collect();
    let n = 3 * k;
    let mut w = vec![0.0; n * n];
    for i in 0..n {
        for j in 0..n {
            let mut sum = 0.0;
            for &(bi, li, ai) in &rows[i] {
                for &(bj, lj, aj) in &rows[j] {
                    if bi == bj {
                        sum += dot(li, lj) / p.mass + dot(ai, apply(&inverse[bi], aj));
                    }
                }
            }
            w[i * n + j] = sum;
        }
    }
    let mut u = vec![0.0; n];
    for (r, acts) in rows.iter().enumerate() {
        u[r] = acts.iter().map(|&(b, l, a)| dot(l, v_free[b].0) + dot(a, v_free[b].1)).sum();
    }
    for (c, contact) in cs.iter().enumerate() {
        let size: f64 = contact.point.iter().map(|x| x.abs()).sum::<f64>()
            + [Some(contact.upper), contact.lower]
                .into_iter()
                .flatten()
                .map(|b| blocks[b].x.iter().map(|x| x.abs()).sum::<f64>() + p.length)
                .sum::<f64>();
        u[3 * c] += bias(contact.gap, h, p.g, 4.0 * f64::EPSILON * size);
    }
    let impulse = if k == 0 { Vec::new() } else { stuck_or_apart(&w, &u, k, p.mu_s)? };
    // Apply.
    let mut next: Vec<Block> = blocks.to_vec();
    let mut dv: Vec<(V3, V3)> = vec![(ZERO, ZERO); blocks.len()];
    for (r, acts) in rows.iter().enumerate() {
        for &(b, l, a) in acts {
            dv[b].0 = plus(dv[b].0, times(impulse[r] / p.mass, l));
            dv[b].1 = plus(dv[b].1, times(impulse[r], apply(&inverse[b], a)));
        }
    }
    for (b, blk) in next.iter_mut().enumerate() {
        let v = plus(v_free[b].0, dv[b].0);
        let omega = plus(v_free[b].1, dv[b].1);
        let (q, omega) = turned(moments, h, blk.q, omega);
        *blk = Block { x: plus(blk.x, times(h, v)), q, v, omega };
    }
    let table = cs.iter().enumerate().filter(|(_, c)| c.lower.is_none()).map(|(i, _)| impulse[3 * i]).sum();
    Ok((next, table))
}

/// The impulses (module docs, "Sticking or separated") of the `k` contacts' rows `(W, u)`
/// (`3 k` rows, normal first per contact), each contact's friction coefficient `mu`.
fn stuck_or_apart(w: &[f64], u: &[f64], k: usize, mu: f64) -> Result<Vec<f64>, StepFailure> {
    let n = 3 * k;
    let after = |p: &[f64]| -> Vec<f64> {
        (0..n).map(|r| u[r] + (0..n).map(|c| w[r * n + c] * p[c]).sum::<f64>()).collect()
    };
    let speed = u.iter().fold(f64::MIN_POSITIVE, |a, x| a.max(x.abs()));
    let rows_of = |on: &[bool]| -> Vec<usize> {
        (0..k).filter(|&c| on[c]).flat_map(|c| [3 * c, 3 * c + 1, 3 * c + 2]).collect()
    };
    // The contacts on (all three rows closed: loaded and stuck) and off (no impulse), by the
    // active-set method of nonnegative least squares (Lawson & Hanson) on the blocks: on from
    // none, each round the off contact that approaches fastest is put on; where a solve would
    // pull a contact (`p_n < 0`) the step goes only as far as the first to unload, which goes
    // off.
    let mut on = vec![false; k];
    let mut p = vec![0.0; n];
    for _ in 0..LOAD_SETS * k.max(1) {
        let w_after = after(&p);
        let entering = (0..k)
            .filter(|&c| !on[c] && w_after[3 * c] < -1e-12 * speed)
            .min_by(|&a, &b| w_after[3 * a].total_cmp(&w_after[3 * b]));
        let Some(c) = entering else {
            // Every off contact separates: the least-norm load of the on ones where it pulls none.
            // Every off contact separates: the least-norm load of the on ones where it pulls none
            // and keeps every friction within its cone, else the internal impulses that do.
            let scale = (0..k).map(|c| p[3 * c]).fold(f64::MIN_POSITIVE, f64::max);
            let (spread, null) = least_norm_and_null(w, u, n, &rows_of(&on)).ok_or(StepFailure::Unsolved)?;
            let carries = |q: &[f64]| -> Vec<bool> { (0..k).map(|c| q[3 * c] > 1e-9 * scale).collect() };
            if (0..k).all(|c| spread[3 * c] >= -1e-12 * scale)
                && check(w, u, k, mu, &carries(&spread), &spread).is_ok()
            {
                return Ok(spread);
            }
            let answer = into_cone(&spread, &null, k, mu).ok_or(StepFailure::Sliding)?;
            check(w, u, k, mu, &carries(&answer), &answer)?;
            return Ok(answer);
        };
        on[c] = true;
        // Solve on the on set; back off along the way while a load would turn negative.
        loop {
            let target = least_norm(w, u, n, &rows_of(&on)).ok_or(StepFailure::Unsolved)?;
            let pulled = (0..k).filter(|&c| on[c] && target[3 * c] < 0.0);
            let Some((first, t)) =
                pulled.map(|c| (c, p[3 * c] / (p[3 * c] - target[3 * c]))).min_by(|a, b| a.1.total_cmp(&b.1))
            else {
                p = target;
                break;
            };
            p = p.iter().zip(&target).map(|(a, b)| a + t * (b - a)).collect();
            for r in 0..3 {
                p[3 * first + r] = 0.0;
            }
            on[first] = false;
        }
    }
    Err(StepFailure::Unsolved)
}

/// The least-norm impulse of the rows `rows` of `(W, u)` (`n` rows in all), `W_RR p = -u_R`, the
/// other rows' impulses zero; `None` when the decomposition fails.
fn least_norm(w: &[f64], u: &[f64], n: usize, rows: &[usize]) -> Option<Vec<f64>> {
    least_norm_and_null(w, u, n, rows).map(|(p, _)| p)
}

/// [`least_norm`] and the null space of `W_RR` (each vector over all `n` rows, zero off `R`):
/// the internal impulses, which move nothing.
fn least_norm_and_null(w: &[f64], u: &[f64], n: usize, rows: &[usize]) -> Option<(Vec<f64>, Vec<Vec<f64>>)> {
    let mut p = vec![0.0; n];
    if rows.is_empty() {
        return Some((p, Vec::new()));
    }
    let columns: Vec<Vec<f64>> = rows.iter().map(|&c| rows.iter().map(|&r| w[r * n + c]).collect()).collect();
    let svd = Svd::of(&columns)?;
    let b: Vec<f64> = rows.iter().map(|&r| -u[r]).collect();
    let (mut x, null) = svd.solve(&b, 1e-14);
    // One round of iterative refinement: the residual's own least-norm correction.
    let residual: Vec<f64> = rows
        .iter()
        .zip(&b)
        .map(|(&r, bi)| bi - rows.iter().zip(&x).map(|(&c, xc)| w[r * n + c] * xc).sum::<f64>())
        .collect();
    let (dx, _) = svd.solve(&residual, 1e-14);
    x.iter_mut().zip(dx).for_each(|(a, d)| *a += d);
    for (&r, v) in rows.iter().zip(x) {
        p[r] = v;
    }
    let full = |v: &Vec<f64>| {
        let mut f = vec![0.0; n];
        for (&r, x) in rows.iter().zip(v) {
            f[r] = *x;
        }
        f
    };
    Some((p, null.iter().map(full).collect()))
}

/// The answer `p` moved by internal impulses (`null`, which change no velocity) until every
/// loaded contact's friction is within its cone, `|p_t| <= mu p_n`, and no load pulls: Gauss-Newton
/// steps on the violated conditions (least-norm corrections, halved while the violation does not
/// shrink), at most 64; `None` when they do not get there.
fn into_cone(p: &[f64], null: &[Vec<f64>], k: usize, mu: f64) -> Option<Vec<f64>> {
    let scale = (0..k).map(|c| p[3 * c].abs()).fold(f64::MIN_POSITIVE, f64::max);
    let margin = 1e-9 * scale;
    let at = |y: &[f64]| -> Vec<f64> {
        let mut q = p.to_vec();
        for (v, yj) in null.iter().zip(y) {
            q.iter_mut().zip(v).for_each(|(a, b)| *a += yj * b);
        }
        q
    };
    // The violated conditions at `q` (value, gradient over `y`).
    let violated = |q: &[f64]| -> Vec<(f64, Vec<f64>)> {
        let mut out = Vec::new();
        for c in 0..k {
            let (pn, t) = (q[3 * c], [q[3 * c + 1], q[3 * c + 2]]);
            let size = t[0].hypot(t[1]);
            if size == 0.0 && pn == 0.0 {
                continue;
            }
            let g = size - mu * pn + margin;
            if g > 0.0 {
                let grad = null
                    .iter()
                    .map(|v| {
                        let along =
                            if size > 0.0 { (t[0] * v[3 * c + 1] + t[1] * v[3 * c + 2]) / size } else { 0.0 };
                        along - mu * v[3 * c]
                    })
                    .collect();
                out.push((g, grad));
            }
            if pn < 0.0 {
                out.push((-pn, null.iter().map(|v| -v[3 * c]).collect()));
            }
        }
        out
    };
    let total = |v: &[(f64, Vec<f64>)]| v.iter().map(|(g, _)| g * g).sum::<f64>();
    let mut y = vec![0.0; null.len()];
    for _ in 0..64 {
        let q = at(&y);
        let bad = violated(&q);
        if bad.is_empty() {
            return Some(q);
        }
        // The least-norm dy with J dy = -g: dy = J^T (J J^T)^+ (-g).
        let a: Vec<Vec<f64>> = bad
            .iter()
            .map(|(_, gi)| bad.iter().map(|(_, gj)| gi.iter().zip(gj).map(|(x, z)| x * z).sum()).collect())
            .collect();
        let (z, _) = Svd::of(&a)?.solve(&bad.iter().map(|(g, _)| -g).collect::<Vec<_>>(), 1e-14);
        let dy: Vec<f64> =
            (0..y.len()).map(|j| bad.iter().zip(&z).map(|((_, g), zi)| g[j] * zi).sum()).collect();
        let before = total(&bad);
        let mut step = 1.0;
        loop {
            let trial: Vec<f64> = y.iter().zip(&dy).map(|(a, d)| a + step * d).collect();
            if total(&violated(&at(&trial))) < before || step < 1e-6 {
                y = trial;
                break;
            }
            step *= 0.5;
        }
    }
    None
}

/// Every condition of a sticking-or-separated answer `p`: the normal rows complementary, the
/// loaded contacts' slips zero, the unloaded ones' friction zero, each friction within `mu p_n`
/// (else the contact would slide: [`StepFailure::Sliding`]); the tolerances from the data.
fn check(w: &[f64], u: &[f64], k: usize, mu: f64, loaded: &[bool], p: &[f64]) -> Result<(), StepFailure> {
    let n = 3 * k;
    let after: Vec<f64> = (0..n).map(|r| u[r] + (0..n).map(|c| w[r * n + c] * p[c]).sum::<f64>()).collect();
    let w_norm = (0..n).map(|r| (0..n).map(|c| w[r * n + c].abs()).sum::<f64>()).fold(0.0, f64::max);
    let p_norm = p.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let u_norm = u.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    // Round-off's, or `1e-8` of the step's velocities: a block on its corners and on the table's
    // edge at once has more normal rows than the three motions they close (its corners' gaps
    // along `z`, the edge's along the face's normal), consistent only to the face's tilt; they
    // are met in least squares.
    let tol = (1e3 * n as f64 * f64::EPSILON * (w_norm * p_norm + u_norm)).max(1e-8 * u_norm);
    for c in 0..k {
        let (pn, wn) = (p[3 * c], after[3 * c]);
        if pn < -tol || wn < -tol || pn.min(wn).abs() > tol {
            return Err(StepFailure::Unsolved);
        }
        let friction = p[3 * c + 1].hypot(p[3 * c + 2]);
        if loaded[c] {
            if after[3 * c + 1].abs() > tol || after[3 * c + 2].abs() > tol {
                return Err(StepFailure::Unsolved);
            }
            if friction > mu * pn + tol {
                return Err(StepFailure::Sliding);
            }
        } else if friction > tol {
            return Err(StepFailure::Unsolved);
        }
    }
    Ok(())
}
