//! What `docs/scenes.md`'s laws say of the scenes of several bodies and of those in three
//! dimensions.

use meterstick_core::multibody::scenes::DiscOnBoardParams;
use meterstick_core::scene::spatial::{BilliardParams, CurlingParams, PuckParams};
use meterstick_core::scene::{OutcomeKind, SceneKind, SceneParams};

use crate::trajectory::Measured;

/// What `docs/scenes.md`'s laws say of a scene of several bodies: the outcome, and the
/// accelerations where the law gives them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Law {
    /// The outcome the law predicts (`None` where it does not decide: a run at a threshold).
    pub outcome: Option<OutcomeKind>,
    /// The lower body's acceleration along `x` while both are in full contact (m/s^2).
    pub lower_acceleration: Option<f64>,
    /// The upper body's (m/s^2).
    pub upper_acceleration: Option<f64>,
    /// The scene's measured quantities where the law gives them (a scene in three dimensions).
    pub measured: Measured,
    /// The law in words, with its thresholds.
    pub text: &'static str,
}

/// The laws of block-on-block and the tablecloth (`docs/scenes.md`): the floor holds the pull
/// `F` up to `mu_floor (M + m) g`; up to `(mu_s + mu_floor) (M + m) g` both ride at
/// `a = F / (M + m) - mu_floor g` (block-on-block: a tall top block tips first when
/// `g w / h < a`); above it the upper one slides back at `mu_k g` and the lower one accelerates
/// at `(F - mu_k m g - mu_floor (M + m) g) / M`; the stack holds iff its overhang scale is below 1;
/// disc-on-board's ([`disc_on_board_law`]).
#[must_use]
pub fn law(spec: &SceneParams) -> Option<Law> {
    let pulled = |force: f64, lower: f64, upper: f64, mu_s: f64, mu_k: f64, mu_floor: f64, g: f64| {
        let total = lower + upper;
        let (held, riding) = (mu_floor * total * g, (mu_s + mu_floor) * total * g);
        if force <= held {
            (OutcomeKind::Held, 0.0, 0.0)
        } else if force <= riding {
            let a = force / total - mu_floor * g;
            (OutcomeKind::Rode, a, a)
        } else {
            (OutcomeKind::Slid, (force - mu_k * upper * g - mu_floor * total * g) / lower, mu_k * g)
        }
    };
    Some(match *spec {
        SceneParams::BlockOnBlock(p) => {
            let (mut outcome, a_bottom, a_top) =
                pulled(p.force, p.bottom_mass, p.top_mass, p.mu_static, p.mu_kinetic, p.mu_floor, p.gravity);
            if outcome == OutcomeKind::Rode && a_top > p.gravity * p.top_width / p.top_height {
                outcome = OutcomeKind::Tipped;
            }
            Law {
                outcome: Some(outcome),
                lower_acceleration: Some(a_bottom),
                upper_acceleration: Some(a_top),
                measured: Measured::default(),
                text: "Held iff F <= mu_floor (M + m) g; Rode iff F <= (mu_s + mu_floor) (M + m) g, at \
                       F / (M + m) - mu_floor g (Tipped when that exceeds g w / h); else Slid: a_top = mu_k g",
            }
        }
        SceneParams::Tablecloth(p) => {
            let (outcome, a_board, a_block) =
                pulled(p.force, p.board_mass, p.block_mass, p.mu_static, p.mu_kinetic, p.mu_floor, p.gravity);
            let outcome = if outcome == OutcomeKind::Slid { OutcomeKind::Stayed } else { outcome };
            Law {
                outcome: Some(outcome),
                lower_acceleration: Some(a_board),
                upper_acceleration: Some(a_block),
                measured: Measured::default(),
                text: "Held iff F <= mu_floor (m + m_b) g; Rode iff F <= (mu_s + mu_floor) (m + m_b) g; \
                       else the board comes out and the block Stayed, moved less the harder the pull",
            }
        }
        SceneParams::Stack(s) => Law {
            outcome: if s.params.overhang < 1.0 {
                Some(OutcomeKind::Held)
            } else if s.params.overhang > 1.0 {
                Some(OutcomeKind::Fell)
            } else {
                None
            },
            lower_acceleration: None,
            upper_acceleration: None,
            measured: Measured::default(),
            text: "Held iff the overhang scale s < 1 (every block's load inside the edge below it), Fell above",
        },
        SceneParams::DiscOnBoard(p) => disc_on_board_law(&p),
        SceneParams::Puck(p) => puck_law(&p),
        SceneParams::Billiard(p) => billiard_law(&p),
        SceneParams::Curling(p) => curling_law(&p),
        _ => return None,
    })
}

/// Disc-on-board's law (`docs/scenes.md`, "disc-on-board"; `docs/formulation.md`, "The rim-on-face
/// contact"): the floor holds the pull `F` up to `mu_floor (M + m) g`; beyond it the board
/// accelerates at `A = (F - mu_floor (M + m) g) / (M + m / 3)` with the disc rolling, its centre
/// at `a_c = A / 3` (the board's friction `m A / 3` on the disc, its turning `J alpha = r m A / 3`
/// with `J = m r^2 / 2`, and the rim's point moving with the board: `a_c + r alpha = A`), while that
/// friction is within `mu_s m g`: `A <= 3 mu_s g`; beyond, the disc slides at `a_c = mu_k g` and
/// the board accelerates at `(F - mu_k m g - mu_floor (M + m) g) / M`. The rim's point moves along
/// the board by `(a_c - A) t^2 / 2`: past an end of the board (`|offset + (a_c - A) T^2 / 2| >
/// L / 2` by `max_time` `T`) the run ends `Unfinished`.
#[must_use]
pub fn disc_on_board_law(p: &DiscOnBoardParams<f64>) -> Law {
    let (big_m, m, g) = (p.board_mass, p.disc_mass, p.gravity);
    let floor = p.mu_floor * (big_m + m) * g;
    let rolling = (p.force - floor) / (big_m + m / 3.0);
    let (outcome, a_board, a_disc) = if p.force <= floor {
        (OutcomeKind::Held, 0.0, 0.0)
    } else if rolling <= 3.0 * p.mu_static * g {
        (OutcomeKind::Rolled, rolling, rolling / 3.0)
    } else {
        (OutcomeKind::Slid, (p.force - p.mu_kinetic * m * g - floor) / big_m, p.mu_kinetic * g)
    };
    let travel = p.offset + 0.5 * (a_disc - a_board) * p.max_time * p.max_time;
    let outcome = if travel.abs() > p.board_length / 2.0 { OutcomeKind::Unfinished } else { outcome };
    Law {
        outcome: Some(outcome),
        lower_acceleration: Some(a_board),
        upper_acceleration: Some(a_disc),
        measured: Measured::default(),
        text: "Held iff F <= mu_floor (M + m) g; else Rolled at A = (F - mu_floor (M + m) g) / (M + m / 3), \
               a_disc = A / 3, iff A <= 3 mu_s g; else Slid: a_disc = mu_k g; Unfinished once the rim's point \
               passes an end of the board",
    }
}

/// The puck's law (`docs/scenes.md`, "puck"): on the slope `tan(alpha)` against `mu_k`: below it
/// the puck stops (and `mu_s >= mu_k` holds it), above it it slides on; at it, launched across the
/// slope, its speed tends to half the launch speed (it slides on). On a level table it stops after
/// `v^2 / (2 mu_k g)` along its heading, at `v / (mu_k g)` (the first step's `mu_s` aside).
/// Stopping later than `max_time`, it ends `Slid`; on a slope where it stops by a time the law
/// bounds but not within `max_time`, the law does not decide (`None`).
#[must_use]
pub fn puck_law(p: &PuckParams<f64>) -> Law {
    let (v, g, mu) = (p.speed, p.gravity, p.mu_kinetic);
    let slope = p.angle.tan();
    let level = p.angle == 0.0;
    let (outcome, measured) = if v == 0.0 {
        // At rest from the start: it stays iff static friction holds it on the slope.
        (if slope <= p.mu_static { OutcomeKind::Stopped } else { OutcomeKind::Slid }, [None; 3])
    } else if level && mu * g > 0.0 {
        let stops = v / (mu * g) <= p.max_time;
        let heading = p.heading.to_degrees();
        let heading = heading - 360.0 * ((heading + 180.0) / 360.0).floor();
        let law = [Some(0.0), Some(v * v / (2.0 * mu * g)), Some(heading)];
        (if stops { OutcomeKind::Stopped } else { OutcomeKind::Slid }, if stops { law } else { [None; 3] })
    } else if slope < mu {
        // Friction outweighs the slope's pull along any heading: the speed falls at least at
        // `g (mu_k cos(alpha) - sin(alpha))`, so it has stopped by `v` over that; past
        // `max_time` the law does not say which comes first.
        let (s, c) = p.angle.sin_cos();
        let by = v / (g * (mu * c - s));
        (if by <= p.max_time { OutcomeKind::Stopped } else { OutcomeKind::Unfinished }, [None; 3])
    } else {
        // At `mu_k = tan(alpha)` (to round-off), launched across the slope.
        let half =
            ((slope - mu).abs() <= 1e-12 * slope && p.heading.abs() <= f64::EPSILON).then_some(v / 2.0);
        (OutcomeKind::Slid, [half, None, None])
    };
    Law {
        // `Unfinished` above stands for "not decided by max_time": no outcome.
        outcome: (outcome != OutcomeKind::Unfinished).then_some(outcome),
        lower_acceleration: None,
        upper_acceleration: None,
        measured: Measured::of(SceneKind::Puck, measured),
        text: "level table: Stopped after v^2 / (2 mu_k g) along its heading; incline: Stopped iff tan(angle) < mu_k, \
               else Slid (at mu_k = tan(angle), launched across the slope, tending to half the launch speed)",
    }
}

/// The billiard ball's law (`docs/scenes.md`, "billiard"): its slip `u0 = (v0 - R spin_y, R
/// spin_x)` shrinks along its own direction at `7 mu_k g / 2`; it rolls from `2 |u0| / (7 mu_k g)`
/// at `(5 v0 + 2 R omega0 x z) / 7` (the first step's `mu_s` aside); later than `max_time`, the run
/// ends `Unfinished`.
#[must_use]
pub fn billiard_law(p: &BilliardParams<f64>) -> Law {
    let (r, g, mu) = (p.radius, p.gravity, p.mu_kinetic);
    let slip = (p.speed - r * p.spin_y).hypot(r * p.spin_x);
    let t = if slip == 0.0 { 0.0 } else { 2.0 * slip / (7.0 * mu * g) };
    let rolls = t.is_finite() && t <= p.max_time;
    let v = [(5.0 * p.speed + 2.0 * r * p.spin_y) / 7.0, -2.0 * r * p.spin_x / 7.0];
    Law {
        outcome: Some(if rolls { OutcomeKind::Rolled } else { OutcomeKind::Unfinished }),
        lower_acceleration: None,
        upper_acceleration: None,
        measured: Measured::of(
            SceneKind::Billiard,
            if rolls { [Some(t), Some(v[0]), Some(v[1])] } else { [None; 3] },
        ),
        text: "Rolled at t = 2 |u0| / (7 mu_k g), u0 = (v0 - R spin_y, R spin_x), at v = (5 v0 + 2 R omega0 x z) / 7",
    }
}

/// The curling stone's law (`docs/scenes.md`, "curling"; Farkas, Bartels, Unger & Wolf, PRL 90,
/// 248302 (2003)): sliding and spinning stop together, `v / (R omega)` tending to 1 for a ring and
/// to 0.6530 for a uniform disc (the root of `F(e) / e = 2 T(e)`, derived there), whatever the
/// launch; the stopping time has no closed form. A launch without spin or without speed has no
/// ratio.
#[must_use]
pub fn curling_law(p: &CurlingParams<f64>) -> Law {
    let ratio =
        if p.speed > 0.0 && p.spin != 0.0 { Some(if p.is_ring() { 1.0 } else { 0.653 }) } else { None };
    Law {
        outcome: Some(OutcomeKind::Stopped),
        lower_acceleration: None,
        upper_acceleration: None,
        measured: Measured::of(SceneKind::Curling, [ratio, None, None]),
        text: "Stopped: sliding and spinning end together, v / (R omega) -> 1 (ring), 0.653 (uniform disc)",
    }
}
