//! [`PlanarView`]: a scene of one body ([`Scene`]) seen as a [`SceneView`].

use super::{
    BodyView, ContactView, EventView, RunStats, SceneView, StepFigure, StepStats, SupportView, Thing,
};
use crate::planar::{Checksum, ContactMode, ContactReport, Support};
use crate::real::Real;
use crate::scene::{MAX_MEASURES, Outcome, Scene};

/// A scene of one body on `K` supports, `S`, seen as a [`SceneView`]: it owns the scene (or a
/// `&mut` to it) and keeps the last step's contact reports and solve, and the checksum of the steps
/// taken through it.
#[derive(Debug, Clone)]
pub struct PlanarView<T: Real, const K: usize, S> {
    scene: S,
    last: [ContactReport<T>; K],
    solve: Option<StepStats<T>>,
    checksum: Checksum,
}

impl<T: Real, const K: usize, S: Scene<T, K>> PlanarView<T, K, S> {
    /// Sees `scene` from where it is (no impulses yet, an empty checksum).
    pub fn new(scene: S) -> Self {
        let modes = scene.modes();
        let last = core::array::from_fn(|k| ContactReport {
            mode: modes[k],
            previous_mode: modes[k],
            normal_impulse: T::zero(),
            friction_impulse: T::zero(),
            along: T::zero(),
        });
        Self { scene, last, solve: None, checksum: Checksum::new() }
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

impl<T: Real, const K: usize, S: Scene<T, K>> SceneView<T> for PlanarView<T, K, S> {
    fn step(&mut self) -> bool {
        let Some(report) = self.scene.step() else {
            return false;
        };
        self.checksum.add(&report.state);
        self.last = report.contacts;
        self.solve = Some(StepStats { pivots: report.pivots, residual: Some(report.residual) });
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
        1
    }

    fn body(&self, i: usize) -> Option<BodyView<T>> {
        let zero = T::zero();
        (i == 0).then(|| {
            BodyView::planar(self.scene.shape(), &self.scene.body(), self.scene.state(), [zero; 2], zero)
        })
    }

    fn contact_count(&self) -> usize {
        K
    }

    fn contact(&self, i: usize) -> Option<ContactView<T>> {
        let frame = self.scene.frames().get(i)?;
        let last = self.last.get(i)?;
        let state = self.scene.state();
        Some(ContactView {
            between: [Thing::Body(0), Thing::Support(u8::try_from(i).ok()?)],
            active: frame.active,
            point: super::in_space([state.x + frame.r[0], state.y + frame.r[1]]),
            lever: super::in_space(frame.r),
            normal: super::in_space(frame.normal()),
            tangent: super::in_space(frame.tangent()),
            gap: frame.gap,
            mode: self.scene.modes().get(i).copied().unwrap_or(ContactMode::Separated),
            normal_impulse: last.normal_impulse,
            friction_impulse: last.friction_impulse,
            along: last.along,
        })
    }

    fn support_count(&self) -> usize {
        K
    }

    fn support(&self, i: usize) -> Option<SupportView<T>> {
        Some(match *self.scene.supports().get(i)? {
            Support::Point { position, velocity } => SupportView::Point { position, velocity },
            Support::Line { position, normal, velocity } => SupportView::Line { position, normal, velocity },
        })
    }

    fn event_count(&self) -> usize {
        self.scene.events().len()
    }

    fn event(&self, i: usize) -> Option<EventView<T>> {
        self.scene.events().get(i).map(EventView::from)
    }

    fn measured(&self) -> [Option<T>; MAX_MEASURES] {
        self.scene.measured()
    }

    fn summary(&self) -> RunStats {
        *self.scene.stats()
    }

    fn last_step(&self) -> Option<StepStats<T>> {
        self.solve
    }

    fn lcp_capacity(&self) -> usize {
        crate::scene::LcpLayout::Full.size(K)
    }

    fn figure_count(&self) -> usize {
        0
    }

    fn figure(&self, _: usize) -> Option<StepFigure<T>> {
        None
    }

    fn checksum(&self) -> u32 {
        self.checksum.value()
    }
}
