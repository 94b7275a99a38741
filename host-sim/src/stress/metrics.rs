//! What one run of a stress case measures, in f64, from what the core reports after every step:
//! physics the core does not compute for itself.
//!
//! * **Penetration** of each contact, from the state after the step, with this module's own
//!   geometry (`docs/formulation.md`, "Contacts"): a finger tip under the rod,
//!   `l = R(theta)^T (f - com)`, `psi = -l_y - t/2`; a corner or an end on a line, `psi = (P - o).n`;
//!   a round rim on a line, `psi = (c - o).n - r`.
//! * **Energy** `E = m (vx^2 + vy^2) / 2 + J omega^2 / 2 + m g y`, and the work the moving supports
//!   do over a step, `sum_i u_i . P_i` with `u_i` a support's velocity over the step and
//!   `P_i = n p_n + d p_f` its impulse on the body (`n`, `d` at the step's start angle). For the
//!   implicit step of eqs. 13-18 one has exactly
//!   `E+ - E <= sum u . P - sum_i p_ni min(psi_i, 0) / h - (v+ - v)^T M (v+ - v) / 2`
//!   (the normal and friction rows' complementarity, `sigma >= 0`, and `y+ = y + h vy+`), so apart
//!   from round-off the body gains energy beyond the supports' work only by pushing out of a
//!   penetration.
//! * **LCP residual**: each step's verified residual over the solver's tolerance (`256 N eps`).

use std::time::Instant;

use meterstick_core::Real;
use meterstick_core::lcp::default_tolerance;
use meterstick_core::scene::{
    MeterStick, Outcome, PlanarView, Pose, Scene, SceneView, SceneVisitor, SupportView, Velocity, ViewVisitor,
};

use super::cases::{Case, Claim};
use crate::scenes::{LcpLayout, Precision, SceneParams};
use crate::trajectory::{OutcomeKind, RunOutcome};

/// What one run of one case measured.
#[derive(Debug, Clone, Default)]
pub struct Metrics {
    /// How it ended (`None`: it panicked).
    pub outcome: Option<RunOutcome>,
    /// Steps taken.
    pub steps: u64,
    /// Largest verification residual over the tolerance.
    pub residual_ratio: f64,
    /// Largest penetration (m).
    pub penetration: f64,
    /// Largest penetration over its bound.
    pub penetration_ratio: f64,
    /// Largest `E+ - E - W_supports` over one step (J).
    pub step_energy_gain: f64,
    /// Largest `E(t) - E(0) - W_supports(0, t)` (J).
    pub energy_gain: f64,
    /// `energy_gain` over its allowance (`m g pen_0 + tolerance`).
    pub energy_ratio: f64,
    /// Most pivots in one step.
    pub max_pivots: u32,
    /// Mean pivots per step.
    pub mean_pivots: f64,
    /// Reduced-layout check firings.
    pub reduced_check_fired: u64,
    /// For [`Claim::NotDragged`]: largest `|x - x_0|` while finger 1 was left of the centre of
    /// mass; for [`Claim::BodyStill`]: largest change of `x`, `y`, `size theta / 2` (m); for
    /// [`Claim::LawAccelerations`]: the largest difference from the law over its tolerance.
    pub claim_motion: f64,
    /// The length a claim of no motion's round-off scales with (m): the body's size; several
    /// bodies: the largest body's size plus the largest `|x| + |y|` of a body's start (positions
    /// round relative to their magnitude, as [`penetration_bound`]'s round-off term).
    pub still_scale: f64,
    /// Solves answered by the solver's regularised retry.
    pub regularized_solves: u64,
    /// Machine epsilon of the run's scalar.
    pub eps: f64,
    /// Sampled `(x, y, theta)` for the f32-vs-f64 deviation.
    pub trace: Vec<[f64; 3]>,
    /// Wall-clock time (s).
    pub wall_s: f64,
}

impl Metrics {
    /// A run the core refused to build: `Failed`, the refusal its detail.
    #[must_use]
    pub fn invalid(e: impl std::fmt::Display) -> Self {
        Self {
            outcome: Some(RunOutcome { class: OutcomeKind::Failed, detail: Some(format!("invalid: {e}")) }),
            ..Self::default()
        }
    }

    /// The outcome's class (`None`: the run panicked).
    #[must_use]
    pub fn class(&self) -> Option<OutcomeKind> {
        self.outcome.as_ref().map(|o| o.class)
    }
}

/// Round-off of a claim of no motion, in units of `eps size`: a position's rounding (a tilt of
/// `eps` gives a normal impulse a horizontal part).
pub const STILL_TOLERANCE: f64 = 64.0;

/// The body's mass, inertia, size (its larger extent) and the scene's characteristic speed (a
/// support's, or the body's at the start): the first three as the scene's f64 build holds them,
/// read through its view ([`super::figures::bodies_of`]); all NaN for a scene of several bodies
/// (`super::bodies` measures them), which fails any bound they enter.
#[must_use]
pub fn body_of(spec: &SceneParams) -> (f64, f64, f64, f64) {
    let speed = match spec {
        SceneParams::MeterStick(p) => p.finger1_velocity.abs().max(p.finger2_velocity.abs()),
        SceneParams::ThreeFingers(p) => p.finger1_velocity.abs(),
        SceneParams::Painleve(p) => p.speed.abs(),
        SceneParams::Incline(_) | SceneParams::Ladder(_) | SceneParams::Cylinder(_) => 0.0,
        SceneParams::BlockOnBlock(_)
        | SceneParams::Tablecloth(_)
        | SceneParams::Stack(_)
        | SceneParams::DiscOnBoard(_)
        | SceneParams::Puck(_)
        | SceneParams::Billiard(_)
        | SceneParams::Curling(_)
        | SceneParams::MeterStick3d(_)
        | SceneParams::Stack3d(_) => f64::NAN,
    };
    match super::figures::bodies_of(spec).0.as_slice() {
        &[(m, w, h, j)] if !speed.is_nan() => (m, j, w.max(h), speed),
        _ => (f64::NAN, f64::NAN, f64::NAN, f64::NAN),
    }
}

/// The penetration bound of one step: what the step started with, the second-order terms of the
/// step's geometry (`h^2` times `|omega| (|u| + |v|)` for the contact point's turning,
/// `size omega^2 / 2` for the arc, `g` for gravity within the step), and round-off of the
/// coordinates (`64 eps (size + |x| + |y|)`); `body` is [`body_of`]'s.
#[must_use]
pub fn penetration_bound(
    body: (f64, f64, f64, f64),
    spec: &SceneParams,
    eps: f64,
    pen_before: f64,
    s: &[f64; 6],
    u: f64,
) -> f64 {
    let (_, _, size, _) = body;
    let h = spec.step();
    let g = spec.get("gravity").unwrap_or(0.0);
    let omega = s[5].abs();
    let speed = s[3].abs() + s[4].abs();
    pen_before
        + h * h * (omega * (u.abs() + speed) + size * omega * omega / 2.0 + g)
        + 64.0 * eps * (size + s[0].abs() + s[1].abs())
}

/// Round-off allowance of the run's energy balance: `4096 N eps` of the energy scale
/// `m (g (size + |y|) + V^2 + |v|^2 + (size omega)^2)` at the step (`V` the characteristic support
/// speed), `N` the LCP size (the verification tolerance is `256 N eps`, and each of `N`
/// complementarity products contributes up to it times the impulse and velocity scales); `body` is
/// [`body_of`]'s.
#[must_use]
pub fn energy_tolerance(
    body: (f64, f64, f64, f64),
    spec: &SceneParams,
    eps: f64,
    n: usize,
    s: &[f64; 6],
) -> f64 {
    let (m, _, size, v_f) = body;
    let g = spec.get("gravity").unwrap_or(0.0);
    let v2 = s[3] * s[3] + s[4] * s[4] + (size * s[5]).powi(2);
    4096.0 * n as f64 * eps * m * (g * (size + s[1].abs()) + v_f * v_f + v2)
}

/// The body's energy; `body` is [`body_of`]'s.
#[must_use]
pub fn energy(body: (f64, f64, f64, f64), spec: &SceneParams, s: &[f64; 6]) -> f64 {
    let (m, j, _, _) = body;
    let g = spec.get("gravity").unwrap_or(0.0);
    0.5 * m * (s[3] * s[3] + s[4] * s[4]) + 0.5 * j * s[5] * s[5] + m * g * s[1]
}

/// Each contact's penetration (0 when apart, or a finger not under the rod), with this module's
/// own geometry; `supports` are the finger tips (meter stick, three fingers).
#[must_use]
pub fn penetrations(spec: &SceneParams, s: &[f64; 6], supports: &[[f64; 2]]) -> Vec<f64> {
    let (sn, cs) = s[2].sin_cos();
    let world = |p: [f64; 2]| [s[0] + cs * p[0] - sn * p[1], s[1] + sn * p[0] + cs * p[1]];
    let under_rod = |length: f64, thickness: f64| {
        supports
            .iter()
            .map(|f| {
                let (dx, dy) = (f[0] - s[0], f[1] - s[1]);
                let lx = cs * dx + sn * dy;
                let ly = -sn * dx + cs * dy;
                if lx.abs() <= length / 2.0 && ly <= 0.0 { (ly + thickness / 2.0).max(0.0) } else { 0.0 }
            })
            .collect()
    };
    match spec {
        SceneParams::MeterStick(p) => under_rod(p.rod_length, p.rod_thickness),
        SceneParams::ThreeFingers(p) => under_rod(p.rod_length, p.rod_thickness),
        SceneParams::Incline(p) => {
            let n = [-p.angle.sin(), p.angle.cos()];
            [-1.0, 1.0]
                .iter()
                .map(|side| {
                    let c = world([side * p.width / 2.0, -p.height / 2.0]);
                    (-(c[0] * n[0] + c[1] * n[1])).max(0.0)
                })
                .collect()
        }
        SceneParams::Ladder(p) => {
            let (bottom, top) = (world([-p.length / 2.0, 0.0]), world([p.length / 2.0, 0.0]));
            vec![(-bottom[1]).max(0.0), top[0].max(0.0)]
        }
        // The rim against the plane through the origin with normal (-sin a, cos a).
        SceneParams::Cylinder(p) => {
            vec![(p.radius - (-p.angle.sin() * s[0] + p.angle.cos() * s[1])).max(0.0)]
        }
        // The lower end, body point (-L/2, 0), against the floor y = 0.
        SceneParams::Painleve(p) => vec![(-world([-p.length / 2.0, 0.0])[1]).max(0.0)],
        // Not for several bodies (`super::bodies`) nor in three dimensions (not stressed yet): NaN
        // fails any bound.
        SceneParams::BlockOnBlock(_)
        | SceneParams::Tablecloth(_)
        | SceneParams::Stack(_)
        | SceneParams::DiscOnBoard(_)
        | SceneParams::Puck(_)
        | SceneParams::Billiard(_)
        | SceneParams::Curling(_)
        | SceneParams::MeterStick3d(_)
        | SceneParams::Stack3d(_) => vec![f64::NAN],
    }
}

/// Body 0's `(x, y, theta, vx, vy, omega)` in f64 (NaN for a body not in the plane, which fails
/// every bound).
fn state_of<T: Real>(view: &dyn SceneView<T>) -> [f64; 6] {
    match view.body(0).map(|b| (b.pose, b.velocity)) {
        Some((Pose::Planar { x, y, theta }, Velocity::Planar { vx, vy, omega })) => {
            [x, y, theta, vx, vy, omega].map(Real::as_f64)
        }
        _ => [f64::NAN; 6],
    }
}

/// Each support's position (finger tips; fixed lines give zero velocity anyway).
fn support_points<T: Real>(view: &dyn SceneView<T>) -> Vec<[f64; 2]> {
    (0..view.support_count())
        .filter_map(|i| match view.support(i)? {
            SupportView::Point { position, .. } | SupportView::Line { position, .. } => {
                Some(position.map(Real::as_f64))
            }
            _ => None,
        })
        .collect()
}

/// Each contact's normal and friction impulse over the last step (N s).
fn impulses<T: Real>(view: &dyn SceneView<T>) -> Vec<[f64; 2]> {
    (0..view.contact_count())
        .filter_map(|i| view.contact(i).map(|c| [c.normal_impulse.as_f64(), c.friction_impulse.as_f64()]))
        .collect()
}

/// Runs `case`, a scene of one body, in `precision` and `layout` through the core's scene
/// interface, measuring as it goes; samples the state every `stride` steps (a scene of several
/// bodies: [`super::bodies::measure`]). A case that starts above its rest ([`Case::start_dy`], the
/// meter stick) is built at that start, then measured through the same interface.
#[must_use]
pub fn measure(case: &Case, precision: Precision, layout: LcpLayout, stride: u64) -> Metrics {
    let measure = Measure { case, stride, layout };
    let built = if case.start_dy == 0.0 {
        case.spec.build_view::<0, _>(precision, layout, measure)
    } else {
        case.spec.build::<0, _>(precision, layout, Lifted(measure))
    };
    built.unwrap_or_else(Metrics::invalid)
}

/// [`Measure`], the scene first lifted `start_dy` above its rest on the fingers (the meter stick:
/// no other scene starts elsewhere than its parameters say).
struct Lifted<'a>(Measure<'a>);

impl SceneVisitor for Lifted<'_> {
    type Output = Metrics;

    fn visit<T: Real, const K: usize, const N: usize, S: Scene<T, K>>(self, _: S) -> Metrics {
        Metrics::invalid("only the meter stick starts above its rest")
    }

    fn visit_meter_stick<T: Real, const N: usize, const E: usize>(
        self,
        scene: MeterStick<T, N, E>,
    ) -> Metrics {
        let p = *scene.params();
        let mut start = p.resting_state();
        start.y += T::of(self.0.case.start_dy);
        match MeterStick::<T, N, E>::with_state(p, start) {
            Ok(lifted) => self.0.visit(&mut PlanarView::new(lifted)),
            Err(e) => Metrics::invalid(e),
        }
    }
}

/// Measures a scene of one body through its view.
struct Measure<'a> {
    case: &'a Case,
    stride: u64,
    layout: LcpLayout,
}

/// The work of the supports on the body over a step: `sum_i u_i . (n p_n + d p_f)`, `u_i` from
/// the supports' positions before and after, `n = R(theta) (0, 1)`, `d = R(theta) (1, 0)` for a
/// finger under the rod at the step's start angle (supports on lines do not move).
fn support_work(
    spec: &SceneParams,
    impulses: &[[f64; 2]],
    before: &[[f64; 2]],
    after: &[[f64; 2]],
    theta: f64,
) -> f64 {
    if !matches!(spec, SceneParams::MeterStick(_) | SceneParams::ThreeFingers(_)) {
        return 0.0;
    }
    let (sn, cs) = theta.sin_cos();
    let h = spec.step();
    let mut work = 0.0;
    for ((b, a), &[pn, pf]) in before.iter().zip(after).zip(impulses) {
        let u = [(a[0] - b[0]) / h, (a[1] - b[1]) / h];
        work += u[0] * (-sn * pn + cs * pf) + u[1] * (cs * pn + sn * pf);
    }
    work
}

impl ViewVisitor for Measure<'_> {
    type Output = Metrics;

    /// Steps `view` (one body on `K` supports, an LCP of the layout's size, the full layout's
    /// when the reduced check sent a step to it) to its outcome, measuring.
    fn visit<T: Real>(self, view: &mut dyn SceneView<T>) -> Metrics {
        let started = Instant::now();
        let (case, stride) = (self.case, self.stride);
        let spec = &case.spec;
        let body = body_of(spec);
        let (m_body, _, size, _) = body;
        let eps = T::EPS.as_f64();
        let g = spec.get("gravity").unwrap_or(0.0);
        let (n, n_full) = (self.layout.size(view.contact_count()), view.lcp_capacity());
        let mut m = Metrics { eps, still_scale: size, ..Metrics::default() };
        let mut s = state_of(view);
        let s0 = s;
        let mut supports = support_points(view);
        let mut pen = penetrations(spec, &s, &supports);
        let pen0 = pen.iter().fold(0.0, |a: f64, &p| a.max(p));
        let e0 = energy(body, spec, &s);
        let mut e_before = e0;
        let mut work = 0.0;
        let mut fired = view.summary().reduced_check_fired;
        m.trace.push([s[0], s[1], s[2]]);
        while view.step() {
            let stats = view.summary();
            // The full layout's tolerance when the reduced check sent the step to it.
            let n_used = if stats.reduced_check_fired > fired { n_full } else { n };
            fired = stats.reduced_check_fired;
            let tolerance = default_tolerance::<T, 8>().as_f64() * n_used as f64 / 8.0;
            if let Some(last) = view.last_step() {
                let residual = last.residual.map_or(0.0, Real::as_f64);
                m.residual_ratio = m.residual_ratio.max(residual / tolerance);
                m.max_pivots = m.max_pivots.max(last.pivots);
            }
            let after = state_of(view);
            let supports_after = support_points(view);
            let step_work = support_work(spec, &impulses(view), &supports, &supports_after, s[2]);
            let u =
                supports.iter().zip(&supports_after).fold(0.0, |a: f64, (b, c)| a.max((c[0] - b[0]).abs()))
                    / spec.step();
            let e_after = energy(body, spec, &after);
            if e_after.is_finite() {
                m.step_energy_gain = m.step_energy_gain.max(e_after - e_before - step_work);
                work += step_work;
                let gain = e_after - e0 - work;
                m.energy_gain = m.energy_gain.max(gain);
                let allowance = m_body * g * pen0 + energy_tolerance(body, spec, eps, n, &after);
                m.energy_ratio = m.energy_ratio.max(gain / allowance);
            }
            let pen_after = penetrations(spec, &after, &supports_after);
            for (&before, &after) in pen.iter().zip(&pen_after) {
                let bound = penetration_bound(body, spec, eps, before, &s, u);
                m.penetration = m.penetration.max(after);
                m.penetration_ratio = m.penetration_ratio.max(after / bound);
            }
            match case.claim {
                Claim::NotDragged => {
                    if supports_after[0][0] < after[0] - 0.01 * size {
                        m.claim_motion = m.claim_motion.max((after[0] - s0[0]).abs());
                    }
                }
                Claim::BodyStill => {
                    let moved = [after[0] - s0[0], after[1] - s0[1], size / 2.0 * (after[2] - s0[2])];
                    m.claim_motion = moved.iter().fold(m.claim_motion, |a, d| a.max(d.abs()));
                }
                Claim::None | Claim::LawAccelerations => {}
            }
            s = after;
            e_before = e_after;
            supports = supports_after;
            pen = pen_after;
            if stats.steps % stride == 0 {
                m.trace.push([s[0], s[1], s[2]]);
            }
        }
        let stats = view.summary();
        m.steps = stats.steps;
        m.mean_pivots = stats.pivots as f64 / stats.steps.max(1) as f64;
        m.reduced_check_fired = stats.reduced_check_fired;
        m.regularized_solves = stats.regularized_solves;
        m.outcome = Some(view.outcome().unwrap_or(Outcome::Unfinished).into());
        m.wall_s = started.elapsed().as_secs_f64();
        m
    }
}

#[cfg(test)]
#[allow(clippy::panic)]
mod tests {
    use super::*;
    use meterstick_core::scene::SceneKind;

    /// The meter stick's figures, read through the view: the rod's mass, `m L^2 / 12`, its length,
    /// the faster finger's speed; the cylinder's `k m r^2` and diameter; NaN for several bodies.
    #[test]
    fn body_of_reads_the_parameters_figures_through_the_view() {
        let SceneParams::MeterStick(p) = SceneParams::defaults(SceneKind::MeterStick) else { panic!() };
        let want = (p.rod_mass, p.rod_mass * p.rod_length * p.rod_length / 12.0, p.rod_length);
        let (m, j, size, speed) = body_of(&SceneParams::MeterStick(p));
        assert_eq!([m, j, size].map(f64::to_bits), [want.0, want.1, want.2].map(f64::to_bits));
        assert_eq!(speed.to_bits(), p.finger1_velocity.abs().max(p.finger2_velocity.abs()).to_bits());
        let SceneParams::Cylinder(c) = SceneParams::defaults(SceneKind::Cylinder) else { panic!() };
        let (m, j, size, _) = body_of(&SceneParams::Cylinder(c));
        let want = [c.mass, c.inertia_factor * c.mass * c.radius * c.radius, 2.0 * c.radius];
        assert_eq!([m, j, size].map(f64::to_bits), want.map(f64::to_bits));
        assert!(body_of(&SceneParams::defaults(SceneKind::BlockOnBlock)).0.is_nan());
    }
}
