//! The bodies a step's contacts push: how an impulse at one contact moves the others (the
//! Delassus operator `W`), and the bodies' motion after the impulses, for one body on a plane or
//! supports (`B = 1`) and for several bodies resting on each other.
//!
//! Contact `i` pushes its body `a` with `+p` at the arm `r_a` from `a`'s centre of mass and, when
//! it rests on another body `b` (not a fixed plane or support), pushes `b` with `-p` at the arm
//! `r_b`; its velocity is `a`'s point's less `b`'s point's less the support's material's
//! ([`Touch::carried`]). Impulses are per unit of a reference mass `m0` (the first body's): a
//! body of mass `m` and world inertia `I_w` moves by `(m0 / m) p` and turns by `m0 I_w^-1 (r x
//! p)`, and
//!
//! ```text
//! e . W_ij f = sum over the bodies c both contacts push, s_i s_j [ (m0 / m_c) e . f
//!              + m0 (r_ic x e) . I_c^-1 (r_jc x f) ]
//! ```
//!
//! (`s = +1` for a contact's body, `-1` for the one beneath it). With one body `m0 / m = 1` and the
//! sum has one term: the one-body operator of `super`'s module docs (2), which one body's paths
//! compute as they did (`B == 1`, folded at compile time: the same operations in the same order).

use super::algebra::{Vector, add, cross, dot, scale, sub};
use super::body::{Body, InverseInertia, Motion};
use super::friction::{Contacts, System, Touch, put_row, solved};
use crate::real::Real;

/// One side of a contact along one direction `e` (a body it pushes, `sign` the impulse's on it):
/// `r x e` and `I_w^-1 (r x e)`, computed once a contact and direction for the LCP's entries.
#[derive(Debug, Clone, Copy)]
pub(super) struct Side<T> {
    body: usize,
    pushed: bool,
    lever: Vector<T>,
    turn: Vector<T>,
}

impl<T: Real, const K: usize, const B: usize> Contacts<'_, T, K, B> {
    /// The sides of contact `c` along `e`: its body's, then the one beneath it (if any).
    pub(super) fn sides(&self, c: &Touch<T>, e: &Vector<T>) -> [Option<Side<T>>; 2] {
        let side = |body: usize, pushed: bool, arm: &Vector<T>| {
            let frame = self.bodies.get(body)?;
            let lever = cross(arm, e);
            Some(Side { body, pushed, lever, turn: frame.inverse_inertia.times(&lever) })
        };
        if B == 1 {
            return [side(0, true, &c.arm), None];
        }
        [side(c.body, true, &c.arm), c.beneath.and_then(|(b, arm)| side(b, false, &arm))]
    }

    /// Whether contacts `a` and `b` push a body in common (their bodies, or those beneath them).
    pub(super) fn share_a_body(a: &Touch<T>, b: &Touch<T>) -> bool {
        let bodies = |c: &Touch<T>| [Some(c.body), c.beneath.map(|(body, _)| body)];
        let [a0, a1] = bodies(a);
        let [b0, b1] = bodies(b);
        a0 == b0 || a0 == b1 || (a1.is_some() && (a1 == b0 || a1 == b1))
    }

    /// `e . W f` (module docs) from the [`Self::sides`] of the contacts along `e` and `f`.
    pub(super) fn coupling(
        &self,
        a: &[Option<Side<T>>; 2],
        e: &Vector<T>,
        b: &[Option<Side<T>>; 2],
        f: &Vector<T>,
    ) -> T {
        if B == 1 {
            // One body: `e . f + m (r x e) . I_w^-1 (r' x f)`.
            return match (&a[0], &b[0]) {
                (Some(sa), Some(sb)) => dot(e, f) + self.mass * dot(&sa.lever, &sb.turn),
                _ => T::zero(),
            };
        }
        // Each pair of sides on one body in turn, `a`'s first then `b`'s: written out, not as
        // iterators over the options (the stack's LCP has `4 K^2` of these, most of its pairs on no
        // common body).
        let mut total = T::zero();
        let mut add_pair = |sa: &Side<T>, sb: &Side<T>| {
            if sb.body == sa.body {
                let inverse_mass = self.bodies.get(sa.body).map_or(T::zero(), |frame| frame.inverse_mass);
                let term = inverse_mass * dot(e, f) + self.mass * dot(&sa.lever, &sb.turn);
                total = if sa.pushed == sb.pushed { total + term } else { total - term };
            }
        };
        for sa in [&a[0], &a[1]] {
            let Some(sa) = sa else { continue };
            if let Some(sb) = &b[0] {
                add_pair(sa, sb);
            }
            if let Some(sb) = &b[1] {
                add_pair(sa, sb);
            }
        }
        total
    }

    /// `e . W f` between a unit impulse along `f` at contact `cf` and contact `ce`'s velocity
    /// along `e` (module docs): [`Self::coupling`] of `ce`'s [`Self::levers`] and `cf`'s
    /// [`Self::sides`].
    pub(super) fn delassus(&self, ce: &Touch<T>, e: &Vector<T>, cf: &Touch<T>, f: &Vector<T>) -> T {
        self.coupling(&Self::levers(ce, e), e, &self.sides(cf, f), f)
    }

    /// The sides of contact `c` along `e` as [`Self::sides`], but for their turns (zero): all
    /// [`Self::coupling`] reads of the sides it is given first.
    pub(super) fn levers(c: &Touch<T>, e: &Vector<T>) -> [Option<Side<T>>; 2] {
        let levers = |body: usize, pushed: bool, arm: &Vector<T>| {
            Some(Side { body, pushed, lever: cross(arm, e), turn: [T::zero(); 3] })
        };
        if B == 1 {
            return [levers(0, true, &c.arm), None];
        }
        [levers(c.body, true, &c.arm), c.beneath.and_then(|(b, arm)| levers(b, false, &arm))]
    }

    /// The turn's linear system (`Contacts::turn`) solved in a `D x D` array (`m <= D` unknowns, the
    /// rest `x = 0`), its answer by unknown: the elimination's loops run over the array, so the
    /// meter stick's six or nine unknowns are not solved in the problem's `N x N`; the same
    /// operations on them either way.
    pub(super) fn turn_solved<const D: usize, const N: usize>(
        &self,
        system: &System<'_, T, [Option<Side<T>>; 2], K>,
    ) -> [T; N] {
        let (zero, one) = (T::zero(), T::one());
        let mut jac = [[zero; D]; D];
        let mut rhs = [zero; D];
        for (r, row) in jac.iter_mut().enumerate() {
            put_row(row, r, one);
        }
        for (r, ((row, b), &(i, e, residual, own))) in
            jac.iter_mut().zip(rhs.iter_mut()).zip(system.rows).enumerate()
        {
            let Some(ci) = self.touches.get(i) else { continue };
            *b = residual;
            put_row(row, r, own);
            let levers = Self::levers(ci, &e);
            for (entry, &(j, k)) in row.iter_mut().zip(system.unknowns) {
                if let Some((f, sides)) = system.effects.get(j).and_then(|unknowns| unknowns.get(k)) {
                    *entry += self.coupling(&levers, &e, sides, f);
                }
            }
        }
        let x = solved(jac, rhs);
        core::array::from_fn(|c| x.get(c).copied().unwrap_or(zero))
    }

    /// Contact `c`'s velocity in `motion`: its body's point's less the one beneath's less the
    /// support's material's.
    pub(super) fn velocity(motion: &Motion<T, B>, c: &Touch<T>) -> Vector<T> {
        if let (1, Some((v, w))) = (B, motion.first()) {
            return sub(&add(v, &cross(w, &c.arm)), &c.carried);
        }
        let at = |body: usize, arm: &Vector<T>| {
            motion.get(body).map_or([T::zero(); 3], |(v, w)| add(v, &cross(w, arm)))
        };
        let mut u = at(c.body, &c.arm);
        if let Some((b, arm)) = c.beneath {
            u = sub(&u, &at(b, &arm));
        }
        sub(&u, &c.carried)
    }

    /// Contact `c`'s slip in `motion`: its velocity's part in its plane.
    pub(super) fn slip_in(motion: &Motion<T, B>, c: &Touch<T>) -> Vector<T> {
        let u = Self::velocity(motion, c);
        sub(&u, &scale(dot(&c.normal, &u), &c.normal))
    }

    /// The motion after each active contact's impulse `p` (per unit reference mass, world axes)
    /// on the motion `free`.
    pub(super) fn moved_all(&self, p: &[Vector<T>; K], free: &Motion<T, B>) -> Motion<T, B> {
        if let (1, Some(frame)) = (B, self.bodies.first()) {
            // One body: `v~ + sum p`, `omega~ + m I_w^-1 sum r x p`.
            let (mut push, mut twist) = ([T::zero(); 3], [T::zero(); 3]);
            for (c, p) in self.touches.iter().zip(p).filter(|(c, _)| c.active) {
                push = add(&push, p);
                twist = add(&twist, &cross(&c.arm, p));
            }
            let turn = frame.inverse_inertia.times(&twist);
            let mut motion = *free;
            if let Some((v, w)) = motion.first_mut() {
                (*v, *w) = (add(v, &push), add(w, &scale(self.mass, &turn)));
            }
            return motion;
        }
        let (mut push, mut twist) = ([[T::zero(); 3]; B], [[T::zero(); 3]; B]);
        for (c, p) in self.touches.iter().zip(p).filter(|(c, _)| c.active) {
            if let (Some(v), Some(w)) = (push.get_mut(c.body), twist.get_mut(c.body)) {
                *v = add(v, p);
                *w = add(w, &cross(&c.arm, p));
            }
            if let Some((b, arm)) = c.beneath
                && let (Some(v), Some(w)) = (push.get_mut(b), twist.get_mut(b))
            {
                *v = sub(v, p);
                *w = sub(w, &cross(&arm, p));
            }
        }
        let mut motion = *free;
        for (((frame, (v, w)), push), twist) in self.bodies.iter().zip(&mut motion).zip(&push).zip(&twist) {
            let turn = frame.inverse_inertia.times(twist);
            (*v, *w) = (add(v, &scale(frame.inverse_mass, push)), add(w, &scale(self.mass, &turn)));
        }
        motion
    }

    /// Adds contact `c`'s impulse `change` (per unit reference mass) to `motion`.
    pub(super) fn push(&self, motion: &mut Motion<T, B>, c: &Touch<T>, change: &Vector<T>) {
        if let (1, Some(frame), Some((v, w))) = (B, self.bodies.first(), motion.first_mut()) {
            *v = add(v, change);
            let turn = frame.inverse_inertia.times(&cross(&c.arm, change));
            *w = add(w, &scale(self.mass, &turn));
            return;
        }
        let mut apply = |body: usize, arm: &Vector<T>, change: &Vector<T>| {
            if let (Some(frame), Some((v, w))) = (self.bodies.get(body), motion.get_mut(body)) {
                *v = add(v, &scale(frame.inverse_mass, change));
                let turn = frame.inverse_inertia.times(&cross(arm, change));
                *w = add(w, &scale(self.mass, &turn));
            }
        };
        apply(c.body, &c.arm, change);
        if let Some((b, arm)) = c.beneath {
            apply(b, &arm, &scale(-T::one(), change));
        }
    }
}

impl<T: Real, const K: usize> Contacts<'_, T, K> {
    /// The one body.
    pub(super) fn body(&self) -> &Body<T> {
        let [frame] = &self.bodies;
        frame.body
    }

    /// The one body's `I_w^-1` at the step's start.
    pub(super) fn inverse_inertia(&self) -> &InverseInertia<T> {
        let [frame] = &self.bodies;
        &frame.inverse_inertia
    }

    /// The body's velocity and angular velocity after each active contact's impulse `p` (per unit
    /// mass, world axes): `v~ + sum p`, `omega~ + m I_w^-1 sum r x p`.
    pub(super) fn moved(
        &self,
        p: &[Vector<T>; K],
        v_free: &Vector<T>,
        w_free: &Vector<T>,
    ) -> (Vector<T>, Vector<T>) {
        let [(v, w)] = self.moved_all(p, &[(*v_free, *w_free)]);
        (v, w)
    }

    /// Contact `c`'s slip at velocity `v` and angular velocity `w`: its point's velocity less the
    /// support's ([`Touch::carried`]), in the plane.
    pub(super) fn slip(v: &Vector<T>, w: &Vector<T>, c: &Touch<T>) -> Vector<T> {
        Self::slip_in(&[(*v, *w)], c)
    }
}
