//! Contact geometry: docs/formulation.md, "The body" and "Contacts".
//!
//! The body is a box of half-width `a` (body `x`) and half-height `b` (body `y`) centred on its
//! centre of mass, at `q = (x, y, theta)`. `R(theta)` rotates the body frame into the world.
//!
//! * A **support point** `f` (world) under the lower face `y_b = -b`: with `l = R^T (f - com)`,
//!   active when `|l_x| <= a` and `l_y <= 0`; gap `psi = -l_y - b`; contact point (body frame)
//!   `(l_x, -b)`; `n = R (0, 1)`, `d = R (1, 0)`; coordinate along the contact `l_x`.
//! * A **body point on a support line**: body point `p_b`, line through `o` with unit normal `n_s`
//!   toward the body. `P = com + R p_b`, always active; `psi = (P - o) . n_s`; `n = n_s`;
//!   `d = (n_y, -n_x)`; coordinate along the contact `(P - o) . d`.
//! * A **round rim on a support line** (docs/scenes.md, "cylinder"): a circle of radius `rho`
//!   about the centre of mass, line through `o` with unit normal `n_s` toward the body. The rim
//!   touches the line at the point nearest to it whatever the body's angle, so the contact point
//!   is `P = com - rho n_s` (`r = -rho n_s`), always active; `psi = (com - o) . n_s - rho` (the
//!   centre's distance from the line less the radius); `n = n_s`; `d = (n_y, -n_x)`; coordinate
//!   along the contact `(P - o) . d`. With `r` parallel to `n`, `r x n = 0` and
//!   `r x d = -rho (n_x d_y - n_y d_x) = rho` (`n x d = -1` for `d` the normal turned clockwise).
//!
//! In both, `r = R p` is the contact point relative to the centre of mass (world), and a unit
//! impulse along `a` applied there has the wrench `[a; r x a]` with `r x a = r_x a_y - r_y a_x`
//! (eq. 3).

/// `R(theta) v`.
pub(super) fn rotate(theta: f64, v: [f64; 2]) -> [f64; 2] {
    let (s, c) = theta.sin_cos();
    [c * v[0] - s * v[1], s * v[0] + c * v[1]]
}

/// `R(theta)^T v`.
pub(super) fn rotate_back(theta: f64, v: [f64; 2]) -> [f64; 2] {
    let (s, c) = theta.sin_cos();
    [c * v[0] + s * v[1], -s * v[0] + c * v[1]]
}

/// `a . b`.
pub(super) fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// The wrench `[a; r x a]` of a unit impulse along `a` applied at `r` (eq. 3).
pub(super) fn wrench(r: [f64; 2], a: [f64; 2]) -> [f64; 3] {
    [a[0], a[1], r[0] * a[1] - r[1] * a[0]]
}

/// The rigid body: a box centred on its centre of mass, with its mass and inertia.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Body {
    /// Half the width (body `x`), m.
    pub half_width: f64,
    /// Half the height (body `y`), m.
    pub half_height: f64,
    /// Mass `m`, kg.
    pub mass: f64,
    /// Inertia `J` about the centre of mass, kg m^2.
    pub inertia: f64,
}

/// What a contact's support is at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Support {
    /// A support point (finger tip) at world `tip`, under the body's lower face.
    Point {
        /// The tip, world.
        tip: [f64; 2],
    },
    /// A support line touched by a point of the body.
    Line {
        /// The body's point, body frame.
        body_point: [f64; 2],
        /// A point of the line, world.
        origin: [f64; 2],
        /// The line's unit normal, pointing toward the body's side.
        normal: [f64; 2],
    },
    /// A support line touched by the body's round rim.
    Round {
        /// The rim's radius `rho` (a circle about the centre of mass), m.
        radius: f64,
        /// A point of the line, world.
        origin: [f64; 2],
        /// The line's unit normal, pointing toward the body's side.
        normal: [f64; 2],
    },
}

/// One contact's geometry at one configuration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Frame {
    /// Whether the contact enters the step's LCP.
    pub active: bool,
    /// Gap `psi`, positive when apart, m.
    pub gap: f64,
    /// Contact point relative to the centre of mass, world (`r`).
    pub lever: [f64; 2],
    /// Normal on the body `n`, world.
    pub normal: [f64; 2],
    /// Tangent `d`, world.
    pub tangent: [f64; 2],
    /// Coordinate along the contact, m.
    pub along: f64,
    /// The support's point, world: the tip, or the foot of the body point on the line.
    pub support_point: [f64; 2],
}

/// The geometry of `support` against `body` at configuration `q`.
pub(super) fn frame(body: &Body, q: [f64; 3], support: &Support) -> Frame {
    let com = [q[0], q[1]];
    match *support {
        Support::Point { tip } => {
            let local = rotate_back(q[2], [tip[0] - com[0], tip[1] - com[1]]);
            Frame {
                active: local[0].abs() <= body.half_width && local[1] <= 0.0,
                gap: -local[1] - body.half_height,
                lever: rotate(q[2], [local[0], -body.half_height]),
                normal: rotate(q[2], [0.0, 1.0]),
                tangent: rotate(q[2], [1.0, 0.0]),
                along: local[0],
                support_point: tip,
            }
        }
        Support::Line { body_point, origin, normal } => {
            let lever = rotate(q[2], body_point);
            let from_origin = [com[0] + lever[0] - origin[0], com[1] + lever[1] - origin[1]];
            let tangent = [normal[1], -normal[0]];
            let along = dot(from_origin, tangent);
            Frame {
                active: true,
                gap: dot(from_origin, normal),
                lever,
                normal,
                tangent,
                along,
                support_point: [origin[0] + along * tangent[0], origin[1] + along * tangent[1]],
            }
        }
        Support::Round { radius, origin, normal } => {
            let lever = [-radius * normal[0], -radius * normal[1]];
            let centre = [com[0] - origin[0], com[1] - origin[1]];
            let tangent = [normal[1], -normal[0]];
            let along = dot([centre[0] + lever[0], centre[1] + lever[1]], tangent);
            Frame {
                active: true,
                gap: dot(centre, normal) - radius,
                lever,
                normal,
                tangent,
                along,
                support_point: [origin[0] + along * tangent[0], origin[1] + along * tangent[1]],
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_floor_has_tangent_plus_x_and_a_wall_facing_minus_x_has_tangent_plus_y() {
        let body = Body { half_width: 0.5, half_height: 0.01, mass: 1.0, inertia: 1.0 / 12.0 };
        let floor = Support::Line { body_point: [-0.5, 0.0], origin: [0.0, 0.0], normal: [0.0, 1.0] };
        let wall = Support::Line { body_point: [0.5, 0.0], origin: [0.0, 0.0], normal: [-1.0, 0.0] };
        // A level rod with its right end 1 mm from the wall and 0.2 m up.
        let q = [-0.501, 0.2, 0.0];
        let f = frame(&body, q, &floor);
        assert!(f.tangent[0] - 1.0 == 0.0 && f.tangent[1] == 0.0, "{f:?}");
        assert!((f.gap - 0.2).abs() < 1e-15 && (f.along + 1.001).abs() < 1e-15, "{f:?}");
        let w = frame(&body, q, &wall);
        assert!(w.tangent[0] == 0.0 && w.tangent[1] - 1.0 == 0.0, "{w:?}");
        assert!((w.gap - 0.001).abs() < 1e-15 && (w.along - 0.2).abs() < 1e-15, "{w:?}");
        assert!((w.support_point[0]).abs() < 1e-15 && (w.support_point[1] - 0.2).abs() < 1e-15);
    }

    #[test]
    fn a_rim_touches_a_slope_below_its_centre_whatever_its_angle() {
        // A disc of radius 0.1 with its centre 0.13 m from a 30 degree slope and 0.2 m up it.
        let alpha = 30_f64.to_radians();
        let (s, c) = alpha.sin_cos();
        let body = Body { half_width: 0.1, half_height: 0.1, mass: 1.0, inertia: 0.005 };
        let slope = Support::Round { radius: 0.1, origin: [0.0, 0.0], normal: [-s, c] };
        let centre = [0.2 * c - 0.13 * s, 0.2 * s + 0.13 * c];
        for theta in [0.0, 1.0, -2.5] {
            let f = frame(&body, [centre[0], centre[1], theta], &slope);
            assert!(f.active && (f.gap - 0.03).abs() < 1e-15, "{f:?}");
            // The contact point 0.1 m below the centre along -n, 0.2 m up the slope.
            assert!((f.lever[0] - 0.1 * s).abs() < 1e-15 && (f.lever[1] + 0.1 * c).abs() < 1e-15, "{f:?}");
            assert!((f.tangent[0] - c).abs() < 1e-15 && (f.tangent[1] - s).abs() < 1e-15, "{f:?}");
            assert!((f.along - 0.2).abs() < 1e-15, "{f:?}");
            assert!(
                (f.support_point[0] - 0.2 * c).abs() < 1e-15 && (f.support_point[1] - 0.2 * s).abs() < 1e-15
            );
            // Eq. 3: the normal passes through the centre, friction has the lever arm rho.
            assert!(wrench(f.lever, f.normal)[2].abs() < 1e-16);
            assert!((wrench(f.lever, f.tangent)[2] - 0.1).abs() < 1e-15);
        }
    }

    #[test]
    fn a_tip_past_the_centre_line_or_beyond_the_end_is_inactive() {
        let body = Body { half_width: 0.5, half_height: 0.0025, mass: 0.2, inertia: 0.2 / 12.0 };
        let q = [0.0, 0.0025, 0.0];
        let under = frame(&body, q, &Support::Point { tip: [0.3, 0.0] });
        assert!(under.active && under.gap.abs() < 1e-18 && (under.along - 0.3).abs() < 1e-15);
        assert!(!frame(&body, q, &Support::Point { tip: [0.51, 0.0] }).active);
        assert!(!frame(&body, q, &Support::Point { tip: [0.0, 0.003] }).active);
        // Wrench of the normal at the tip: torque r x n = 0.3.
        let wn = wrench(under.lever, under.normal);
        assert!((wn[2] - 0.3).abs() < 1e-15, "{wn:?}");
    }
}
