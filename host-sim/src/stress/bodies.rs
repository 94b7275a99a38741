//! What one stress run of a scene of several bodies, or in three dimensions, measures, in f64, from what the core's
//! [`SceneView`] gives after every step (each body's pose and velocity, the step's pivots, the LCP's
//! capacity; the counterpart of [`super::metrics::measure`], which is shaped for one body):
//!
//! * **Energy** `E = sum_b m_b (vx^2 + vy^2) / 2 + J_b omega^2 / 2 + m_b g y_b` against the work of
//!   the scene's pull, `W = sum F . (x+ - x)` (the pull acts at the bottom block's or the board's
//!   centre of mass). The implicit step (`docs/formulation.md`, "Several bodies": `q+ = q + h v+`)
//!   gives `E+ - E <= F . h v+` up to what pushing out of a penetration adds, as for one body; the
//!   bodies start touching without penetration, so the allowance is round-off:
//!   `4096 N eps` of the energy scale `sum_b m_b (g (size_b + |y_b|) + |v_b|^2 + (size_b omega_b)^2)`
//!   plus `|F| size`.
//!   A body in three dimensions (no pull): `E = sum_b m_b |v_b|^2 / 2 + omega_b' I_b omega_b / 2 + m_b
//!   g z_b` (`omega_b'` in the body's frame, `I_b` its principal moments from the parameters,
//!   [`super::figures::moments_of`]), the scale `sum_b m_b (g (d_b + |z_b|) + |v_b|^2 + (d_b
//!   |omega_b|)^2)`: friction and the contact's velocity-level impulses only take energy away.
//! * **Still** ([`Claim::BodyStill`]): the largest change of any body's `x`, `y`, `size theta / 2`,
//!   judged against `64 eps (size + |x| + |y|)` ([`Metrics::still_scale`]); a body in three
//!   dimensions: of its `x`, `y`, `z`.
//! * **The laws' accelerations** ([`Claim::LawAccelerations`], block-on-block, disc-on-board): the
//!   scene's measured lower and upper accelerations against `docs/scenes.md`'s
//!   ([`crate::bodies::law`]), their largest difference over [`acceleration_tolerance`].
//!
//! Every LCP answer is verified in the core (a step that cannot be verified ends the run with
//! `Failed`), so no residual is reported here (0); penetration is not measured for several bodies
//! (0: the single-body geometry of [`super::metrics::penetrations`] does not describe them).

use std::time::Instant;

use meterstick_core::Real;
use meterstick_core::scene::{
    BodyShape, BodyView, LcpLayout, Outcome, Pose, SceneParams, SceneView, Velocity, ViewVisitor,
};

use super::cases::{Case, Claim};
use super::figures::{bodies_of, moments_of};
use super::metrics::Metrics;
use crate::scenes::Precision;

/// The largest body dimension of a scene of several bodies (m).
#[must_use]
pub fn size_of(spec: &SceneParams) -> f64 {
    bodies_of(spec).0.iter().fold(0.0, |a: f64, b| a.max(b.1).max(b.2))
}

/// The tolerance of a measured acceleration against the law's: `1e-3 (|a| + g)` (the law is
/// exact for the implicit step once the contacts settle into their modes; this allows for the
/// finite differences in f32 over a short window).
#[must_use]
pub fn acceleration_tolerance(law: f64, g: f64) -> f64 {
    1e-3 * (law.abs() + g)
}

/// Runs a scene of several bodies in `precision`, measuring as it goes; samples the bodies'
/// centres every `stride` steps (body 0's `(x, y, theta)` in the trace, the deviation's input).
#[must_use]
pub fn measure(case: &Case, precision: Precision, stride: u64) -> Metrics {
    case.spec
        .build_view::<0, _>(precision, LcpLayout::Full, Measure { case, stride })
        .unwrap_or_else(Metrics::invalid)
}

/// A body's `(x, y, theta, vx, vy, omega)` in f64; a body in three dimensions' `(x, y, z, vx, vy,
/// vz)`.
fn state_of<T: Real>(b: Option<BodyView<T>>) -> [f64; 6] {
    match b.map(|b| (b.pose, b.velocity)) {
        Some((Pose::Planar { x, y, theta }, Velocity::Planar { vx, vy, omega })) => {
            [x, y, theta, vx, vy, omega].map(Real::as_f64)
        }
        Some((Pose::Spatial { position: [x, y, z], .. }, Velocity::Spatial { linear: [vx, vy, vz], .. })) => {
            [x, y, z, vx, vy, vz].map(Real::as_f64)
        }
        _ => [f64::NAN; 6],
    }
}

/// `v` turned by the inverse of the unit quaternion `q = [w, x, y, z]`: a world vector in the
/// body's frame (`v + w t + u x t`, `t = 2 u x v`, `u = -(x, y, z)`).
fn unrotate(q: [f64; 4], v: [f64; 3]) -> [f64; 3] {
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
    };
    let u = [-q[1], -q[2], -q[3]];
    let t = cross(u, v).map(|c| 2.0 * c);
    let ut = cross(u, t);
    [0, 1, 2].map(|i| v[i] + q[0] * t[i] + ut[i])
}

/// The energy of a scene's bodies in three dimensions, `sum_b m_b |v_b|^2 / 2 + omega_b' I_b
/// omega_b / 2 + m_b g z_b` (`omega_b'` the angular velocity in the body's frame, `I_b` its
/// principal moments `moments`), and its scale `sum_b m_b (g (d_b + |z_b|) + |v_b|^2 + (d_b
/// |omega_b|)^2)` (`d_b` the body's largest dimension); `None` for a scene of planar bodies.
fn spatial_energy<T: Real>(view: &dyn SceneView<T>, moments: &[[f64; 3]], g: f64) -> Option<(f64, f64)> {
    if moments.is_empty() {
        return None;
    }
    let (mut energy, mut scale) = (0.0, 0.0);
    for (i, inertia) in moments.iter().enumerate() {
        let b = view.body(i)?;
        let (Pose::Spatial { position, orientation }, Velocity::Spatial { linear, angular }) =
            (b.pose, b.velocity)
        else {
            return None;
        };
        let (z, q, v, w) = (
            position[2].as_f64(),
            orientation.map(Real::as_f64),
            linear.map(Real::as_f64),
            angular.map(Real::as_f64),
        );
        let m = b.mass.as_f64();
        let own = unrotate(q, w);
        let d = match b.shape {
            BodyShape::Ball { radius } => 2.0 * radius.as_f64(),
            BodyShape::Puck { radius, thickness } => (2.0 * radius.as_f64()).max(thickness.as_f64()),
            BodyShape::Cuboid { length, width, height } => {
                length.as_f64().max(width.as_f64()).max(height.as_f64())
            }
            _ => f64::NAN,
        };
        let v2: f64 = v.iter().map(|c| c * c).sum();
        let rot: f64 = own.iter().zip(inertia).map(|(c, i)| i * c * c).sum();
        energy += 0.5 * m * v2 + 0.5 * rot + m * g * z;
        scale += m * (g * (d + z.abs()) + v2 + d * d * w.iter().map(|c| c * c).sum::<f64>());
    }
    Some((energy, scale))
}

/// Every body's [`state_of`], body 0 first.
fn states<T: Real>(view: &dyn SceneView<T>) -> Vec<[f64; 6]> {
    (0..view.body_count()).map(|i| state_of(view.body(i))).collect()
}

struct Measure<'a> {
    case: &'a Case,
    stride: u64,
}

impl ViewVisitor for Measure<'_> {
    type Output = Metrics;

    fn visit<T: Real>(self, view: &mut dyn SceneView<T>) -> Metrics {
        let started = Instant::now();
        let spec = &self.case.spec;
        let (bodies, force) = bodies_of(spec);
        let g = spec.get("gravity").unwrap_or(0.0);
        let eps = T::EPS.as_f64();
        let size = size_of(spec);
        let rows = view.lcp_capacity();
        let energy = |s: &[[f64; 6]]| -> f64 {
            s.iter()
                .zip(&bodies)
                .map(|(s, &(m, _, _, j))| {
                    0.5 * m * (s[3] * s[3] + s[4] * s[4]) + 0.5 * j * s[5] * s[5] + m * g * s[1]
                })
                .sum()
        };
        let scale = |s: &[[f64; 6]]| -> f64 {
            s.iter()
                .zip(&bodies)
                .map(|(s, &(m, w, h, _))| {
                    let d = w.max(h);
                    m * (g * (d + s[1].abs()) + s[3] * s[3] + s[4] * s[4] + (d * s[5]).powi(2))
                })
                .sum::<f64>()
                + force.abs() * size
        };
        let moments = moments_of(spec);
        let s0 = states(view);
        let extent = s0.iter().fold(0.0, |a: f64, s| a.max(s[0].abs() + s[1].abs()));
        let mut m = Metrics { eps, still_scale: size + extent, ..Metrics::default() };
        let mut s = s0.clone();
        // The energy and its scale: of planar bodies from their states, of bodies in three
        // dimensions from the view.
        let energy_now = |view: &dyn SceneView<T>, s: &[[f64; 6]]| {
            spatial_energy(view, &moments, g).unwrap_or_else(|| (energy(s), scale(s)))
        };
        let e0 = energy_now(view, &s0).0;
        let mut e_before = e0;
        let mut work = 0.0;
        m.trace.push([s[0][0], s[0][1], s[0][2]]);
        let mut steps = 0_u64;
        while view.step() {
            steps += 1;
            m.max_pivots = m.max_pivots.max(view.last_step().map_or(0, |r| r.pivots));
            let after = states(view);
            let step_work = force * (after[0][0] - s[0][0]);
            let (e_after, e_scale) = energy_now(view, &after);
            if e_after.is_finite() {
                m.step_energy_gain = m.step_energy_gain.max(e_after - e_before - step_work);
                work += step_work;
                let gain = e_after - e0 - work;
                m.energy_gain = m.energy_gain.max(gain);
                m.energy_ratio = m.energy_ratio.max(gain / (4096.0 * rows as f64 * eps * e_scale));
            }
            if self.case.claim == Claim::BodyStill {
                // A planar body's angle counts at half its size; a body in three dimensions' `z`.
                let third = if moments.is_empty() { size / 2.0 } else { 1.0 };
                for (a, b) in after.iter().zip(&s0) {
                    let moved = [a[0] - b[0], a[1] - b[1], third * (a[2] - b[2])];
                    m.claim_motion = moved.iter().fold(m.claim_motion, |acc, d| acc.max(d.abs()));
                }
            }
            s = after;
            e_before = e_after;
            if steps.is_multiple_of(self.stride) {
                m.trace.push([s[0][0], s[0][1], s[0][2]]);
            }
        }
        if self.case.claim == Claim::LawAccelerations {
            let measured = view.measured();
            let law = crate::bodies::law(spec);
            let laws = [law.and_then(|l| l.lower_acceleration), law.and_then(|l| l.upper_acceleration)];
            // A missing measure (or law) is NaN, which fails the judge's `<= 1`.
            m.claim_motion =
                laws.iter().zip(&measured).fold(0.0, |acc: f64, (want, got)| match (want, got) {
                    (Some(want), Some(got)) if !acc.is_nan() => {
                        acc.max((got.as_f64() - want).abs() / acceleration_tolerance(*want, g))
                    }
                    _ => f64::NAN,
                });
        }
        m.steps = steps;
        m.mean_pivots = view.summary().pivots as f64 / steps.max(1) as f64;
        m.outcome = Some(view.outcome().unwrap_or(Outcome::Unfinished).into());
        m.wall_s = started.elapsed().as_secs_f64();
        m
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::panic)]
mod tests {
    use super::*;
    use meterstick_core::scene::SceneKind;

    /// The energy of a body in three dimensions at the start, read through the view: the billiard
    /// ball struck with spin has `m v0^2 / 2 + (2 m R^2 / 5) |omega0|^2 / 2 + m g R` (its centre at
    /// `z = R`), whatever its orientation's frame (a sphere's moments are equal); a quarter turn
    /// about `z` takes `x` to `-y` back into the body's frame.
    #[test]
    fn the_energy_in_three_dimensions_is_the_parameters() {
        struct Start(Vec<[f64; 3]>);
        impl ViewVisitor for Start {
            type Output = Option<(f64, f64)>;
            fn visit<T: Real>(self, view: &mut dyn SceneView<T>) -> Self::Output {
                spatial_energy(view, &self.0, 9.81)
            }
        }
        let turned = unrotate([0.5f64.sqrt(), 0.0, 0.0, 0.5f64.sqrt()], [1.0, 0.0, 0.0]);
        assert!(
            (turned[0]).abs() < 1e-15 && (turned[1] + 1.0).abs() < 1e-15 && turned[2].abs() < 1e-15,
            "{turned:?}"
        );
        let SceneParams::Billiard(p) = SceneParams::defaults(SceneKind::Billiard) else { panic!() };
        let p =
            meterstick_core::scene::spatial::BilliardParams { spin_x: 30.0, spin_y: -40.0, spin_z: 5.0, ..p };
        let spec = SceneParams::Billiard(p);
        let (energy, scale) = spec
            .build_view::<0, _>(Precision::F64, LcpLayout::Full, Start(moments_of(&spec)))
            .unwrap()
            .unwrap();
        let (m, r) = (p.mass, p.radius);
        let spin2 = 30.0f64 * 30.0 + 40.0 * 40.0 + 5.0 * 5.0;
        let want = 0.5 * m * p.speed * p.speed + 0.5 * 0.4 * m * r * r * spin2 + m * 9.81 * r;
        assert!((energy - want).abs() <= 1e-12 * want, "{energy} against {want}");
        assert!(scale > energy);
    }

    /// Each figure as its bits (the view's f64 figures are the parameters' exactly).
    fn bits(bodies: &[(f64, f64, f64, f64)], pull: f64) -> (Vec<[u64; 4]>, u64) {
        let b = bodies.iter().map(|&(m, w, h, j)| [m, w, h, j].map(f64::to_bits)).collect();
        (b, pull.to_bits())
    }

    /// Block-on-block's blocks and pull, and disc-on-board's board and disc, read through the view,
    /// are the parameters' figures: a box's `m (w^2 + h^2) / 12`, a disc's diameter and `m r^2 / 2`.
    #[test]
    fn bodies_of_reads_the_parameters_figures_through_the_view() {
        let block = |m: f64, w: f64, h: f64| (m, w, h, m * (w * w + h * h) / 12.0);
        let SceneParams::BlockOnBlock(p) = SceneParams::defaults(SceneKind::BlockOnBlock) else { panic!() };
        let (bodies, pull) = bodies_of(&SceneParams::BlockOnBlock(p));
        let want = [
            block(p.bottom_mass, p.bottom_width, p.bottom_height),
            block(p.top_mass, p.top_width, p.top_height),
        ];
        assert!(p.force > 0.0);
        assert_eq!(bits(&bodies, pull), bits(&want, p.force));
        let SceneParams::DiscOnBoard(p) = SceneParams::defaults(SceneKind::DiscOnBoard) else { panic!() };
        let (bodies, pull) = bodies_of(&SceneParams::DiscOnBoard(p));
        let (m, r) = (p.disc_mass, p.disc_radius);
        let want =
            [block(p.board_mass, p.board_length, p.board_height), (m, 2.0 * r, 2.0 * r, m * r * r / 2.0)];
        assert_eq!(bits(&bodies, pull), bits(&want, p.force));
    }
}
