//! [`StackView`]: the stack in three dimensions ([`Stack3d`]) seen as a [`SceneView`].

use super::Stack3d;
use super::view::{add_state, mode_of, tangent_of};
use crate::planar::{Checksum, ContactMode};
use crate::real::Real;
use crate::scene::{
    BodyView, ContactView, Force, MAX_MEASURES, Outcome, Pose, RunStats, SceneView, StepStats, SupportView,
    Thing, Velocity,
};
use crate::spatial::{SlotContacts, SpatialContactReport, norm};

/// The stack in three dimensions, `B` blocks in `K` contact slots and an LCP of `N` rows in `W`
/// words, seen as a [`SceneView`]: it owns the scene and keeps each slot's contact now (its pair
/// and its point, normal and gap: [`crate::spatial::BlockStack::contacts`]), the last step's
/// impulses and pivots, and the checksum of the steps taken through it (each block's position,
/// orientation `[w, x, y, z]`, velocity and angular velocity, block 0 first).
///
/// Its bodies are the blocks, block 0 the bottom; its contacts the slots the pairs' contacts fill
/// now (block `i` on block `i - 1`, block 0 on the table: [`Thing::Table`]), each with the
/// impulses its slot carried over the last step; its one support the table, whose top is `z = 0`
/// over `x <= 0`.
#[derive(Debug, Clone)]
pub struct StackView<T: Real, const B: usize, const K: usize, const N: usize, const W: usize> {
    scene: Stack3d<T, B, K, N, W>,
    seen: SlotContacts<T, K>,
    last: Option<[SpatialContactReport<T>; K]>,
    solve: Option<StepStats<T>>,
    checksum: Checksum,
}

impl<T: Real, const B: usize, const K: usize, const N: usize, const W: usize> StackView<T, B, K, N, W> {
    /// Sees `scene` from where it is (its contacts now, no impulses yet, an empty checksum).
    pub fn new(scene: Stack3d<T, B, K, N, W>) -> Self {
        let seen = scene.stepper().contacts().unwrap_or([None; K]);
        Self { scene, seen, last: None, solve: None, checksum: Checksum::new() }
    }

    /// The scene.
    pub const fn scene(&self) -> &Stack3d<T, B, K, N, W> {
        &self.scene
    }
}

impl<T: Real, const B: usize, const K: usize, const N: usize, const W: usize> SceneView<T>
    for StackView<T, B, K, N, W>
{
    fn step(&mut self) -> bool {
        let Some(report) = self.scene.step() else {
            return false;
        };
        for state in &report.states {
            add_state(&mut self.checksum, state);
        }
        self.seen = self.scene.stepper().contacts().unwrap_or([None; K]);
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
        self.scene.stepper().time()
    }

    fn body_count(&self) -> usize {
        B
    }

    fn body(&self, i: usize) -> Option<BodyView<T>> {
        let stepper = self.scene.stepper();
        let (body, state) = (stepper.body(), stepper.states().get(i)?);
        let zero = [T::zero(); 3];
        Some(BodyView {
            shape: self.scene.shape(),
            mass: body.mass,
            inertia: body.inertia[2],
            pose: Pose::Spatial { position: state.position, orientation: state.orientation },
            velocity: Velocity::Spatial { linear: state.velocity, angular: state.angular_velocity },
            force: Force::Spatial { force: zero, torque: zero },
        })
    }

    /// The slots filled now: the pairs' contacts fill them in turn from slot 0.
    fn contact_count(&self) -> usize {
        self.seen.iter().take_while(|s| s.is_some()).count()
    }

    fn contact(&self, i: usize) -> Option<ContactView<T>> {
        let (upper, c) = (*self.seen.get(i)?)?;
        let stepper = self.scene.stepper();
        let state = stepper.states().get(upper)?;
        let (normal_impulse, friction, slip) = self
            .last
            .and_then(|l| l.get(i).copied())
            .map_or((T::zero(), [T::zero(); 3], [T::zero(); 3]), |r| {
                (r.normal_impulse, r.friction_impulse, r.slip)
            });
        let beneath =
            upper.checked_sub(1).map_or(Thing::Table, |b| Thing::Body(u8::try_from(b).unwrap_or(u8::MAX)));
        Some(ContactView {
            between: [Thing::Body(u8::try_from(upper).ok()?), beneath],
            active: true,
            point: c.point,
            lever: core::array::from_fn(|k| c.point[k] - state.position[k]),
            normal: c.normal,
            tangent: tangent_of(&friction, &slip, &c.normal),
            gap: c.gap,
            mode: stepper.modes().get(i).map_or(ContactMode::Separated, |m| mode_of(*m)),
            normal_impulse,
            friction_impulse: norm(&friction),
            along: T::zero(),
        })
    }

    fn support_count(&self) -> usize {
        1
    }

    fn support(&self, i: usize) -> Option<SupportView<T>> {
        (i == 0).then_some(SupportView::Table { lo: None, hi: Some(T::zero()) })
    }

    fn measured(&self) -> [Option<T>; MAX_MEASURES] {
        let mut measured = [None; MAX_MEASURES];
        if let Some(first) = measured.first_mut() {
            *first = Some(self.scene.max_speed());
        }
        measured
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
