//! The meter stick's fingers in three dimensions (docs/scenes.md, "meter-stick-3d"): the planar
//! scene's finger motion in `x` ("meter-stick", "Finger motion"), at the path's `x` speeds `v cos
//! psi`, each tip's `y` following at `tan psi` of its `x`'s travel.

use super::algebra::V3;

/// The fingers' motion (docs/scenes.md, "meter-stick", "Finger motion", in `x`; `y` follows at
/// `tan psi` of `x`'s travel).
pub(crate) struct Fingers {
    start: [f64; 2],
    height: [f64; 2],
    /// `x` speeds.
    velocity: [f64; 2],
    stop: Option<[f64; 2]>,
    tan: f64,
    h: f64,
}

/// What the fingers' motion is made from (the scene's parameters of that name, SI units):
/// the fingers' start `x`, heights, speeds along the path, width, the path's heading (rad), the
/// step.
pub(crate) struct FingerParams {
    pub x: [f64; 2],
    pub height: [f64; 2],
    pub speed: [f64; 2],
    pub width: f64,
    pub heading: f64,
    pub h: f64,
}

impl Fingers {
    pub(crate) fn new(p: &FingerParams) -> Self {
        let c = p.heading.cos();
        let [x1, x2] = p.x;
        let [v1, v2] = [p.speed[0] * c, p.speed[1] * c];
        let stop = crate::scenes::finger_stops([x1, x2], [v1, v2], p.width);
        Self { start: [x1, x2], height: p.height, velocity: [v1, v2], stop, tan: p.heading.tan(), h: p.h }
    }

    pub(crate) fn stopped(&self, steps: u64) -> bool {
        let Some([s1, s2]) = self.stop else { return false };
        let t = steps as f64 * self.h;
        let [v1, v2] = self.velocity;
        if v1 > 0.0 {
            self.start[0] + v1 * t >= s1
        } else if v1 < 0.0 {
            self.start[0] + v1 * t <= s1
        } else {
            self.start[1] + v2 * t <= s2
        }
    }

    /// The tips at `steps h`, world.
    pub(crate) fn tips(&self, steps: u64) -> [V3; 2] {
        let t = steps as f64 * self.h;
        let x = match self.stop {
            Some(stop) if self.stopped(steps) => stop,
            _ => [self.start[0] + self.velocity[0] * t, self.start[1] + self.velocity[1] * t],
        };
        std::array::from_fn(|i| [x[i], (x[i] - self.start[i]) * self.tan, self.height[i]])
    }

    /// The fingers' velocities over the step from `steps h`, world.
    pub(crate) fn velocity_over(&self, steps: u64) -> [V3; 2] {
        let vx = if self.stopped(steps + 1) {
            let (a, b) = (self.tips(steps), self.tips(steps + 1));
            [(b[0][0] - a[0][0]) / self.h, (b[1][0] - a[1][0]) / self.h]
        } else {
            self.velocity
        };
        vx.map(|v| [v, v * self.tan, 0.0])
    }
}
