//! The load where rigid contact leaves it open (docs/formulation.md, "The load: the least norm"),
//! by exhaustive enumeration of active sets: the core's own method (an LCP of the least-norm
//! problem's optimality conditions, solved by Lemke's method) is not used here.
//!
//! With the step's motion fixed, the touching contacts may carry any load `x = (x_n, x_f)` per
//! contact with the same momentum change, `sum_c x_n W_n,c + x_f W_d,c = r`, within their laws: a
//! sticking contact `x_n >= 0`, `|x_f| <= mu x_n`; a sliding one `x_n >= 0`, `x_f = f x_n` (`f`
//! the signed coefficient against its slip). The answer is the load of least `||x||_2`.
//!
//! The problem is strictly convex, so its minimiser is unique, and it is the minimiser of `||x||`
//! over the equalities and the inequalities binding at it, taken as equalities. So subsets of the
//! inequalities are tried as equalities, the smallest first: each gives the least-norm solution of
//! a linear system (rows chosen independent by Gaussian elimination with partial pivoting, then the
//! normal equations `G G^T y = g`, `x = G^T y`, `y` the multipliers), and the first that satisfies
//! every inequality with a non-negative multiplier on each binding one (the Karush-Kuhn-Tucker
//! conditions, which one point satisfies) is the answer. A resting body's load usually binds
//! nothing: one solve.

/// What a touching contact may carry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Law {
    /// `x_n >= 0`, `|x_f| <= mu x_n`.
    Sticking { mu: f64 },
    /// `x_n >= 0`, `x_f = f x_n`.
    Sliding { f: f64 },
}

/// A touching contact: its normal and friction columns in the bodies' coordinates (`3B` long),
/// its law.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Touching {
    pub normal: Vec<f64>,
    pub tangent: Vec<f64>,
    pub law: Law,
}

/// The least-norm load over `contacts` with the momentum change `r`, `(x_n, x_f)` per contact;
/// `None` when the equalities alone decide the load (the step's LCP answer is then the only one)
/// or no subset gives a feasible point (the motion is not reachable within the laws).
pub(crate) fn least_norm(contacts: &[Touching], r: &[f64], scale: f64) -> Option<Vec<[f64; 2]>> {
    let n = 2 * contacts.len();
    if n == 0 {
        return Some(Vec::new());
    }
    let (equalities, inequalities) = rows(contacts, r);
    let tolerance = 1e-12 * scale.max(f64::MIN_POSITIVE);
    if rank(&equalities) == n {
        return None; // determinate: the LCP's answer is the only load
    }
    // Subsets by their size: the first whose equality-constrained minimiser satisfies every
    // inequality with non-negative multipliers on its binding ones is the minimiser (the
    // Karush-Kuhn-Tucker conditions of a strictly convex problem: one point satisfies them).
    let m = inequalities.len();
    for subset in subsets_by_size(m) {
        let mut rows: Vec<(Vec<f64>, f64)> = equalities.clone();
        for (j, a) in inequalities.iter().enumerate() {
            if subset >> j & 1 == 1 {
                rows.push((a.clone(), 0.0));
            }
        }
        let Some((x, multipliers)) = min_norm_solution(&rows, tolerance) else { continue };
        let feasible = inequalities.iter().all(|a| dot(a, &x) >= -tolerance);
        let binding_hold = multipliers.iter().all(|&(row, y)| row < equalities.len() || y >= -tolerance);
        if feasible && binding_hold {
            return Some(x.chunks(2).map(|p| [p[0], p[1]]).collect());
        }
    }
    None
}

/// Rows with their values: `row . x = value`.
type Equalities = Vec<(Vec<f64>, f64)>;

/// Every subset of `m < 64` items as a bit set, the smaller first (Gosper's hack within a size):
/// the first few sizes are all a load usually needs, and none is made before it is asked for.
fn subsets_by_size(m: usize) -> impl Iterator<Item = u64> {
    let full: u64 = if m >= 64 { u64::MAX } else { (1u64 << m) - 1 };
    (0..=m).flat_map(move |size| {
        let first: u64 = if size == 0 { 0 } else { (1u64 << size) - 1 };
        std::iter::successors(Some(first), move |&set| {
            if set == 0 {
                return None;
            }
            let low = set & set.wrapping_neg();
            let ripple = set + low;
            let next = (((ripple ^ set) >> 2) / low) | ripple;
            (next <= full && next.count_ones() as usize == size).then_some(next)
        })
        .take_while(move |&set| set <= full)
    })
}

/// `true` when the contacts' equalities alone decide the load (their rank is the number of
/// unknowns): the step's LCP answer is then the only load.
pub(crate) fn determinate(contacts: &[Touching]) -> bool {
    let coordinates = contacts.first().map_or(0, |c| c.normal.len());
    rank(&rows(contacts, &vec![0.0; coordinates]).0) == 2 * contacts.len()
}

/// The equalities `(row, value)` (the momentum change `r`, each sliding contact's friction law)
/// and the inequality rows (`x_n >= 0`, the sticking contacts' cone) over the unknowns
/// `(x_n, x_f)` per contact.
fn rows(contacts: &[Touching], r: &[f64]) -> (Equalities, Vec<Vec<f64>>) {
    let n = 2 * contacts.len();
    let mut equalities: Vec<(Vec<f64>, f64)> = (0..r.len())
        .map(|k| {
            let row = contacts.iter().flat_map(|c| [c.normal[k], c.tangent[k]]).collect();
            (row, r[k])
        })
        .collect();
    let mut inequalities: Vec<Vec<f64>> = Vec::new();
    for (i, c) in contacts.iter().enumerate() {
        let unit = |a: f64, b: f64| {
            let mut row = vec![0.0; n];
            row[2 * i] = a;
            row[2 * i + 1] = b;
            row
        };
        inequalities.push(unit(1.0, 0.0));
        match c.law {
            Law::Sticking { mu } => {
                inequalities.push(unit(mu, -1.0));
                inequalities.push(unit(mu, 1.0));
            }
            Law::Sliding { f } => equalities.push((unit(-f, 1.0), 0.0)),
        }
    }
    (equalities, inequalities)
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The indices of a largest set of independent rows: each row reduced against the echelon rows
/// kept so far (Gaussian elimination with partial pivoting by column), kept when something of it
/// is left beyond round-off of its own size.
fn independent(rows: &[(Vec<f64>, f64)]) -> Vec<usize> {
    let mut echelon: Vec<(Vec<f64>, usize)> = Vec::new();
    let mut kept: Vec<usize> = Vec::new();
    for (i, (row, _)) in rows.iter().enumerate() {
        let size = row.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        let mut rest = row.clone();
        for (e, pivot) in &echelon {
            let k = rest[*pivot] / e[*pivot];
            for (r, x) in rest.iter_mut().zip(e) {
                *r -= k * x;
            }
        }
        let (pivot, largest) = rest
            .iter()
            .enumerate()
            .fold((0, 0.0_f64), |b, (j, x)| if x.abs() > b.1 { (j, x.abs()) } else { b });
        if largest > 1e-10 * size {
            echelon.push((rest, pivot));
            kept.push(i);
        }
    }
    kept
}

/// The rank of the rows.
fn rank(rows: &[(Vec<f64>, f64)]) -> usize {
    independent(rows).len()
}

/// The least-norm `x` with `row . x = value` for every `(row, value)`, with the multiplier `y`
/// of each row kept (`x = sum y_row row`; a row dependent on earlier ones has none); `None` when
/// the rows are inconsistent beyond `tolerance`.
#[allow(clippy::type_complexity)]
fn min_norm_solution(rows: &[(Vec<f64>, f64)], tolerance: f64) -> Option<(Vec<f64>, Vec<(usize, f64)>)> {
    let n = rows.first()?.0.len();
    let kept = independent(rows);
    // Normal equations of the kept rows, solved by Gaussian elimination with partial pivoting.
    let m = kept.len();
    let mut a: Vec<Vec<f64>> = kept
        .iter()
        .map(|&i| {
            let mut line: Vec<f64> = kept.iter().map(|&j| dot(&rows[i].0, &rows[j].0)).collect();
            line.push(rows[i].1);
            line
        })
        .collect();
    for col in 0..m {
        let pivot = (col..m).max_by(|&p, &q| a[p][col].abs().total_cmp(&a[q][col].abs()))?;
        a.swap(col, pivot);
        if a[col][col] == 0.0 {
            return None;
        }
        for r in 0..m {
            if r != col {
                let k = a[r][col] / a[col][col];
                for c in col..=m {
                    a[r][c] -= k * a[col][c];
                }
            }
        }
    }
    let mut x = vec![0.0; n];
    let mut multipliers = Vec::with_capacity(m);
    for (r, &i) in kept.iter().enumerate() {
        let y = a[r][m] / a[r][r];
        multipliers.push((i, y));
        for (xc, gc) in x.iter_mut().zip(&rows[i].0) {
            *xc += y * gc;
        }
    }
    // Consistent within round-off of the terms each row sums (a row dropped as dependent within
    // its elimination's 1e-10 still holds to that), or within `tolerance`.
    let consistent = |(row, value): &(Vec<f64>, f64)| {
        let size: f64 = row.iter().zip(&x).map(|(a, b)| (a * b).abs()).sum::<f64>() + value.abs();
        (dot(row, &x) - value).abs() <= tolerance.max(1e-9 * size)
    };
    rows.iter().all(consistent).then_some((x, multipliers))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;

    fn rod(xs: &[f64]) -> Vec<Touching> {
        xs.iter()
            .map(|&x| Touching {
                normal: vec![0.0, 1.0, x],
                tangent: vec![1.0, 0.0, 0.0025],
                law: Law::Sticking { mu: 0.6 },
            })
            .collect()
    }

    #[test]
    fn three_fingers_carry_an_affine_split_and_a_puller_nothing() {
        // Centre of mass at 0 between fingers -0.45, -0.05, 0.3: N = a + b x, all positive.
        let xs = [-0.45, -0.05, 0.3];
        let x = least_norm(&rod(&xs), &[0.0, 1.0, 0.0], 1.0).unwrap();
        let (s1, s2) = (xs.iter().sum::<f64>(), xs.iter().map(|x| x * x).sum::<f64>());
        let b = -s1 / (3.0 * s2 - s1 * s1);
        let a = (1.0 - b * s1) / 3.0;
        for (p, xi) in x.iter().zip(xs) {
            assert!((p[0] - (a + b * xi)).abs() < 1e-13 && p[1].abs() < 1e-13, "{x:?}");
        }
        // Fingers -0.4, -0.3, 0.02: the affine split would pull at -0.4, which carries nothing.
        let x = least_norm(&rod(&[-0.4, -0.3, 0.02]), &[0.0, 1.0, 0.0], 1.0).unwrap();
        let expected = [0.0, 0.02 / 0.32, 0.3 / 0.32];
        for (p, e) in x.iter().zip(expected) {
            assert!((p[0] - e).abs() < 1e-13, "{x:?}");
        }
    }

    #[test]
    fn subsets_come_by_size_each_once() {
        for m in 0..=10 {
            let all: Vec<u64> = subsets_by_size(m).collect();
            assert_eq!(all.len(), 1 << m, "m = {m}");
            assert!(all.windows(2).all(|w| w[0].count_ones() <= w[1].count_ones()), "m = {m}");
            let mut sorted = all.clone();
            sorted.sort_unstable();
            sorted.dedup();
            assert_eq!(sorted.len(), 1 << m, "m = {m}");
        }
    }

    #[test]
    fn a_load_outside_the_laws_is_none() {
        // A sideways push larger than friction can hold on two sticking fingers.
        let two = rod(&[-0.1, 0.1]);
        assert!(!determinate(&two));
        assert!(least_norm(&two, &[1.0, 1.0, 0.0025], 1.0).is_none());
        assert!(least_norm(&two, &[0.5, 1.0, 0.00125], 1.0).is_some());
    }
}
