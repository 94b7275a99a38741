//! The grid's scenes of several bodies (`docs/scenes.md`), each with what the laws decide.

use meterstick_core::multibody::scenes::{
    BlockOnBlockParams, DiscOnBoardParams, StackParams, TableclothParams,
};
use meterstick_core::scene::StackSetup;

use super::{Case, Claim};
use crate::scenes::SceneParams;
use crate::trajectory::OutcomeKind;

/// The law's outcome of a scene of several bodies (`docs/scenes.md`; [`crate::bodies::law`])
/// where it is clear: every threshold the scene's parameters meet more than 5 % away (the
/// pulled scenes: the pull against `mu_floor (M + m) g` and `(mu_s + mu_floor) (M + m) g`; the
/// stack: its overhang scale against 1), and a tablecloth's `Stayed` only with the board out within
/// the run (the block's trailing distance `L_b - offset` covered at the relative acceleration of
/// the law before `max_time`), a sliding top block only while it stays in full contact.
fn law_claim(spec: &SceneParams) -> Option<OutcomeKind> {
    let clear = |a: f64, b: f64| (a - b).abs() > 0.05 * a.abs().max(b.abs());
    let law = crate::bodies::law(spec)?;
    let pulled = |force: f64, total: f64, mu_s: f64, mu_floor: f64, g: f64| {
        clear(force, mu_floor * total * g) && clear(force, (mu_s + mu_floor) * total * g)
    };
    let decided = match spec {
        SceneParams::BlockOnBlock(p) => {
            // A sliding top block stays in full contact over the run: its rear corner does not
            // reach the bottom block's end (there it tips off the edge or slides off it, whichever
            // comes first: no law decides the race).
            let in_contact = match (law.outcome, law.lower_acceleration, law.upper_acceleration) {
                (Some(OutcomeKind::Slid), Some(bottom), Some(top)) => {
                    0.5 * (bottom - top) * p.max_time * p.max_time < 0.5 * (p.bottom_width - p.top_width)
                }
                _ => true,
            };
            pulled(p.force, p.top_mass + p.bottom_mass, p.mu_static, p.mu_floor, p.gravity)
                // Tipping against riding: a = g w / h.
                && law.lower_acceleration.is_none_or(|a| clear(a, p.gravity * p.top_width / p.top_height))
                && in_contact
        }
        SceneParams::Tablecloth(p) => {
            let riding = pulled(p.force, p.block_mass + p.board_mass, p.mu_static, p.mu_floor, p.gravity);
            let out_in_time = match (law.lower_acceleration, law.upper_acceleration) {
                (Some(board), Some(block)) if law.outcome == Some(OutcomeKind::Stayed) => {
                    let distance = p.board_length - p.offset;
                    board > block && (2.0 * distance / (board - block)).sqrt() < 0.5 * p.max_time
                }
                _ => true,
            };
            // The law has no tipping for the block: a riding block that would tip is left open.
            let tips = law.outcome == Some(OutcomeKind::Rode)
                && law
                    .upper_acceleration
                    .is_some_and(|a| a >= 0.95 * p.gravity * p.block_width / p.block_height);
            riding && out_in_time && !tips
        }
        SceneParams::Stack(s) => clear(s.params.overhang, 1.0),
        // Disc-on-board: the pull against `mu_floor (M + m) g`, the rolling board's acceleration
        // against `3 mu_s g`, and the rim on the board to the end also as the implicit step moves
        // it (`a T (T + h) / 2` after `T / h` steps of `a h^2 n (n + 1) / 2`, not `a T^2 / 2`).
        SceneParams::DiscOnBoard(p) => {
            let floor = p.mu_floor * (p.board_mass + p.disc_mass) * p.gravity;
            let rolling = (p.force - floor) / (p.board_mass + p.disc_mass / 3.0);
            let stepped = match (law.lower_acceleration, law.upper_acceleration) {
                (Some(board), Some(disc)) => {
                    p.offset + 0.5 * (disc - board) * p.max_time * (p.max_time + p.step)
                }
                _ => f64::NAN,
            };
            clear(p.force, floor)
                && clear(rolling, 3.0 * p.mu_static * p.gravity)
                && law.outcome != Some(OutcomeKind::Unfinished)
                && stepped.abs() < 0.5 * p.board_length
        }
        _ => false,
    };
    if decided { law.outcome } else { None }
}

/// The scenes of several bodies (`docs/scenes.md`): mass ratios 1:1000 both ways, steps from
/// 1e-6 s to 0.1 s, friction up to 1e4, each case's outcome by the laws where they decide it,
/// held cases still, and block-on-block's and disc-on-board's accelerations the laws'.
#[must_use]
#[allow(clippy::too_many_lines)] // one table of cases
pub(super) fn cases(quick: bool) -> Vec<Case> {
    let mut out = Vec::new();
    let mut add = |group: &'static str, name: String, spec: SceneParams, claim: Claim| {
        let outcome = law_claim(&spec);
        out.push(Case { group, name, spec, start_dy: 0.0, outcome, claim });
    };
    let bob = BlockOnBlockParams::<f64>::default();
    let g = bob.gravity;
    // The pull at a fraction of the way between the laws' thresholds: 0.5 holds, 1.5 rides (half
    // way), 3 slides (1.5 x the riding threshold).
    let pull = |p: &BlockOnBlockParams<f64>, regime: f64| {
        let total = p.top_mass + p.bottom_mass;
        let (held, riding) = (p.mu_floor * total * g, (p.mu_static + p.mu_floor) * total * g);
        match regime {
            r if r < 1.0 => r * held,
            r if r < 2.0 => 0.5 * (held + riding),
            r => 0.5 * r * riding,
        }
    };
    let regimes = [
        (0.5, "held", Claim::BodyStill),
        (1.5, "rides", Claim::LawAccelerations),
        (3.0, "slides", Claim::LawAccelerations),
    ];
    let mut variants = Vec::new();
    if !quick {
        for (top, bottom) in [(1.0, 1000.0), (1000.0, 1.0)] {
            variants.push((
                format!("m:M = {top}:{bottom}"),
                BlockOnBlockParams { top_mass: top, bottom_mass: bottom, max_time: 0.2, ..bob },
            ));
        }
    }
    // Durations within full contact (a sliding top block reaches the end in 0.22 s at the defaults).
    for (h, max_time) in [(1e-6, 0.01), (1e-4, 0.2), (1e-2, 0.2), (1e-1, 0.2)] {
        if !quick || h >= 1e-2 {
            variants.push((format!("h={h:e}"), BlockOnBlockParams { step: h, max_time, ..bob }));
        }
    }
    for (label, p) in variants {
        for &(regime, word, claim) in &regimes {
            let p = BlockOnBlockParams { force: pull(&p, regime), ..p };
            add(
                "block-on-block",
                format!("block-on-block {label} {word}"),
                SceneParams::BlockOnBlock(p),
                claim,
            );
        }
    }
    if !quick {
        for mu in [1e3, 1e4] {
            let p = BlockOnBlockParams { mu_static: mu, mu_kinetic: mu, ..bob };
            add(
                "block-on-block",
                format!("block-on-block mu_s=mu_k={mu:e} (rides)"),
                SceneParams::BlockOnBlock(p),
                Claim::LawAccelerations,
            );
            let p = BlockOnBlockParams { mu_floor: mu, ..bob };
            add(
                "block-on-block",
                format!("block-on-block mu_floor={mu:e} (held)"),
                SceneParams::BlockOnBlock(p),
                Claim::BodyStill,
            );
        }
        let p = BlockOnBlockParams { mu_static: 0.0, mu_kinetic: 0.0, mu_floor: 0.0, ..bob };
        add(
            "block-on-block",
            "block-on-block frictionless".into(),
            SceneParams::BlockOnBlock(p),
            Claim::LawAccelerations,
        );
    }

    let cloth = TableclothParams::<f64>::default();
    let riding =
        |p: &TableclothParams<f64>| (p.mu_static + p.mu_floor) * (p.block_mass + p.board_mass) * p.gravity;
    for (block, board) in [(1.0, 1e-3), (1e-3, 1.0)] {
        let p = TableclothParams { block_mass: block, board_mass: board, ..cloth };
        for (k, word) in [(0.5, "rides"), (3.0, "pulled out")] {
            if quick {
                continue;
            }
            let q = TableclothParams { force: k * riding(&p), ..p };
            add(
                "tablecloth",
                format!("tablecloth m:m_b = {block}:{board} {word}"),
                SceneParams::Tablecloth(q),
                Claim::None,
            );
        }
    }
    for (h, max_time) in [(1e-6, 0.01), (1e-1, 1.0)] {
        if quick && h < 1e-2 {
            continue;
        }
        let p = TableclothParams { step: h, max_time, ..cloth };
        add("tablecloth", format!("tablecloth h={h:e}"), SceneParams::Tablecloth(p), Claim::None);
    }
    if !quick {
        let p = TableclothParams { mu_static: 1e3, mu_kinetic: 1e3, ..cloth };
        add("tablecloth", "tablecloth mu_s=mu_k=1e3 (rides)".into(), SceneParams::Tablecloth(p), Claim::None);
        let p = TableclothParams { mu_floor: 1e3, ..cloth };
        add(
            "tablecloth",
            "tablecloth mu_floor=1e3 (held)".into(),
            SceneParams::Tablecloth(p),
            Claim::BodyStill,
        );
    }

    let stack = |blocks: f64, params: StackParams<f64>| SceneParams::Stack(StackSetup { blocks, params });
    let base = StackParams::<f64> { max_time: 1.0, ..StackParams::default() };
    for (h, max_time) in [(1e-6, 0.01), (1e-4, 1.0), (1e-1, 10.0)] {
        if quick && h < 1e-2 {
            continue;
        }
        for (overhang, claim) in [(0.98, Claim::BodyStill), (1.02, Claim::None)] {
            let p = StackParams { step: h, max_time, overhang, ..base };
            add("stack", format!("stack of 3 h={h:e} s={overhang}"), stack(3.0, p), claim);
        }
    }
    if !quick {
        for mu in [0.0, 1e3, 1e4] {
            for (overhang, claim) in [(0.98, Claim::BodyStill), (1.02, Claim::None)] {
                let p = StackParams { mu_static: mu, mu_kinetic: mu, overhang, ..base };
                add("stack", format!("stack of 3 mu={mu:e} s={overhang}"), stack(3.0, p), claim);
            }
        }
        let p = StackParams { mu_static: 1.0, mu_kinetic: 0.1, overhang: 1.02, ..base };
        add("stack", "stack of 2 mu_s=1 mu_k=0.1 s=1.02".into(), stack(2.0, p), Claim::None);
    }

    // Disc-on-board: held (half the floor's hold), rolling (half way to the rolling limit),
    // sliding (1.5 x the rolling limit, 0.1 s: the disc stays on the board); steps from 1e-6 s to
    // 0.1 s, mass ratios 1:1000 both ways.
    let disc = DiscOnBoardParams::<f64>::default();
    let pull = |p: &DiscOnBoardParams<f64>, regime: f64| {
        let held = p.mu_floor * (p.board_mass + p.disc_mass) * p.gravity;
        let rolls = 3.0 * p.mu_static * p.gravity * (p.board_mass + p.disc_mass / 3.0) + held;
        match regime {
            r if r < 1.0 => r * held,
            r if r < 2.0 => 0.5 * (held + rolls),
            r => 0.5 * r * rolls,
        }
    };
    let mut variants = Vec::new();
    if !quick {
        for (m, big_m) in [(1.0, 1000.0), (1000.0, 1.0)] {
            variants.push((
                format!("m:M = {m}:{big_m}"),
                DiscOnBoardParams { disc_mass: m, board_mass: big_m, max_time: 0.1, ..disc },
            ));
        }
    }
    for (h, max_time) in [(1e-6, 0.01), (1e-4, 0.1), (1e-2, 0.1), (1e-1, 0.2)] {
        if !quick || h >= 1e-2 {
            variants.push((format!("h={h:e}"), DiscOnBoardParams { step: h, max_time, ..disc }));
        }
    }
    for (label, p) in variants {
        for (regime, word, claim) in [
            (0.5, "held", Claim::BodyStill),
            (1.5, "rolls", Claim::LawAccelerations),
            (3.0, "slides", Claim::LawAccelerations),
        ] {
            let p = DiscOnBoardParams { force: pull(&p, regime), ..p };
            add("disc-on-board", format!("disc-on-board {label} {word}"), SceneParams::DiscOnBoard(p), claim);
        }
    }
    out
}
