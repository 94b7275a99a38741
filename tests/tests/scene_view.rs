//! The engine-neutral view of a scene (`meterstick_core::scene::SceneView`): every catalogue
//! scene driven through `&mut dyn SceneView<T>` runs as the concrete scene does, bit for bit
//! (every body's state, every contact's impulses and mode and the solve's pivots and residual after
//! every step, its figures, the outcome, the measures, the counters, the LCP's capacity, the
//! checksum), and the view's contacts of a known state are right.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use meterstick_core::Real;
use meterstick_core::multibody::scenes::{BlockOnBlock, BlockOnBlockParams, MultibodyScene};
use meterstick_core::planar::{Checksum, ContactMode, Support};
use meterstick_core::scene::{
    BodyShape, Force, LcpLayout, MultibodyView, MultibodyVisitor, Outcome, PlanarView, Pose, Precision,
    Scene, SceneKind, SceneParams, SceneView, SceneVisitor, SupportView, Thing, Velocity, ViewVisitor,
};

/// At most this many steps of a run (each catalogue scene's default ends before).
const MOST_STEPS: usize = 20_000;

/// What a run leaves, every value as its f64 bits: per step every body's state and every contact's
/// mode and impulses; then the outcome, the measures, the steps and the checksum.
#[derive(Debug, PartialEq)]
struct Trace {
    steps: Vec<Vec<u64>>,
    outcome: Option<Outcome>,
    measured: Vec<Option<u64>>,
    step_count: u64,
    checksum: u32,
    /// Each switch event the scene keeps: time, contact, mode.
    events: Vec<(u64, usize, u64)>,
    /// The rows of the largest LCP a step may solve.
    lcp_capacity: usize,
    /// The most contacts one step's LCP held, where the engine counts them.
    most_lcp_contacts: Option<u8>,
}

/// A step's pivots and residual (`u64::MAX`: none reported), as a trace records them.
fn solve_bits<T: Real>(pivots: u32, residual: Option<T>) -> [u64; 2] {
    [u64::from(pivots), residual.map_or(u64::MAX, bits)]
}

fn bits<T: Real>(v: T) -> u64 {
    v.as_f64().to_bits()
}

/// A mode as a number (the trace is numbers).
fn mode_code(mode: ContactMode) -> u64 {
    match mode.name() {
        "separated" => 0,
        "sticking" => 1,
        "sliding+" => 2,
        _ => 3,
    }
}

/// A support's position and velocity (a table: its ends, NaN for none), as bits.
fn support_bits<T: Real>(support: SupportView<T>) -> Vec<u64> {
    match support {
        SupportView::Point { position, velocity } => {
            [position, velocity].concat().into_iter().map(bits).collect()
        }
        SupportView::Line { position, normal, velocity } => {
            [position, normal, velocity].concat().into_iter().map(bits).collect()
        }
        SupportView::Table { lo, hi } => [lo, hi].map(|e| e.map_or(f64::NAN.to_bits(), bits)).to_vec(),
        _ => panic!("a support of the engines today"),
    }
}

/// The trace of `view` driven to its outcome through the view alone.
fn trace_view<T: Real>(view: &mut dyn SceneView<T>) -> Trace {
    assert!(view.last_step().is_none(), "no solve before the first step");
    let mut steps = Vec::new();
    while steps.len() < MOST_STEPS && view.step() {
        let mut row = Vec::new();
        for i in 0..view.body_count() {
            let body = view.body(i).unwrap();
            let Pose::Planar { x, y, theta } = body.pose else { panic!("a planar body") };
            let Velocity::Planar { vx, vy, omega } = body.velocity else { panic!("a planar body") };
            row.extend([x, y, theta, vx, vy, omega].map(bits));
        }
        for i in 0..view.contact_count() {
            let c = view.contact(i).unwrap();
            row.extend([mode_code(c.mode), bits(c.normal_impulse), bits(c.friction_impulse)]);
        }
        for i in 0..view.support_count() {
            row.extend(support_bits(view.support(i).unwrap()));
        }
        let solve = view.last_step().unwrap();
        row.extend(solve_bits(solve.pivots, solve.residual));
        row.extend((0..view.figure_count()).map(|i| bits(view.figure(i).unwrap().value)));
        steps.push(row);
    }
    assert!(view.body(view.body_count()).is_none() && view.contact(view.contact_count()).is_none());
    assert!(view.support(view.support_count()).is_none() && view.event(view.event_count()).is_none());
    Trace {
        steps,
        outcome: view.outcome(),
        measured: view.measured().iter().map(|m| m.map(bits)).collect(),
        step_count: view.summary().steps,
        checksum: view.checksum(),
        events: (0..view.event_count())
            .map(|i| view.event(i).unwrap())
            .map(|e| (bits(e.time), e.contact, mode_code(e.mode)))
            .collect(),
        lcp_capacity: view.lcp_capacity(),
        most_lcp_contacts: view.summary().most_lcp_contacts,
    }
}

/// Traces any scene the registry builds as a view ([`SceneParams::build_view`]).
struct Traced;

impl ViewVisitor for Traced {
    type Output = Trace;

    fn visit<T: Real>(self, view: &mut dyn SceneView<T>) -> Trace {
        trace_view(view)
    }
}

/// Drives a scene of one body by its own interface ([`Scene`]), or through a [`PlanarView`].
struct Planar {
    through_view: bool,
}

impl SceneVisitor for Planar {
    type Output = Trace;

    fn visit<T: Real, const K: usize, const N: usize, S: Scene<T, K>>(self, mut scene: S) -> Trace {
        if self.through_view {
            return trace_view(&mut PlanarView::new(scene));
        }
        let (mut steps, mut checksum) = (Vec::new(), Checksum::new());
        while steps.len() < MOST_STEPS
            && let Some(r) = scene.step()
        {
            checksum.add(&r.state);
            let mut row: Vec<u64> = r.state.to_array().map(bits).to_vec();
            for c in &r.contacts {
                row.extend([mode_code(c.mode), bits(c.normal_impulse), bits(c.friction_impulse)]);
            }
            for support in scene.supports() {
                row.extend(
                    match *support {
                        Support::Point { position, velocity } => [position, velocity].concat(),
                        Support::Line { position, normal, velocity } => [position, normal, velocity].concat(),
                        _ => panic!("a support of the scenes today"),
                    }
                    .into_iter()
                    .map(bits),
                );
            }
            row.extend(solve_bits(r.pivots, Some(r.residual)));
            steps.push(row);
        }
        Trace {
            steps,
            outcome: scene.outcome(),
            measured: scene.measured().iter().map(|m| m.map(bits)).collect(),
            step_count: scene.stats().steps,
            checksum: checksum.value(),
            events: scene
                .events()
                .iter()
                .map(|e| (bits(e.time), usize::from(e.contact), mode_code(e.mode)))
                .collect(),
            lcp_capacity: LcpLayout::Full.size(K),
            most_lcp_contacts: None,
        }
    }
}

/// Drives a scene of several bodies by its own interface ([`MultibodyScene`]), or through a
/// [`MultibodyView`].
struct Bodies {
    through_view: bool,
}

impl MultibodyVisitor for Bodies {
    type Output = Trace;

    fn visit<T: Real, const B: usize, const P: usize, S: MultibodyScene<T, B, P>>(
        self,
        mut scene: S,
    ) -> Trace {
        if self.through_view {
            return trace_view(&mut MultibodyView::new(scene));
        }
        let h = scene.system().settings.base.step;
        let (mut steps, mut checksum, mut most_active) = (Vec::new(), Checksum::new(), 0u8);
        while steps.len() < MOST_STEPS
            && let Some(r) = scene.step()
        {
            r.add_to(&mut checksum);
            most_active = most_active.max(r.active);
            let mut row: Vec<u64> = r.states.iter().flat_map(|s| s.to_array().map(bits)).collect();
            for (modes, loads) in r.modes.iter().zip(&r.corner_loads) {
                for (mode, [n, f]) in modes.iter().zip(loads) {
                    row.extend([mode_code(*mode), bits(*n * h), bits(*f * h)]);
                }
            }
            let table = scene.system().table;
            row.extend([table.lo, table.hi].map(|e| e.map_or(f64::NAN.to_bits(), bits)));
            row.extend(solve_bits::<T>(r.pivots, None));
            for (force, loads) in r.interface_forces.iter().zip(&r.corner_loads) {
                row.extend(force.iter().chain(loads.as_flattened()).map(|&v| bits(v)));
            }
            steps.push(row);
        }
        Trace {
            steps,
            outcome: scene.outcome(),
            measured: scene.measured().iter().map(|m| m.map(bits)).collect(),
            step_count: scene.stats().steps,
            checksum: checksum.value(),
            events: Vec::new(),
            lcp_capacity: S::ROWS,
            most_lcp_contacts: Some(most_active),
        }
    }
}

/// Every catalogue scene, in every precision (and, for a scene of one body, every layout), runs
/// through the view as by its own interface, bit for bit, to its outcome.
#[test]
fn every_catalogue_scene_runs_through_the_view_as_itself() {
    let mut events = 0;
    // A scene in three dimensions against its stepper: tests/tests/spatial_scenes.rs.
    for kind in SceneKind::ALL.into_iter().filter(|k| !k.is_spatial()) {
        let params = SceneParams::defaults(kind);
        for precision in Precision::ALL {
            let traces = |through_view| {
                if kind.is_multibody() {
                    vec![params.build_multibody(precision, Bodies { through_view }).unwrap()]
                } else {
                    LcpLayout::ALL
                        .iter()
                        .map(|&layout| {
                            params.build::<64, _>(precision, layout, Planar { through_view }).unwrap()
                        })
                        .collect()
                }
            };
            let (own, viewed) = (traces(false), traces(true));
            // The registry's one entry for either engine, `build_view` (a scene of several bodies
            // has one layout).
            let built: Vec<Trace> = LcpLayout::ALL[..own.len()]
                .iter()
                .map(|&layout| params.build_view::<64, _>(precision, layout, Traced).unwrap())
                .collect();
            assert_eq!(own.len(), if kind.is_multibody() { 1 } else { 2 }, "{kind}");
            for ((own, viewed), built) in own.iter().zip(&viewed).zip(&built) {
                assert!(own.outcome.is_some() && !own.steps.is_empty(), "{kind} {precision:?} ran");
                assert_eq!(own.step_count, own.steps.len() as u64, "{kind} {precision:?}");
                assert_eq!(viewed, own, "{kind} {precision:?}");
                assert_eq!(built, own, "{kind} {precision:?}, built as a view");
                events += own.events.len();
            }
        }
    }
    assert!(events > 0, "the scenes of one body switch modes");
}

/// Block-on-block without the pull stays at rest: through the view, the bottom block's two lower
/// corners stick on the table and the top block's two on the bottom one, each pair's normal
/// impulses carrying the weight above it over the step; the table's and the bottom block's upper
/// corners (none, and outside the top block's face) are separated.
#[test]
fn block_on_block_at_rest_shows_its_four_corners_carrying_the_weights() {
    let mut p = SceneParams::defaults(SceneKind::BlockOnBlock);
    assert!(p.set("force", 0.0));
    let SceneParams::BlockOnBlock(bb) = p else { panic!("block-on-block") };
    let (g, h) = (bb.gravity, bb.step);
    let mut view = MultibodyView::new(BlockOnBlock::<f64>::new(bb).unwrap());
    let view: &mut dyn SceneView<f64> = &mut view;
    assert_eq!((view.body_count(), view.contact_count()), (2, 8));
    assert_eq!(
        view.body(0).unwrap().shape,
        BodyShape::Box { width: bb.bottom_width, height: bb.bottom_height }
    );
    assert_eq!(view.body(1).unwrap().shape, BodyShape::Box { width: bb.top_width, height: bb.top_height });
    for _ in 0..10 {
        assert!(view.step());
    }
    // Pair 0 (bottom block on the table), then pair 1 (top block on the bottom one).
    let expected = [
        ([Thing::Body(0), Thing::Table], bb.bottom_width, 0.0, bb.top_mass + bb.bottom_mass),
        ([Thing::Body(1), Thing::Body(0)], bb.top_width, bb.bottom_height, bb.top_mass),
    ];
    for (pair, (between, width, y, mass)) in expected.into_iter().enumerate() {
        let mut sum = 0.0;
        for (corner, side) in [-0.5, 0.5].into_iter().enumerate() {
            let c = view.contact(4 * pair + corner).unwrap();
            assert_eq!(c.between, between, "pair {pair} corner {corner}");
            assert!(c.active, "pair {pair} corner {corner}");
            assert_eq!(c.mode, ContactMode::Sticking, "pair {pair} corner {corner}");
            assert!(
                (c.point[0] - side * width).abs() < 1e-9 && (c.point[1] - y).abs() < 1e-9,
                "{:?}",
                c.point
            );
            assert!(c.normal[0].abs() < 1e-12 && (c.normal[1] - 1.0).abs() < 1e-12, "{:?}", c.normal);
            assert!(c.normal_impulse > 0.0 && c.friction_impulse.abs() < 1e-12, "{c:?}");
            sum += c.normal_impulse;
        }
        let weight = mass * g * h;
        assert!((sum - weight).abs() <= 1e-9 * weight, "pair {pair}: {sum} against m g h = {weight}");
        for candidate in 2..4 {
            let c = view.contact(4 * pair + candidate).unwrap();
            assert_eq!(c.between, [between[1], between[0]], "the lower thing's corner first");
            assert_eq!((c.mode, c.normal_impulse, c.friction_impulse), (ContactMode::Separated, 0.0, 0.0));
        }
    }
    assert_eq!(view.summary().steps, 10);
    assert!(view.outcome().is_none());
    let zero = Force::Planar { fx: 0.0, fy: 0.0, torque: 0.0 };
    assert_eq!((view.body(0).unwrap().force, view.body(1).unwrap().force), (zero, zero));
}

/// Block-on-block's pull is the bottom block's applied force, the top block has none.
#[test]
fn block_on_block_shows_its_pull_on_the_bottom_block() {
    let (bb, view) = block_on_block();
    let view: &dyn SceneView<f64> = &view;
    assert!(bb.force > 0.0);
    assert_eq!(view.body(0).unwrap().force, Force::Planar { fx: bb.force, fy: 0.0, torque: 0.0 });
    assert_eq!(view.body(1).unwrap().force, Force::Planar { fx: 0.0, fy: 0.0, torque: 0.0 });
}

/// Block-on-block's defaults, and its f64 scene at its start seen through a [`MultibodyView`].
fn block_on_block() -> (BlockOnBlockParams<f64>, MultibodyView<f64, 2, 2, BlockOnBlock<f64>>) {
    let SceneParams::BlockOnBlock(bb) = SceneParams::defaults(SceneKind::BlockOnBlock) else {
        panic!("block-on-block")
    };
    (bb, MultibodyView::new(BlockOnBlock::<f64>::new(bb).unwrap()))
}

/// Block-on-block's figures, named as the columns of `host-sim run`'s CSV, zero before the first
/// step: each pair's interface force, then its four candidates' normal and friction loads.
#[test]
fn block_on_block_names_its_figures_pair_by_pair() {
    let (_, view) = block_on_block();
    let view: &dyn SceneView<f64> = &view;
    let names: Vec<String> =
        (0..view.figure_count()).map(|i| view.figure(i).unwrap().name.to_string()).collect();
    let mut want = Vec::new();
    for p in 0..2 {
        want.extend([format!("pair{p}_fx"), format!("pair{p}_fy")]);
        for c in 0..4 {
            want.extend([format!("pair{p}_c{c}_normal"), format!("pair{p}_c{c}_friction")]);
        }
    }
    assert_eq!(names, want);
    assert!((0..view.figure_count()).all(|i| view.figure(i).unwrap().value == 0.0));
    assert!(view.figure(view.figure_count()).is_none());
}

/// The meter stick at its start, through the view: one body, the rod, on two fingers, each a
/// support under it with the upward normal; after a step the normal impulses carry its weight.
#[test]
fn the_meter_stick_shows_its_rod_on_two_fingers() {
    let p = SceneParams::defaults(SceneKind::MeterStick);
    let SceneParams::MeterStick(ms) = p else { panic!("meter stick") };
    let mut view = PlanarView::new(meterstick_core::scene::MeterStick8::<f64>::new(ms).unwrap());
    let view: &mut dyn SceneView<f64> = &mut view;
    assert_eq!((view.body_count(), view.contact_count()), (1, 2));
    assert_eq!(
        view.body(0).unwrap().shape,
        BodyShape::Box { width: ms.rod_length, height: ms.rod_thickness }
    );
    assert!(view.step());
    let mut sum = 0.0;
    for k in 0..2 {
        let c = view.contact(k).unwrap();
        assert_eq!(c.between, [Thing::Body(0), Thing::Support(k as u8)]);
        assert!(c.active && c.normal[0].abs() < 1e-12 && (c.normal[1] - 1.0).abs() < 1e-12, "{c:?}");
        assert_ne!(c.mode, ContactMode::Separated);
        sum += c.normal_impulse;
    }
    let weight = ms.rod_mass * ms.gravity * ms.step;
    assert!((sum - weight).abs() <= 1e-6 * weight, "{sum} against m g h = {weight}");
    assert_eq!(view.support_count(), 2);
    let h = ms.step;
    assert_eq!(
        view.support(1),
        Some(SupportView::Point {
            position: [ms.finger2_x, ms.finger2_y],
            velocity: [ms.finger2_velocity, 0.0]
        })
    );
    let Some(SupportView::Point { position, velocity }) = view.support(0) else { panic!("finger 1 a point") };
    #[allow(clippy::float_cmp)] // copied from the parameters, not computed: exactly equal
    {
        assert_eq!(velocity, [ms.finger1_velocity, 0.0]);
    }
    assert!(
        (position[0] - (ms.finger1_x + ms.finger1_velocity * h)).abs() < 1e-12,
        "moved one step: {position:?}"
    );
}

/// The stack's table ends at its edge, `x = 0` (in the plane and in three dimensions);
/// block-on-block's floor has no ends.
#[test]
fn the_table_is_the_multibody_scenes_support() {
    for (kind, hi) in
        [(SceneKind::Stack, Some(0.0)), (SceneKind::Stack3d, Some(0.0)), (SceneKind::BlockOnBlock, None)]
    {
        let table =
            SceneParams::defaults(kind).build_view::<0, _>(Precision::F64, LcpLayout::Full, Table).unwrap();
        assert_eq!(table, (1, Some(SupportView::Table { lo: None, hi })), "{kind}");
    }
}

/// A scene's supports: how many, and the first as f64.
struct Table;

impl ViewVisitor for Table {
    type Output = (usize, Option<SupportView<f64>>);

    fn visit<T: Real>(self, view: &mut dyn SceneView<T>) -> Self::Output {
        let first = view.support(0).map(|s| match s {
            SupportView::Table { lo, hi } => {
                SupportView::Table { lo: lo.map(Real::as_f64), hi: hi.map(Real::as_f64) }
            }
            _ => panic!("a table"),
        });
        (view.support_count(), first)
    }
}

/// Every catalogue scene's bodies, through the view, have the masses and inertias of the
/// catalogue's parameters (`docs/scenes.md`): a rod's `m L^2 / 12`, a box's `m (w^2 + h^2) / 12`,
/// a disc's `m r^2 / 2`, the cylinder's `k m r^2`, a puck's `m r^2 / 2` and a ball's `2 m R^2 / 5`
/// about their `z`; in f64 exactly (the same expression as the
/// scene's), in f32 to the scalar's round-off.
#[test]
fn every_body_has_its_catalogue_mass_and_inertia() {
    for kind in SceneKind::ALL {
        let params = SceneParams::defaults(kind);
        let want = mass_and_inertia(&params);
        assert!(!want.is_empty(), "{kind}");
        for precision in Precision::ALL {
            let got = params.build_view::<0, _>(precision, LcpLayout::Full, Masses).unwrap();
            assert_eq!(got.len(), want.len(), "{kind} {precision:?}");
            for (b, (&(m, j), &(gm, gj, eps))) in want.iter().zip(&got).enumerate() {
                if precision == Precision::F64 {
                    assert_eq!((gm.to_bits(), gj.to_bits()), (m.to_bits(), j.to_bits()), "{kind} body {b}");
                } else {
                    assert!((gm - m).abs() <= 4.0 * eps * m, "{kind} body {b}: mass {gm} against {m}");
                    assert!((gj - j).abs() <= 8.0 * eps * j, "{kind} body {b}: inertia {gj} against {j}");
                }
            }
        }
    }
}

/// Each body's `(mass, inertia)` from a scene's parameters, body 0 the lowest.
fn mass_and_inertia(params: &SceneParams) -> Vec<(f64, f64)> {
    let rod = |m: f64, l: f64| (m, m * l * l / 12.0);
    let block = |m: f64, w: f64, h: f64| (m, m * (w * w + h * h) / 12.0);
    match params {
        SceneParams::MeterStick(p) => vec![rod(p.rod_mass, p.rod_length)],
        SceneParams::ThreeFingers(p) => vec![rod(p.rod_mass, p.rod_length)],
        SceneParams::Incline(p) => vec![block(p.mass, p.width, p.height)],
        SceneParams::Ladder(p) => vec![rod(p.mass, p.length)],
        SceneParams::Painleve(p) => vec![rod(p.mass, p.length)],
        SceneParams::Cylinder(p) => vec![(p.mass, p.inertia_factor * p.mass * p.radius * p.radius)],
        SceneParams::BlockOnBlock(p) => vec![
            block(p.bottom_mass, p.bottom_width, p.bottom_height),
            block(p.top_mass, p.top_width, p.top_height),
        ],
        SceneParams::Tablecloth(p) => vec![
            block(p.board_mass, p.board_length, p.board_thickness),
            block(p.block_mass, p.block_width, p.block_height),
        ],
        SceneParams::Stack(s) => {
            vec![block(s.params.mass, s.params.length, s.params.height); s.block_count().unwrap()]
        }
        SceneParams::DiscOnBoard(p) => vec![
            block(p.board_mass, p.board_length, p.board_height),
            (p.disc_mass, p.disc_mass * p.disc_radius * p.disc_radius / 2.0),
        ],
        // In three dimensions: the moment about the body's own `z` (a puck's axis).
        SceneParams::Puck(p) => vec![(p.mass, p.mass * p.radius * p.radius * 0.5)],
        SceneParams::Billiard(p) => vec![(p.mass, 0.4 * p.mass * p.radius * p.radius)],
        // A thin ring (`shape` 0): `m R^2`; a thin uniform disc: `m R^2 / 2`.
        SceneParams::Curling(p) => {
            vec![(p.mass, if p.shape == 0.0 { 1.0 } else { 0.5 } * p.mass * p.radius * p.radius)]
        }
        // A box `L x w x t` about its own `z` (vertical): `m (L^2 + w^2) / 12`.
        SceneParams::MeterStick3d(p) => {
            vec![(p.rod_mass, p.rod_mass * (p.rod_length.powi(2) + p.rod_width.powi(2)) / 12.0)]
        }
        // Each block `L x W x hb` about its own `z` (vertical): `m (L^2 + W^2) / 12`.
        SceneParams::Stack3d(s) => {
            let p = s.params;
            vec![(p.mass, p.mass * (p.length.powi(2) + p.width.powi(2)) / 12.0); s.block_count().unwrap()]
        }
    }
}

/// Each body's mass and inertia through the view, as f64, with the scalar's epsilon.
struct Masses;

impl ViewVisitor for Masses {
    type Output = Vec<(f64, f64, f64)>;

    fn visit<T: Real>(self, view: &mut dyn SceneView<T>) -> Self::Output {
        (0..view.body_count())
            .map(|i| {
                let b = view.body(i).unwrap();
                (b.mass.as_f64(), b.inertia.as_f64(), T::EPS.as_f64())
            })
            .collect()
    }
}
