//! [`BodyView`]: one body of a scene as a driver draws and records it.

/// A body's outline, in its own frame, centred on its centre of mass.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum BodyShape<T> {
    /// A box `width` along the body's `x` by `height` along its `y` (m); a rod is a thin box.
    Box {
        /// Extent along the body's `x` (m).
        width: T,
        /// Extent along the body's `y` (m).
        height: T,
    },
    /// A disc of `radius` (m).
    Disc {
        /// The radius (m).
        radius: T,
    },
    /// A ball of `radius` (m), in three dimensions.
    #[cfg(feature = "spatial")]
    Ball {
        /// The radius (m).
        radius: T,
    },
    /// A flat cylinder (a puck, a curling stone) of `radius` about the body's `z` axis and
    /// `thickness` along it (m), in three dimensions.
    #[cfg(feature = "spatial")]
    Puck {
        /// The radius (m).
        radius: T,
        /// The thickness (m).
        thickness: T,
    },
    /// A box `length` along the body's `x`, `width` along its `y` and `height` along its `z` (m),
    /// in three dimensions (a block of the stack).
    #[cfg(feature = "spatial")]
    Cuboid {
        /// Extent along the body's `x` (m).
        length: T,
        /// Extent along the body's `y` (m).
        width: T,
        /// Extent along the body's `z` (m).
        height: T,
    },
}

/// Where a body is: its centre of mass and its orientation, in the dimension the body moves in.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Pose<T> {
    /// In the plane: `(x, y)` of the centre of mass (m) and the angle `theta` (rad,
    /// counter-clockwise).
    Planar {
        /// `x` of the centre of mass (m).
        x: T,
        /// `y` of the centre of mass (m).
        y: T,
        /// Angle (rad, counter-clockwise).
        theta: T,
    },
    /// In three dimensions: the centre of mass (m, world, `z` up) and the body's orientation, the
    /// unit quaternion `[w, x, y, z]` that turns its frame into the world's.
    #[cfg(feature = "spatial")]
    Spatial {
        /// The centre of mass (m).
        position: [T; 3],
        /// The orientation `[w, x, y, z]`.
        orientation: [T; 4],
    },
}

/// How a body moves: its centre of mass's velocity and its angular velocity, in the dimension the
/// body moves in.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Velocity<T> {
    /// In the plane: `(vx, vy)` (m/s) and `omega` (rad/s, counter-clockwise).
    Planar {
        /// `dx/dt` (m/s).
        vx: T,
        /// `dy/dt` (m/s).
        vy: T,
        /// `d theta / dt` (rad/s).
        omega: T,
    },
    /// In three dimensions: the centre of mass's velocity (m/s) and the angular velocity (rad/s),
    /// world axes.
    #[cfg(feature = "spatial")]
    Spatial {
        /// The centre of mass's velocity (m/s).
        linear: [T; 3],
        /// The angular velocity (rad/s).
        angular: [T; 3],
    },
}

/// The force applied to a body besides its weight and its contacts, in the dimension the body
/// moves in.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Force<T> {
    /// In the plane: `(fx, fy)` at the centre of mass (N, world) and a torque about it (N m,
    /// counter-clockwise).
    Planar {
        /// Along world `x` (N).
        fx: T,
        /// Along world `y` (N).
        fy: T,
        /// About the centre of mass (N m, counter-clockwise).
        torque: T,
    },
    /// In three dimensions: a force at the centre of mass (N) and a torque about it (N m), world
    /// axes.
    #[cfg(feature = "spatial")]
    Spatial {
        /// The force (N).
        force: [T; 3],
        /// The torque (N m).
        torque: [T; 3],
    },
}

/// One body now: its shape, mass and inertia, pose and velocity, and the force applied to it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyView<T> {
    /// Its outline.
    pub shape: BodyShape<T>,
    /// Its mass `m` (kg), as its engine moves it.
    pub mass: T,
    /// Its moment of inertia about its centre of mass `J` (kg m^2; a planar body's about the axis
    /// normal to the plane, a body in three dimensions' about its own `z`), as its engine moves
    /// it.
    pub inertia: T,
    /// Where it is.
    pub pose: Pose<T>,
    /// How it moves.
    pub velocity: Velocity<T>,
    /// The force applied to it besides its weight and its contacts (a pull).
    pub force: Force<T>,
}

impl<T: Copy> BodyView<T> {
    /// A planar `body` of `shape` in `state`, pulled by `force` `[fx, fy]` at its centre of mass.
    #[must_use]
    pub const fn planar(
        shape: BodyShape<T>,
        body: &crate::planar::Body<T>,
        state: &crate::planar::BodyState<T>,
        [fx, fy]: [T; 2],
        torque: T,
    ) -> Self {
        Self {
            shape,
            mass: body.mass,
            inertia: body.inertia,
            pose: Pose::Planar { x: state.x, y: state.y, theta: state.theta },
            velocity: Velocity::Planar { vx: state.vx, vy: state.vy, omega: state.omega },
            force: Force::Planar { fx, fy, torque },
        }
    }
}
