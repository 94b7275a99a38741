//! [`SpatialView`]: a scene in three dimensions ([`SpatialSeen`]) seen as a [`SceneView`].

use super::{Billiard, CIRCULAR_ROWS, Curling, MeterStick3d, Puck, ROD_POINTS, ROD_ROWS, SpatialScene};
use crate::planar::{Checksum, ContactMode, Direction};
use crate::real::Real;
use crate::scene::BodyShape;
use crate::scene::{
    BodyView, ContactView, Force, MAX_MEASURES, Outcome, Pose, RunStats, SceneView, StepStats, SupportView,
    Thing, Velocity,
};
use crate::spatial::{Body, Mode, SpatialContactReport, SpatialStepReport, State, Vector, norm};

/// One contact's geometry now, as the view shows it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeenContact<T> {
    /// The contact point's offset from the centre of mass, world axes, m.
    pub lever: Vector<T>,
    /// Its gap along `normal`, m (negative when sunk in).
    pub gap: T,
    /// The unit normal toward the body.
    pub normal: Vector<T>,
    /// Whether it enters the step's LCP.
    pub active: bool,
    /// The support it touches ([`SpatialSeen::support`]).
    pub support: u8,
}

/// What [`SpatialView`] reads of a scene in three dimensions: the scene's step and outcome
/// ([`SpatialScene`]'s, for the scenes on a plane) and its body, contacts and supports now.
pub trait SpatialSeen<T: Real, const N: usize, const K: usize> {
    /// Advances one step and judges it; `None` once the run has an outcome.
    fn step(&mut self) -> Option<SpatialStepReport<T, K>>;
    /// Takes the outcome so that the run goes on; `None` before it.
    fn go_on(&mut self) -> Option<Outcome>;
    /// The outcome, once the run has ended.
    fn outcome(&self) -> Option<Outcome>;
    /// The body's outline.
    fn shape(&self) -> BodyShape<T>;
    /// What the scene measures, in its catalogue entry's order.
    fn measured(&self) -> [Option<T>; MAX_MEASURES];
    /// Simulated time, s.
    fn time(&self) -> T;
    /// The body and its state now.
    fn body(&self) -> (&Body<T>, &State<T>);
    /// The run's counters.
    fn stats(&self) -> &RunStats;
    /// The contacts the body has.
    fn contact_count(&self) -> usize;
    /// Contact `i` now; `None` past [`Self::contact_count`].
    fn contact(&self, i: usize) -> Option<SeenContact<T>>;
    /// The supports.
    fn support_count(&self) -> usize;
    /// Support `i` now.
    fn support(&self, i: usize) -> Option<SupportView<T>>;
}

/// A scene on a plane ([`SpatialScene`], its [`super::Run`]) as [`SpatialSeen`] reads it.
macro_rules! seen_on_a_plane {
    ($scene:ty, $n:tt, $k:tt $(, $rows:ident)?) => {
        impl<T: Real $(, const $rows: usize)?> SpatialSeen<T, $n, $k> for $scene {
            fn step(&mut self) -> Option<SpatialStepReport<T, $k>> {
                SpatialScene::step(self)
            }
            fn go_on(&mut self) -> Option<Outcome> {
                SpatialScene::go_on(self)
            }
            fn outcome(&self) -> Option<Outcome> {
                SpatialScene::outcome(self)
            }
            fn shape(&self) -> BodyShape<T> {
                SpatialScene::shape(self)
            }
            fn measured(&self) -> [Option<T>; MAX_MEASURES] {
                SpatialScene::measured(self)
            }
            fn time(&self) -> T {
                self.run().stepper().time()
            }
            fn body(&self) -> (&Body<T>, &State<T>) {
                let stepper = self.run().stepper();
                (stepper.body(), stepper.state())
            }
            fn stats(&self) -> &RunStats {
                self.run().stats()
            }
            fn contact_count(&self) -> usize {
                self.run().stepper().used()
            }
            fn contact(&self, i: usize) -> Option<SeenContact<T>> {
                let stepper = self.run().stepper();
                let (lever, gap) = (stepper.lever(i)?, stepper.gap(i)?);
                let normal = stepper.plane().normal;
                Some(SeenContact { lever, gap, normal, active: gap <= stepper.settings().margin, support: 0 })
            }
            fn support_count(&self) -> usize {
                1
            }
            fn support(&self, i: usize) -> Option<SupportView<T>> {
                let plane = self.run().stepper().plane();
                (i == 0).then_some(SupportView::Plane { point: plane.point, normal: plane.normal })
            }
        }
    };
}

seen_on_a_plane!(Puck<T, N>, N, 1, N);
seen_on_a_plane!(Billiard<T, N>, N, 1, N);
seen_on_a_plane!(Curling<T>, { super::curling::CURLING_ROWS }, { super::MAX_POINTS });

impl<T: Real> SpatialSeen<T, ROD_ROWS, ROD_POINTS> for MeterStick3d<T> {
    fn step(&mut self) -> Option<SpatialStepReport<T, ROD_POINTS>> {
        MeterStick3d::step(self)
    }
    fn go_on(&mut self) -> Option<Outcome> {
        MeterStick3d::go_on(self)
    }
    fn outcome(&self) -> Option<Outcome> {
        MeterStick3d::outcome(self)
    }
    fn shape(&self) -> BodyShape<T> {
        let p = self.params();
        BodyShape::Box { width: p.rod_length, height: p.rod_thickness }
    }
    fn measured(&self) -> [Option<T>; MAX_MEASURES] {
        let m = self.meeting();
        [m.map(|m| m.time), m.map(|m| m.com_offset), None]
    }
    fn time(&self) -> T {
        self.stepper().time()
    }
    fn body(&self) -> (&Body<T>, &State<T>) {
        (self.stepper().body(), self.stepper().state())
    }
    fn stats(&self) -> &RunStats {
        MeterStick3d::stats(self)
    }
    fn contact_count(&self) -> usize {
        ROD_POINTS
    }
    fn contact(&self, i: usize) -> Option<SeenContact<T>> {
        MeterStick3d::contact(self, i)
    }
    fn support_count(&self) -> usize {
        2
    }
    fn support(&self, i: usize) -> Option<SupportView<T>> {
        self.finger(i).map(|f| SupportView::Finger { tip: f.tip, across: f.across, velocity: f.velocity })
    }
}

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

impl<T: Real, const N: usize, const K: usize, S: SpatialSeen<T, N, K>> SpatialView<T, S, N, K> {
    /// Sees `scene` from where it is (no impulses yet, an empty checksum).
    pub const fn new(scene: S) -> Self {
        Self { scene, last: None, solve: None, checksum: Checksum::new() }
    }

    /// The scene.
    pub const fn scene(&self) -> &S {
        &self.scene
    }
}

/// Adds a body's state to `checksum`: its position, orientation `[w, x, y, z]`, velocity and
/// angular velocity, in that order.
pub(super) fn add_state<T: Real>(checksum: &mut Checksum, s: &State<T>) {
    let ([x, y, z], [qw, qx, qy, qz]) = (s.position, s.orientation);
    let ([vx, vy, vz], [wx, wy, wz]) = (s.velocity, s.angular_velocity);
    checksum.add_values(&[x, y, z, qw, qx, qy, qz, vx, vy, vz, wx, wy, wz]);
}

/// A contact's tangent as the view gives it ([`ContactView::tangent`]): the friction impulse's
/// direction, where there is none the slip's, where neither a fixed direction across `normal`.
pub(super) fn tangent_of<T: Real>(friction: &Vector<T>, slip: &Vector<T>, normal: &Vector<T>) -> Vector<T> {
    let unit = |v: &Vector<T>| {
        let n = norm(v);
        (n > T::zero()).then(|| v.map(|x| x / n))
    };
    unit(friction).or_else(|| unit(slip)).unwrap_or_else(|| crate::spatial::perpendicular(normal))
}

/// The planar record's mode of a contact in three dimensions: sliding is along the view's tangent
/// (the friction's direction), so `Sliding(Plus)`.
pub(super) const fn mode_of(mode: Mode) -> ContactMode {
    match mode {
        Mode::Separated => ContactMode::Separated,
        Mode::Sticking => ContactMode::Sticking,
        Mode::Sliding => ContactMode::Sliding(Direction::Plus),
    }
}

impl<T: Real, const N: usize, const K: usize, S: SpatialSeen<T, N, K>> SceneView<T>
    for SpatialView<T, S, N, K>
{
    fn step(&mut self) -> bool {
        let Some(report) = self.scene.step() else {
            return false;
        };
        add_state(&mut self.checksum, &report.state);
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
        self.scene.time()
    }

    fn body_count(&self) -> usize {
        1
    }

    fn body(&self, i: usize) -> Option<BodyView<T>> {
        let (body, state) = self.scene.body();
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
        self.scene.contact_count()
    }

    fn contact(&self, i: usize) -> Option<ContactView<T>> {
        let SeenContact { lever, gap, normal, active, support } = self.scene.contact(i)?;
        let state = self.scene.body().1;
        let (mode, normal_impulse, friction, slip) = self
            .last
            .and_then(|l| l.get(i).copied())
            .map_or((ContactMode::Separated, T::zero(), [T::zero(); 3], [T::zero(); 3]), |c| {
                (mode_of(c.mode), c.normal_impulse, c.friction_impulse, c.slip)
            });
        let tangent = tangent_of(&friction, &slip, &normal);
        Some(ContactView {
            between: [Thing::Body(0), Thing::Support(support)],
            active,
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
        self.scene.support_count()
    }

    fn support(&self, i: usize) -> Option<SupportView<T>> {
        self.scene.support(i)
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
        N
    }

    fn checksum(&self) -> u32 {
        self.checksum.value()
    }
}
