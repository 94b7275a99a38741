//! The grid's scenes in three dimensions (`docs/scenes.md`, "Scenes in three dimensions"), each
//! with what its law decides ([`crate::bodies::law`]): the puck, the billiard ball and the curling
//! stone at masses from 1e-3 to 1e3 kg, steps from 1e-6 to 0.1 s, friction from 0 to 1e4, launch
//! speeds to 100 m/s and spins to 1e4 rad/s; the stack in three dimensions held and falling at
//! steps from 1e-6 to 0.1 s and friction from 0 to 1e4.

use meterstick_core::scene::StackSetup;
use meterstick_core::scene::spatial::{BilliardParams, CurlingParams, PuckParams, Stack3dParams};

use super::{Case, Claim};
use crate::scenes::SceneParams;
use crate::trajectory::OutcomeKind;

/// The law's outcome where it decides one away from its threshold: the puck's stop against
/// `max_time` and its slope against `mu_k` (5 % apart), the ball's rolling time against
/// `max_time`; the stone always stops (its law has no time: its runs are long enough).
fn law_claim(spec: &SceneParams) -> Option<OutcomeKind> {
    let clear = |a: f64, b: f64| (a - b).abs() > 0.05 * a.abs().max(b.abs());
    let law = crate::bodies::law(spec)?;
    let decided = match spec {
        SceneParams::Puck(p) => {
            let g = p.gravity;
            let stop = if p.angle == 0.0 { p.speed / (p.mu_kinetic * g) } else { 0.0 };
            clear(p.angle.tan(), p.mu_kinetic) && (p.angle > 0.0 || clear(stop, p.max_time))
        }
        SceneParams::Billiard(_) => {
            law.measured.rolling_time_s.is_some_and(|t| clear(t, spec.max_time()))
                || law.outcome == Some(OutcomeKind::Unfinished)
        }
        SceneParams::Curling(_) => true,
        _ => false,
    };
    if decided { law.outcome } else { None }
}

/// The scenes in three dimensions of the grid.
#[must_use]
pub(super) fn cases(quick: bool) -> Vec<Case> {
    let mut out = Vec::new();
    let mut add = |name: String, spec: SceneParams, claim: Claim| {
        let outcome = law_claim(&spec);
        out.push(Case { group: "three dimensions", name, spec, start_dy: 0.0, outcome, claim });
    };
    let puck = PuckParams::<f64> { angle: 0.0, heading: 137f64.to_radians(), ..Default::default() };
    let mut pucks = vec![
        ("h=1e-1".to_string(), PuckParams { step: 1e-1, ..puck }),
        ("mu=1e4".to_string(), PuckParams { mu_static: 1e4, mu_kinetic: 1e4, ..puck }),
        ("mu=0 (slides on)".to_string(), PuckParams { mu_static: 0.0, mu_kinetic: 0.0, ..puck }),
    ];
    if !quick {
        pucks.extend([
            ("h=1e-6".to_string(), PuckParams { step: 1e-6, max_time: 0.5, ..puck }),
            ("m=1e-3 kg".to_string(), PuckParams { mass: 1e-3, ..puck }),
            ("m=1e3 kg".to_string(), PuckParams { mass: 1e3, ..puck }),
            ("100 m/s".to_string(), PuckParams { speed: 100.0, ..puck }),
            // Down a steep incline with little friction: it slides on.
            (
                "80 deg, mu=0.1".to_string(),
                PuckParams { angle: 80f64.to_radians(), mu_static: 0.1, mu_kinetic: 0.1, ..puck },
            ),
        ]);
    }
    for (label, p) in pucks {
        add(format!("puck {label}"), SceneParams::Puck(p), Claim::None);
    }
    // At rest on a 20 degree incline that its friction holds: it does not move.
    let held = PuckParams::<f64> {
        speed: 0.0,
        mu_static: 0.6,
        mu_kinetic: 0.6,
        max_time: 1.0,
        ..Default::default()
    };
    add("puck held on 20 deg".into(), SceneParams::Puck(held), Claim::BodyStill);

    let ball = BilliardParams::<f64> { spin_x: 30.0, spin_y: -40.0, ..Default::default() };
    let mut balls = vec![
        ("h=1e-1".to_string(), BilliardParams { step: 1e-1, ..ball }),
        ("mu=1e4".to_string(), BilliardParams { mu_static: 1e4, mu_kinetic: 1e4, ..ball }),
    ];
    if !quick {
        balls.extend([
            ("h=1e-6".to_string(), BilliardParams { step: 1e-6, max_time: 0.6, ..ball }),
            (
                "spin 1e3 rad/s".to_string(),
                BilliardParams { spin_x: 1e3, spin_y: -1e3, spin_z: 1e3, max_time: 30.0, ..ball },
            ),
            ("spin_z 1e4 rad/s".to_string(), BilliardParams { spin_z: 1e4, ..ball }),
            ("m=1e3 kg".to_string(), BilliardParams { mass: 1e3, ..ball }),
        ]);
    }
    for (label, p) in balls {
        add(format!("billiard {label}"), SceneParams::Billiard(p), Claim::None);
    }

    let stone = CurlingParams::<f64>::default();
    let mut stones = vec![("h=1e-2".to_string(), CurlingParams { step: 1e-2, ..stone })];
    if !quick {
        stones.extend([
            ("h=1e-1".to_string(), CurlingParams { step: 1e-1, ..stone }),
            ("ring".to_string(), CurlingParams { shape: 0.0, ..stone }),
            ("mu=1e4".to_string(), CurlingParams { mu: 1e4, ..stone }),
            ("spin 1e3 rad/s".to_string(), CurlingParams { spin: 1e3, max_time: 200.0, ..stone }),
            ("m=1e-3 kg".to_string(), CurlingParams { mass: 1e-3, ..stone }),
        ]);
    }
    for (label, p) in stones {
        add(format!("curling {label}"), SceneParams::Curling(p), Claim::None);
    }

    // The stack in three dimensions at 30 deg, as the planar stack's grid: held at 0.98 (still),
    // falling at 1.02; steps from 1e-6 to 0.1 s, friction from 0 to 1e4, 2 blocks. Not in the
    // quick subset: six of its thirteen cases fail today (`docs/scenes.md`, "stack-3d").
    if !quick {
        let stack =
            |blocks: f64, params: Stack3dParams<f64>| SceneParams::Stack3d(StackSetup { blocks, params });
        let base = Stack3dParams::<f64> { heading: 30f64.to_radians(), max_time: 1.0, ..Default::default() };
        for (h, max_time) in [(1e-6, 0.01), (1e-4, 1.0), (1e-1, 10.0)] {
            for (overhang, claim) in [(0.98, Claim::BodyStill), (1.02, Claim::None)] {
                let p = Stack3dParams { step: h, max_time, overhang, ..base };
                add(format!("stack-3d of 3 h={h:e} s={overhang}"), stack(3.0, p), claim);
            }
        }
        for mu in [0.0, 1e3, 1e4] {
            for (overhang, claim) in [(0.98, Claim::BodyStill), (1.02, Claim::None)] {
                let p = Stack3dParams { mu_static: mu, mu_kinetic: mu, overhang, ..base };
                add(format!("stack-3d of 3 mu={mu:e} s={overhang}"), stack(3.0, p), claim);
            }
        }
        let p = Stack3dParams { mu_static: 1.0, mu_kinetic: 0.1, overhang: 1.02, ..base };
        add("stack-3d of 2 mu_s=1 mu_k=0.1 s=1.02".into(), stack(2.0, p), Claim::None);
    }
    out
}
