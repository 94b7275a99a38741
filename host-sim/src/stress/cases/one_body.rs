//! The grid's scenes of one body: the meter stick at extreme speeds, steps, friction, masses,
//! shapes, gravities and edge geometries; blocks on steep and shallow inclines, very tall and very
//! flat; ladders frictionless, at and near the critical angle; Painlevé's rod jamming; cylinders
//! rolling and slipping; each with what statics or dynamics decides of its outcome.

use meterstick_core::scene::{CylinderParams, InclineParams, LadderParams, MeterStickParams, PainleveParams};

use super::{Case, Claim};
use crate::scenes::SceneParams;
use crate::trajectory::OutcomeKind;

/// The base scene: the paper's with finger 1 at -0.35 (asymmetric, as the main job's slow scene).
fn base() -> MeterStickParams<f64> {
    MeterStickParams { finger1_x: -0.35, ..MeterStickParams::paper() }
}

/// The base scene at finger speed `v`, with `stick_speed` 1e-4 of it (as the paper's 1e-5 of
/// 0.1 m/s) and room for the fingers to meet and the hold time.
fn at_speed(v: f64) -> MeterStickParams<f64> {
    let mut p = base();
    p.finger1_velocity = v;
    p.stick_speed = if v > 0.0 { 1e-4 * v } else { 1e-5 };
    p.max_time = if v > 0.0 { (1.2 * (p.finger2_x - p.finger1_x) / v + 5.0).min(1000.0) } else { 2.0 };
    p
}

/// The base scene scaled to rod length `l` with every dimensionless group kept
/// (`v / sqrt(g L)`, `h sqrt(g / L)`, `t / L`, ...): by similarity it ends as the base does.
fn similar(l: f64) -> MeterStickParams<f64> {
    let mut p = base();
    let k = l / p.rod_length;
    let kt = k.sqrt();
    for field in ["rod_length", "rod_thickness", "finger1_x", "finger2_x", "finger_width", "drop_limit"] {
        p.set(field, p.get(field).unwrap_or(f64::NAN) * k);
    }
    for field in ["finger1_velocity", "stick_speed", "step", "hold_time", "max_time"] {
        p.set(field, p.get(field).unwrap_or(f64::NAN) * kt);
    }
    p
}

/// A block on an incline at `deg` degrees, `w x hgt`, friction `mu_s / mu_k`.
fn incline(deg: f64, (w, hgt): (f64, f64), (mu_s, mu_k): (f64, f64)) -> SceneParams {
    SceneParams::Incline(InclineParams {
        angle: deg.to_radians(),
        width: w,
        height: hgt,
        mu_static: mu_s,
        mu_kinetic: mu_k,
        ..InclineParams::default()
    })
}

/// The incline's outcome by statics (`docs/formulation.md`): held when `tan a <= mu_s` and
/// `tan a < w/h`; tipped when `w/h < tan a < mu_s`; slid when `tan a > mu_s` and it tips neither
/// at rest (`tan a < w/h`) nor while sliding (friction at the base tips a sliding block when
/// `mu_k > w/h`). `None` near a boundary (within 2 %).
fn incline_claim(spec: &SceneParams) -> Option<OutcomeKind> {
    let SceneParams::Incline(p) = spec else { return None };
    let (tan, aspect) = (p.angle.tan(), p.width / p.height);
    let clear = |a: f64, b: f64| (a - b).abs() > 0.02 * a.abs().max(b.abs());
    if !(clear(tan, p.mu_static) && clear(tan, aspect) && clear(p.mu_kinetic, aspect)) {
        return None;
    }
    if tan < p.mu_static && tan < aspect {
        Some(OutcomeKind::Held)
    } else if aspect < tan && tan < p.mu_static {
        Some(OutcomeKind::Tipped)
    } else if tan > p.mu_static && tan < aspect && p.mu_kinetic < aspect {
        Some(OutcomeKind::Slid)
    } else {
        None
    }
}

/// A ladder at `deg` degrees with `mu_floor`, `mu_wall`.
fn ladder(deg: f64, mu_f: f64, mu_w: f64) -> SceneParams {
    SceneParams::Ladder(LadderParams {
        angle: deg.to_radians(),
        mu_floor: mu_f,
        mu_wall: mu_w,
        ..LadderParams::default()
    })
}

/// The ladder's outcome by statics: it stands iff `tan theta >= (1 - mu_f mu_w) / (2 mu_f)`;
/// `None` within 2 degrees of the critical angle (a near-critical ladder slips too slowly to
/// reach the floor in the run, or stands by round-off).
fn ladder_claim(spec: &SceneParams) -> Option<OutcomeKind> {
    let SceneParams::Ladder(p) = spec else { return None };
    let critical = if p.mu_floor > 0.0 {
        ((1.0 - p.mu_floor * p.mu_wall) / (2.0 * p.mu_floor)).atan()
    } else {
        std::f64::consts::FRAC_PI_2
    };
    let margin = 2f64.to_radians();
    if p.angle > critical + margin {
        Some(OutcomeKind::Held)
    } else if p.angle < critical - margin {
        Some(OutcomeKind::Fell)
    } else {
        None
    }
}

/// Painlevé's rod at `deg` degrees, `mu_s = mu_k = mu`, speed `v`, step `h`; `stick_speed` 1e-5 of `v` from
/// 1 m/s up (as [`at_speed`]: a slip threshold below `v`'s round-off would read an f32 jam as a
/// slide).
fn painleve(deg: f64, mu: f64, v: f64, h: f64) -> SceneParams {
    SceneParams::Painleve(PainleveParams {
        angle: deg.to_radians(),
        mu_static: mu,
        mu_kinetic: mu,
        speed: -v,
        step: h,
        stick_speed: 1e-5 * v.max(1.0),
        ..PainleveParams::default()
    })
}

/// Painlevé's rod's outcome by the law (docs/scenes.md): Jammed when `mu_k` exceeds
/// `(1 + 3 c^2) / (3 s c)` by more than 5 % and the impact `m V / 4 (1 + 3 c^2)` exceeds the
/// weight's impulse over four steps; `None` otherwise (below it, sliding or falling depends on the
/// run's length).
fn painleve_claim(spec: &SceneParams) -> Option<OutcomeKind> {
    let SceneParams::Painleve(p) = spec else { return None };
    let (s, c) = p.angle.sin_cos();
    let critical = (1.0 + 3.0 * c * c) / (3.0 * s * c);
    let impact = -p.mass * p.speed / 4.0 * (1.0 + 3.0 * c * c);
    (p.mu_kinetic > 1.05 * critical && impact > 4.0 * p.mass * p.gravity * p.step)
        .then_some(OutcomeKind::Jammed)
}

/// A cylinder at `deg` degrees, inertia ratio `k`, `mu_s` (and `mu_k = mu_s`).
fn cylinder(deg: f64, k: f64, mu: f64) -> SceneParams {
    SceneParams::Cylinder(CylinderParams {
        angle: deg.to_radians(),
        inertia_factor: k,
        mu_static: mu,
        mu_kinetic: mu,
        ..CylinderParams::default()
    })
}

/// The cylinder's outcome by the law: Rolled iff `tan a <= mu_s (1 + k) / k`; `None` within 2 %.
fn cylinder_claim(spec: &SceneParams) -> Option<OutcomeKind> {
    let SceneParams::Cylinder(p) = spec else { return None };
    let (tan, limit) = (p.angle.tan(), p.mu_static * (1.0 + p.inertia_factor) / p.inertia_factor);
    if (tan - limit).abs() <= 0.02 * limit {
        None
    } else if tan < limit {
        Some(OutcomeKind::Rolled)
    } else {
        Some(OutcomeKind::Slid)
    }
}

/// The scenes of one body (`quick`: the subset the test command runs).
#[must_use]
#[allow(clippy::too_many_lines)] // one table of cases
pub(super) fn cases(quick: bool) -> Vec<Case> {
    use OutcomeKind::{Balanced, Fell, Unfinished};
    let mut out = Vec::new();
    let mut add = |group, name: &str, spec: SceneParams, start_dy, outcome, claim| {
        out.push(Case { group, name: name.into(), spec, start_dy, outcome, claim });
    };
    let stick = SceneParams::MeterStick;
    let (balanced, fell, unfinished) = (Some(Balanced), Some(Fell), Some(Unfinished));

    // Finger speed, h = 1 ms.
    add("speed", "v=0", stick(at_speed(0.0)), 0.0, unfinished, Claim::BodyStill);
    if !quick {
        add("speed", "v=1e-4 (10^6 steps)", stick(at_speed(1e-4)), 0.0, unfinished, Claim::None);
        add("speed", "v=1e-3", stick(at_speed(1e-3)), 0.0, balanced, Claim::None);
        add("speed", "v=1e-2", stick(at_speed(1e-2)), 0.0, balanced, Claim::None);
    }
    add("speed", "v=0.1", stick(at_speed(0.1)), 0.0, balanced, Claim::None);
    if !quick {
        add("speed", "v=1", stick(at_speed(1.0)), 0.0, fell, Claim::None);
        add("speed", "v=10", stick(at_speed(10.0)), 0.0, fell, Claim::None);
        let both = MeterStickParams { finger2_velocity: -0.05, finger1_velocity: 0.05, ..at_speed(0.05) };
        add("speed", "both fingers inward 0.05", stick(both), 0.0, balanced, Claim::None);
        let second = MeterStickParams {
            finger1_x: -0.4,
            finger2_x: 0.35,
            finger1_velocity: 0.0,
            finger2_velocity: -0.1,
            ..at_speed(0.1)
        };
        add("speed", "finger 2 moves", stick(second), 0.0, balanced, Claim::None);
    }
    add("speed", "v=100", stick(at_speed(100.0)), 0.0, fell, Claim::None);

    // Time step.
    let with_h = |v: f64, h: f64, max_time: Option<f64>| {
        let mut p = at_speed(v);
        p.step = h;
        if let Some(t) = max_time {
            p.max_time = t;
        }
        stick(p)
    };
    if !quick {
        add("h", "v=0.1 h=1e-5", with_h(0.1, 1e-5, None), 0.0, balanced, Claim::None);
        add("h", "v=0.1 h=1e-4", with_h(0.1, 1e-4, None), 0.0, balanced, Claim::None);
        add("h", "v=0.1 h=1e-2", with_h(0.1, 1e-2, None), 0.0, None, Claim::None);
        add("h", "v=0.1 h=5e-2", with_h(0.1, 5e-2, None), 0.0, None, Claim::None);
        add("h", "v=1 h=1e-6", with_h(1.0, 1e-6, Some(1.0)), 0.0, fell, Claim::None);
        add("h", "v=1 h=5e-2", with_h(1.0, 5e-2, None), 0.0, None, Claim::None);
        add("h", "v=0.1 h=10 (> crossing time 7 s)", with_h(0.1, 10.0, None), 0.0, None, Claim::None);
    }
    add("h", "v=10 h=0.1 (> crossing time 0.07 s)", with_h(10.0, 0.1, None), 0.0, None, Claim::None);

    // Friction.
    let with_mu =
        |mu_s: f64, mu_k: f64| stick(MeterStickParams { mu_static: mu_s, mu_kinetic: mu_k, ..base() });
    add("friction", "mu=0 (frictionless)", with_mu(0.0, 0.0), 0.0, fell, Claim::NotDragged);
    if !quick {
        add("friction", "mu_s=0.6 mu_k=0", with_mu(0.6, 0.0), 0.0, fell, Claim::NotDragged);
        add("friction", "mu_s=mu_k=0.4", with_mu(0.4, 0.4), 0.0, None, Claim::None);
        add("friction", "mu_s=0.05 mu_k=0.04", with_mu(0.05, 0.04), 0.0, None, Claim::None);
        add("friction", "mu_s=mu_k=10", with_mu(10.0, 10.0), 0.0, None, Claim::None);
        add("friction", "mu_s=10 mu_k=5", with_mu(10.0, 5.0), 0.0, None, Claim::None);
    }

    // Mass: every force scales with m, so the motion does not depend on it.
    for (k, mass) in [1e-4, 1e-2, 1.0, 1e2, 1e4].into_iter().enumerate() {
        if quick && k != 0 && k != 4 {
            continue;
        }
        add(
            "mass",
            &format!("m={mass:e} kg"),
            stick(MeterStickParams { rod_mass: mass, ..base() }),
            0.0,
            balanced,
            Claim::None,
        );
    }

    // Rod shape: similar rods end as the base does; thin and thick rods, and unscaled short and
    // long rods, make no claim.
    if !quick {
        add("shape", "similar L=0.01 m", stick(similar(0.01)), 0.0, balanced, Claim::None);
        add("shape", "similar L=100 m", stick(similar(100.0)), 0.0, balanced, Claim::None);
        let short = MeterStickParams {
            rod_length: 0.01,
            finger1_x: -0.0035,
            finger2_x: 0.004,
            finger_width: 1e-4,
            ..base()
        };
        add("shape", "short L=0.01 m, v=0.1", stick(short), 0.0, None, Claim::None);
        let long = MeterStickParams {
            rod_length: 100.0,
            finger1_x: -35.0,
            finger2_x: 40.0,
            finger_width: 1.0,
            drop_limit: 2.0,
            ..base()
        };
        add("shape", "long L=100 m, v=0.1", stick(long), 0.0, None, Claim::None);
        add(
            "shape",
            "thin t=1e-5 m",
            stick(MeterStickParams { rod_thickness: 1e-5, ..base() }),
            0.0,
            balanced,
            Claim::None,
        );
        add(
            "shape",
            "thick t=0.2 m",
            stick(MeterStickParams { rod_thickness: 0.2, ..base() }),
            0.0,
            None,
            Claim::None,
        );
    }

    // Gravity.
    let gravities =
        [(0.0, unfinished, Claim::BodyStill), (1.0, None, Claim::None), (100.0, balanced, Claim::None)];
    for (k, (g, outcome, claim)) in gravities.into_iter().enumerate() {
        if quick && k != 0 {
            continue;
        }
        add(
            "gravity",
            &format!("g={g}"),
            stick(MeterStickParams { gravity: g, max_time: 10.0, ..base() }),
            0.0,
            outcome,
            claim,
        );
    }

    // Geometry at the edges.
    if !quick {
        let p = MeterStickParams { finger1_x: -0.5, finger2_x: 0.5, ..base() };
        add("edges", "fingers at the rod ends", stick(p), 0.0, None, Claim::None);
        let p = MeterStickParams { finger1_x: -0.0051, finger2_x: 0.005, ..base() };
        add("edges", "fingers nearly together", stick(p), 0.0, balanced, Claim::None);
        add(
            "edges",
            "finger width 1e-6 m",
            stick(MeterStickParams { finger_width: 1e-6, ..base() }),
            0.0,
            None,
            Claim::None,
        );
        add(
            "edges",
            "finger 1 under the COM",
            stick(MeterStickParams { finger1_x: 0.0, ..base() }),
            0.0,
            None,
            Claim::None,
        );
        let p = MeterStickParams { finger1_x: -0.4, finger2_x: 0.0, ..base() };
        add("edges", "finger 2 under the COM", stick(p), 0.0, None, Claim::None);
        let p = MeterStickParams { finger1_y: 0.02, ..base() };
        add("edges", "finger 1 raised 2 cm", stick(p), 0.0, None, Claim::None);
        add("edges", "drop from 1 cm", stick(base()), 0.01, None, Claim::None);
    }
    add("edges", "drop from 1 mm", stick(base()), 1e-3, balanced, Claim::None);
    add("edges", "penetrating 0.1 mm", stick(base()), -1e-4, balanced, Claim::None);
    if !quick {
        add("edges", "penetrating 1 mm", stick(base()), -1e-3, balanced, Claim::None);
        add(
            "edges",
            "penetrating 0.1 mm, h=1e-5",
            stick(MeterStickParams { step: 1e-5, ..base() }),
            -1e-4,
            balanced,
            Claim::None,
        );
    }

    // Block on an incline (outcome by statics, where it is clear).
    let mut add_incline = |name: &str, spec: SceneParams, claim: Claim| {
        let outcome = incline_claim(&spec);
        out.push(Case { group: "incline", name: name.into(), spec, start_dy: 0.0, outcome, claim });
    };
    add_incline("incline 35 deg (slides)", incline(35.0, (0.1, 0.05), (0.6, 0.4)), Claim::None);
    add_incline("incline tall box tips", incline(20.0, (0.05, 0.2), (0.6, 0.4)), Claim::None);
    if !quick {
        add_incline("incline 1 deg (held)", incline(1.0, (0.1, 0.05), (0.6, 0.4)), Claim::BodyStill);
        add_incline(
            "incline 80 deg flat box mu=10 (held)",
            incline(80.0, (1.0, 0.01), (10.0, 10.0)),
            Claim::BodyStill,
        );
        add_incline("incline 80 deg mu=0.6 flat box", incline(80.0, (1.0, 0.01), (0.6, 0.4)), Claim::None);
        add_incline("incline 30 deg frictionless", incline(30.0, (0.1, 0.05), (0.0, 0.0)), Claim::None);
        add_incline("incline very tall box 5 deg", incline(5.0, (0.01, 1.0), (0.6, 0.4)), Claim::None);
        add_incline("incline very flat box 40 deg", incline(40.0, (1.0, 0.001), (0.6, 0.4)), Claim::None);
        add_incline("incline 0 deg (level)", incline(0.0, (0.1, 0.05), (0.6, 0.4)), Claim::BodyStill);
    }

    // Ladder (outcome by statics, away from the critical angle).
    let mut add_ladder = |name: &str, spec: SceneParams, claim: Claim| {
        let outcome = ladder_claim(&spec);
        out.push(Case { group: "ladder", name: name.into(), spec, start_dy: 0.0, outcome, claim });
    };
    add_ladder("ladder 60 deg (stands)", ladder(60.0, 0.4, 0.3), Claim::BodyStill);
    add_ladder("ladder frictionless 60 deg", ladder(60.0, 0.0, 0.0), Claim::None);
    if !quick {
        let critical = ((1.0 - 0.4 * 0.3) / (2.0 * 0.4_f64)).atan().to_degrees();
        add_ladder("ladder at the critical angle", ladder(critical, 0.4, 0.3), Claim::None);
        add_ladder("ladder 40 deg (slips)", ladder(40.0, 0.4, 0.3), Claim::None);
        add_ladder("ladder 5 deg mu=10", ladder(5.0, 10.0, 10.0), Claim::BodyStill);
        add_ladder("ladder 89 deg frictionless", ladder(89.0, 0.0, 0.0), Claim::None);
        add_ladder("ladder 10 deg mu_floor=0.4", ladder(10.0, 0.4, 0.0), Claim::None);
    }

    // Painlevé's rod (docs/scenes.md, "painleve"): the classic stiff case of rigid contact with
    // friction. Above the critical mu the sliding end jams in one step under an impact whose
    // impulse does not shrink with h; the outcome by the law away from the critical mu (within
    // 5 %, or an impact below the weight's impulse over a step, the outcome is left open).
    let mut add_painleve = |name: &str, spec: SceneParams| {
        let outcome = painleve_claim(&spec);
        out.push(Case {
            group: "painleve",
            name: name.into(),
            spec,
            start_dy: 0.0,
            outcome,
            claim: Claim::None,
        });
    };
    add_painleve("painleve 30 deg mu=3 (jams)", painleve(30.0, 3.0, 1.0, 1e-3));
    if !quick {
        add_painleve("painleve 30 deg mu=3 h=1e-6", painleve(30.0, 3.0, 1.0, 1e-6));
        add_painleve("painleve 63.4 deg mu=1.4 (near the least critical mu)", painleve(63.4, 1.4, 1.0, 1e-3));
        add_painleve("painleve 45 deg mu=1 (slides, falls)", painleve(45.0, 1.0, 1.0, 1e-3));
        add_painleve("painleve 45 deg mu=100", painleve(45.0, 100.0, 1.0, 1e-3));
        add_painleve("painleve 45 deg mu=3 V=100 m/s", painleve(45.0, 3.0, 100.0, 1e-3));
        add_painleve("painleve 85 deg mu=12", painleve(85.0, 12.0, 1.0, 1e-3));
        add_painleve("painleve 30 deg mu=3 V=1e-3 m/s (impact below m g h)", painleve(30.0, 3.0, 1e-3, 1e-3));
    }

    // A cylinder on an incline (docs/scenes.md, "cylinder"): rolls iff tan a <= mu_s (1 + k) / k.
    if !quick {
        let mut add_cylinder = |name: &str, spec: SceneParams| {
            let outcome = cylinder_claim(&spec);
            out.push(Case {
                group: "cylinder",
                name: name.into(),
                spec,
                start_dy: 0.0,
                outcome,
                claim: Claim::None,
            });
        };
        add_cylinder("cylinder 30 deg k=0.5 (rolls)", cylinder(30.0, 0.5, 0.6));
        add_cylinder("cylinder 75 deg k=1 (slips)", cylinder(75.0, 1.0, 0.6));
        add_cylinder("cylinder 89 deg k=1e-3 mu=0.1 (near a point mass: rolls)", cylinder(89.0, 1e-3, 0.1));
        add_cylinder("cylinder 30 deg frictionless (slips)", cylinder(30.0, 0.5, 0.0));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn statics_claims() {
        assert_eq!(incline_claim(&incline(35.0, (0.1, 0.05), (0.6, 0.4))), Some(OutcomeKind::Slid));
        assert_eq!(incline_claim(&incline(20.0, (0.05, 0.2), (0.6, 0.4))), Some(OutcomeKind::Tipped));
        assert_eq!(incline_claim(&incline(10.0, (0.1, 0.05), (0.6, 0.4))), Some(OutcomeKind::Held));
        assert_eq!(incline_claim(&incline(30.96, (0.1, 0.05), (0.6, 0.4))), None); // tan = 0.6: boundary
        assert_eq!(ladder_claim(&ladder(60.0, 0.4, 0.3)), Some(OutcomeKind::Held));
        assert_eq!(ladder_claim(&ladder(40.0, 0.4, 0.3)), Some(OutcomeKind::Fell));
        assert_eq!(ladder_claim(&ladder(47.7, 0.4, 0.3)), None);
        assert_eq!(ladder_claim(&ladder(60.0, 0.0, 0.0)), Some(OutcomeKind::Fell));
        // Painleve: critical mu 2.50 at 30 degrees, 1.67 at 45.
        assert_eq!(painleve_claim(&painleve(30.0, 3.0, 1.0, 1e-3)), Some(OutcomeKind::Jammed));
        assert_eq!(painleve_claim(&painleve(30.0, 2.55, 1.0, 1e-3)), None); // within 5 %
        assert_eq!(painleve_claim(&painleve(45.0, 1.0, 1.0, 1e-3)), None); // below: no claim
        assert_eq!(painleve_claim(&painleve(30.0, 3.0, 1e-3, 1e-3)), None); // impact below m g h
        // Cylinder, k = 0.5, mu_s = 0.6: rolls up to tan a = 1.8 (60.9 degrees).
        assert_eq!(cylinder_claim(&cylinder(60.0, 0.5, 0.6)), Some(OutcomeKind::Rolled));
        assert_eq!(cylinder_claim(&cylinder(62.0, 0.5, 0.6)), Some(OutcomeKind::Slid));
        assert_eq!(cylinder_claim(&cylinder(60.95, 0.5, 0.6)), None);
    }
}
