//! The grid of `host-sim stress`: one [`Case`] per stiff or extreme scene, with what physics says
//! about it where physics decides.

use meterstick_core::multibody::scenes::{
    BlockOnBlockParams, DiscOnBoardParams, StackParams, TableclothParams,
};
use meterstick_core::scene::{
    CylinderParams, InclineParams, LadderParams, MeterStickParams, PainleveParams, StackSetup,
};

use crate::scenes::SceneParams;
use crate::trajectory::OutcomeKind;

/// A physics claim a case makes beyond the generic criteria.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Claim {
    /// None: the generic criteria only.
    None,
    /// While finger 1 is left of the centre of mass (by 1 % of `L`), the rod does not move along
    /// `x` (frictionless contacts or `mu_k = 0`: no force can drag it).
    NotDragged,
    /// The body does not move at all (zero finger speed, zero gravity, a block held by friction;
    /// a scene of several bodies: none of them moves).
    BodyStill,
    /// Block-on-block: the measured accelerations in full contact are the laws' (`docs/scenes.md`,
    /// within [`super::bodies::acceleration_tolerance`]).
    LawAccelerations,
}

/// One scene of the grid.
#[derive(Debug, Clone)]
pub struct Case {
    /// Which part of the grid.
    pub group: &'static str,
    /// A short name, unique.
    pub name: String,
    /// The scene.
    pub spec: SceneParams,
    /// Meter stick: start height above the resting position (m; negative: penetrating).
    pub start_dy: f64,
    /// The outcome class physics decides, if any.
    pub outcome: Option<OutcomeKind>,
    /// Further claim.
    pub claim: Claim,
}

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

/// The grid (`quick`: the subset the test command runs).
#[must_use]
#[allow(clippy::too_many_lines)] // one table of cases
pub fn cases(quick: bool) -> Vec<Case> {
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

    out.extend(multibody_cases(quick));

    if quick {
        // Short runs (at most 5 s simulated): the subset checks the criteria, not long physics; a
        // run cut short cannot balance.
        for c in &mut out {
            if c.spec.max_time() > 5.0 {
                c.spec.set("max_time", 5.0);
                if c.outcome == balanced {
                    c.outcome = unfinished;
                }
            }
        }
    }
    out
}

/// The law's outcome of a scene of several bodies (`docs/scenes.md`; [`crate::multibody::law`])
/// where it is clear: every threshold the scene's parameters meet more than 5 % away (the
/// pulled scenes: the pull against `mu_floor (M + m) g` and `(mu_s + mu_floor) (M + m) g`; the
/// stack: its overhang scale against 1), and a tablecloth's `Stayed` only with the board out within
/// the run (the block's trailing distance `L_b - offset` covered at the relative acceleration of
/// the law before `max_time`), a sliding top block only while it stays in full contact.
fn multibody_claim(spec: &SceneParams) -> Option<OutcomeKind> {
    let clear = |a: f64, b: f64| (a - b).abs() > 0.05 * a.abs().max(b.abs());
    let law = crate::multibody::law(spec)?;
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
fn multibody_cases(quick: bool) -> Vec<Case> {
    let mut out = Vec::new();
    let mut add = |group: &'static str, name: String, spec: SceneParams, claim: Claim| {
        let outcome = multibody_claim(&spec);
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_quick_grid_is_a_subset_with_unique_names() {
        let full = cases(false);
        let quick = cases(true);
        assert!(quick.len() < full.len());
        for c in &quick {
            assert!(full.iter().any(|f| f.name == c.name), "{}", c.name);
        }
        let mut names: Vec<&str> = full.iter().map(|c| c.name.as_str()).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), full.len());
    }

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
