//! What `docs/scenes.md`'s laws say of the scenes of several bodies.

use meterstick_core::multibody::scenes::DiscOnBoardParams;
use meterstick_core::scene::{OutcomeKind, SceneParams};

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
            text: "Held iff the overhang scale s < 1 (every block's load inside the edge below it), Fell above",
        },
        SceneParams::DiscOnBoard(p) => disc_on_board_law(&p),
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
        text: "Held iff F <= mu_floor (M + m) g; else Rolled at A = (F - mu_floor (M + m) g) / (M + m / 3), \
               a_disc = A / 3, iff A <= 3 mu_s g; else Slid: a_disc = mu_k g; Unfinished once the rim's point \
               passes an end of the board",
    }
}
