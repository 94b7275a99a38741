//! [`MultibodyView`]: a scene of several bodies ([`MultibodyScene`]) seen as a [`SceneView`].

use super::{
    Axis, BodyShape, BodyView, ContactView, FigureName, LoadPart, RunStats, SceneView, StepFigure, StepStats,
    SupportView, Thing,
};
use crate::multibody::scenes::MultibodyScene;
use crate::multibody::{RestsOn, Shape};
use crate::planar::Checksum;
use crate::real::Real;
use crate::scene::{MAX_MEASURES, Outcome};

/// A scene of `B` bodies and `P` resting pairs, `S`, seen as a [`SceneView`]: it owns the scene
/// (or a `&mut` to it) and keeps the last step's interface forces, corner loads and pivots, and the
/// checksum of the steps taken through it. Its figures ([`SceneView::figure`]) are, pair by pair,
/// the pair's interface force `x`, `y`, then its four candidates' normal and friction loads. Its contacts are the pairs' candidates, four per pair in the pair's candidate order
/// ([`crate::multibody::Candidate`]): contact `4 p + c` is candidate `c` of pair `p`.
#[derive(Debug, Clone)]
pub struct MultibodyView<T: Real, const B: usize, const P: usize, S> {
    scene: S,
    forces: [[T; 2]; P],
    loads: [[[T; 2]; 4]; P],
    pivots: Option<u32>,
    checksum: Checksum,
}

impl<T: Real, const B: usize, const P: usize, S: MultibodyScene<T, B, P>> MultibodyView<T, B, P, S> {
    /// Sees `scene` from where it is (no loads yet, an empty checksum).
    pub fn new(scene: S) -> Self {
        Self {
            scene,
            forces: [[T::zero(); 2]; P],
            loads: [[[T::zero(); 2]; 4]; P],
            pivots: None,
            checksum: Checksum::new(),
        }
    }

    /// The scene.
    pub const fn scene(&self) -> &S {
        &self.scene
    }

    /// The scene, to step or read by its own interface (steps taken so are not in
    /// [`SceneView::checksum`] and leave [`SceneView::contact`]'s impulses as they were).
    pub const fn scene_mut(&mut self) -> &mut S {
        &mut self.scene
    }

    /// The scene back.
    pub fn into_scene(self) -> S {
        self.scene
    }
}

/// A pair's figures: its interface force's two components, its four candidates' two loads each.
const FIGURES_PER_PAIR: usize = 2 + 4 * 2;

/// The thing a pair's upper body rests on.
const fn thing_of(support: RestsOn) -> Thing {
    match support {
        RestsOn::Body(b) => Thing::Body(b),
        RestsOn::Table => Thing::Table,
    }
}

impl<T: Real, const B: usize, const P: usize, S: MultibodyScene<T, B, P>> SceneView<T>
    for MultibodyView<T, B, P, S>
{
    fn step(&mut self) -> bool {
        let Some(report) = self.scene.step() else {
            return false;
        };
        report.add_to(&mut self.checksum);
        self.forces = report.interface_forces;
        self.loads = report.corner_loads;
        self.pivots = Some(report.pivots);
        true
    }

    fn go_on(&mut self) -> Option<Outcome> {
        self.scene.go_on()
    }

    fn outcome(&self) -> Option<Outcome> {
        self.scene.outcome()
    }

    fn time(&self) -> T {
        self.scene.time()
    }

    fn body_count(&self) -> usize {
        B
    }

    fn body(&self, i: usize) -> Option<BodyView<T>> {
        let system = self.scene.system();
        let body = system.bodies.get(i)?;
        let shape = match system.shapes().get(i)? {
            Shape::Box => BodyShape::Box { width: body.width, height: body.height },
            Shape::Disc => BodyShape::Disc { radius: body.width * T::of(0.5) },
        };
        Some(BodyView::planar(shape, body, self.scene.states().get(i)?, *system.forces.get(i)?, T::zero()))
    }

    fn contact_count(&self) -> usize {
        4 * P
    }

    fn contact(&self, i: usize) -> Option<ContactView<T>> {
        let (p, c) = (i / 4, i % 4);
        let pair = self.scene.system().pairs.get(p)?;
        let frame = self.scene.frames().get(p)?.get(c)?;
        let [normal, friction] = *self.loads.get(p)?.get(c)?;
        let h = self.scene.system().settings.base.step;
        let (upper, lower) = (Thing::Body(pair.upper), thing_of(pair.lower));
        Some(ContactView {
            between: if c < 2 { [upper, lower] } else { [lower, upper] },
            active: frame.active,
            point: super::in_space(frame.point),
            lever: super::in_space(frame.lever_corner),
            normal: super::in_space(frame.normal),
            tangent: super::in_space(frame.tangent),
            gap: frame.gap,
            mode: *self.scene.modes().get(p)?.get(c)?,
            normal_impulse: normal * h,
            friction_impulse: friction * h,
            along: frame.along,
        })
    }

    fn support_count(&self) -> usize {
        1
    }

    fn support(&self, i: usize) -> Option<SupportView<T>> {
        let table = self.scene.system().table;
        (i == 0).then_some(SupportView::Table { lo: table.lo, hi: table.hi })
    }

    fn measured(&self) -> [Option<T>; MAX_MEASURES] {
        self.scene.measured()
    }

    fn summary(&self) -> RunStats {
        *self.scene.stats()
    }

    fn last_step(&self) -> Option<StepStats<T>> {
        self.pivots.map(|pivots| StepStats { pivots, residual: None })
    }

    fn lcp_capacity(&self) -> usize {
        S::ROWS
    }

    fn figure_count(&self) -> usize {
        FIGURES_PER_PAIR * P
    }

    fn figure(&self, i: usize) -> Option<StepFigure<T>> {
        let (p, k) = (i / FIGURES_PER_PAIR, i % FIGURES_PER_PAIR);
        let pair = u8::try_from(p).ok()?;
        if let Some(&value) = self.forces.get(p)?.get(k) {
            let axis = if k == 0 { Axis::X } else { Axis::Y };
            return Some(StepFigure { name: FigureName::PairForce { pair, axis }, value });
        }
        let (c, part) = ((k - 2) / 2, (k - 2) % 2);
        let value = *self.loads.get(p)?.get(c)?.get(part)?;
        let part = if part == 0 { LoadPart::Normal } else { LoadPart::Friction };
        let name = FigureName::CandidateLoad { pair, candidate: u8::try_from(c).ok()?, part };
        Some(StepFigure { name, value })
    }

    fn checksum(&self) -> u32 {
        self.checksum.value()
    }
}
