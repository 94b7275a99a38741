//! [`SpatialView`]: a scene in three dimensions ([`SpatialScene`]) seen as a [`SceneView`].

use super::{CIRCULAR_ROWS, SpatialScene};
use crate::planar::{Checksum, ContactMode, Direction};
use crate::real::Real;
use crate::scene::{
    BodyView, ContactView, EventView, Force, MAX_MEASURES, Outcome, Pose, RunStats, SceneView, StepFigure,
    StepStats, SupportView, Thing, Velocity,
};
use crate::spatial::{Mode, SpatialContactReport, norm};

/// A scene in three dimensions seen as a [`SceneView`]: it owns the scene and keeps the last
/// step's contact report and pivots, and the checksum of the steps taken through it (each step's
/// position, orientation `[w, x, y, z]`, velocity and angular velocity, in that order).
#[derive(Debug, Clone)]
pub struct SpatialView<T: Real, S, const N: usize = CIRCULAR_ROWS, const K: usize = 1> {
    scene: S,
    last: Option<[SpatialContactReport<T>; K]>,
    solve: Option<StepStats<T>>,
    checksum: Checksum,
}

impl<T: Real, const N: usize, const K: usize, S: SpatialScene<T, N, K>> SpatialView<T, S, N, K> {
    /// Sees `scene` from where it is (no impulses yet, an empty checksum).
    pub const fn new(scene: S) -> Self {
        Self { scene, last: None, solve: None, checksum: Checksum::new() }
    }

    /// The scene.
    pub const fn scene(&self) -> &S {
        &self.scene
    }
}

/// The planar record's mode of a contact in three dimensions: sliding is along the view's tangent
/// (the friction's direction), so `Sliding(Plus)`.
const fn mode_of(mode: Mode) -> ContactMode {
    match mode {
        Mode::Separated => ContactMode::Separated,
        Mode::Sticking => ContactMode::Sticking,
        Mode::Sliding => ContactMode::Sliding(Direction::Plus),
    }
}

impl<T: Real, const N: usize, const K: usize, S: SpatialScene<T, N, K>> SceneView<T>
    for SpatialView<T, S, N, K>
{
    fn step(&mut self) -> bool {
        let Some(report) = self.scene.step() else {
            return false;
        };
        let s = report.state;
        let mut values = [T::zero(); 13];
        for (slot, v) in values
            .iter_mut()
            .zip(s.position.into_iter().chain(s.orientation).chain(s.velocity).chain(s.angular_velocity))
        {
            *slot = v;
        }
        self.checksum.add_values(&values);
        self.last = Some(report.contacts);
        self.solve = Some(StepStats { pivots: report.pivots, residual: None });
        true
    }

    fn go_on(&mut self) -> Option<Outcome> {
        self.scene.go_on()
    }

    fn outcome(&self) -> Option<Outcome> {
        self.scene.outcome()
    }

    fn time(&self) -> T {
        self.scene.run().stepper().time()
    }

    fn body_count(&self) -> usize {
        1
    }

    fn body(&self, i: usize) -> Option<BodyView<T>> {
        let stepper = self.scene.run().stepper();
        let (body, state) = (stepper.body(), stepper.state());
        let zero = [T::zero(); 3];
        (i == 0).then(|| BodyView {
            shape: self.scene.shape(),
            mass: body.mass,
            inertia: body.inertia[2],
            pose: Pose::Spatial { position: state.position, orientation: state.orientation },
            velocity: Velocity::Spatial { linear: state.velocity, angular: state.angular_velocity },
            force: Force::Spatial { force: zero, torque: zero },
        })
    }

    fn contact_count(&self) -> usize {
        self.scene.run().stepper().used()
    }

    fn contact(&self, i: usize) -> Option<ContactView<T>> {
        let stepper = self.scene.run().stepper();
        let (lever, gap) = (stepper.lever(i)?, stepper.gap(i)?);
        let (state, plane) = (stepper.state(), stepper.plane());
        let normal = plane.normal;
        let (mode, normal_impulse, friction, slip) = self
            .last
            .and_then(|l| l.get(i).copied())
            .map_or((ContactMode::Separated, T::zero(), [T::zero(); 3], [T::zero(); 3]), |c| {
                (mode_of(c.mode), c.normal_impulse, c.friction_impulse, c.slip)
            });
        let unit = |v: [T; 3]| {
            let n = norm(&v);
            (n > T::zero()).then(|| v.map(|x| x / n))
        };
        let tangent =
            unit(friction).or_else(|| unit(slip)).unwrap_or_else(|| crate::spatial::perpendicular(&normal));
        Some(ContactView {
            between: [Thing::Body(0), Thing::Support(0)],
            active: gap <= stepper.settings().margin,
            point: core::array::from_fn(|k| state.position[k] + lever[k]),
            lever,
            normal,
            tangent,
            gap,
            mode,
            normal_impulse,
            friction_impulse: norm(&friction),
            along: T::zero(),
        })
    }

    fn support_count(&self) -> usize {
        1
    }

    fn support(&self, i: usize) -> Option<SupportView<T>> {
        let plane = self.scene.run().stepper().plane();
        (i == 0).then_some(SupportView::Plane { point: plane.point, normal: plane.normal })
    }

    fn event_count(&self) -> usize {
        0
    }

    fn event(&self, _: usize) -> Option<EventView<T>> {
        None
    }

    fn measured(&self) -> [Option<T>; MAX_MEASURES] {
        self.scene.measured()
    }

    fn summary(&self) -> RunStats {
        *self.scene.run().stats()
    }

    fn last_step(&self) -> Option<StepStats<T>> {
        self.solve
    }

    fn lcp_capacity(&self) -> usize {
        N
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
