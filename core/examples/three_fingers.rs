//! A scene written outside the crate, as a user would: a rod on three fingers, the left one moving
//! toward the middle one until they are 1 cm apart.
//!
//! With three supports under a rigid rod the normal forces are statically indeterminate (only
//! their sum and moment are fixed), so each step's LCP has a family of solutions, and since friction
//! is `mu` times the normal force, different splits drag the rod differently: rigid contact with
//! friction does not decide this motion. The stepper takes the motion of least kinetic energy and the
//! load of least 2-norm with it: the split that equally stiff fingers give, `N_i = a + b x_i` at
//! rest (`docs/formulation.md`, "The load: the least norm").
//!
//! `cargo run -p meterstick-core --example three_fingers` (CONTRIBUTING.md, "Adding a scene").
#![allow(clippy::print_stdout)]

use meterstick_core::ParamError;
use meterstick_core::planar::{
    Body, BodyState, Contact, ContactFrame, ContactMode, EventLog, Feature, Layout, Model, RunStats,
    Settings, StepReport, Stepper, Support, SwitchEvent, Tangents,
};
use meterstick_core::scene::{BodyShape, Outcome, Scene};

/// Finger 1 drags the rod toward `+x` (`+d`); fingers 2 and 3 hold it back (`-d`): 3 + 3 + 3
/// variables, checked against the full layout (3 + 6 + 3) after every step.
const REDUCED: Layout<3, 9> = Layout::new([Tangents::Plus, Tangents::Minus, Tangents::Minus]);
const FULL: Layout<3, 12> = Layout::full();
const START: [f64; 3] = [-0.4, 0.0, 0.4];
const SPEED: f64 = 0.1;
const WIDTH: f64 = 0.01;

struct ThreeFingers {
    stepper: Stepper<f64, 3, 9, 12>,
    events: EventLog<f64, 3, 32>,
    stopped_at: Option<f64>,
    outcome: Option<Outcome>,
}

fn fingers(x1: f64, v1: f64) -> [Support<f64>; 3] {
    [
        Support::point([x1, 0.0], [v1, 0.0]),
        Support::point([START[1], 0.0], [0.0; 2]),
        Support::point([START[2], 0.0], [0.0; 2]),
    ]
}

/// The rod: 0.2 kg, 1 m long, 5 mm thick.
fn rod() -> Body<f64> {
    Body::rod(0.2, 1.0, 0.005)
}

impl ThreeFingers {
    fn new() -> Result<Self, ParamError> {
        let finger = Contact { feature: Feature::LowerFace, mu_static: 0.6, mu_kinetic: 0.4 };
        let model = Model {
            body: rod(),
            contacts: [finger; 3],
            settings: Settings { step: 1e-3, gravity: 9.81, stick_speed: 1e-5 },
        };
        let start = BodyState::at_rest(0.0, 0.0025, 0.0);
        let stepper = Stepper::new(model, REDUCED, FULL, start, fingers(START[0], SPEED))?;
        Ok(Self { stepper, events: EventLog::new(), stopped_at: None, outcome: None })
    }
}

impl Scene<f64, 3> for ThreeFingers {
    fn step(&mut self) -> Option<StepReport<f64, 3>> {
        if self.outcome.is_some() {
            return None;
        }
        let t = self.stepper.next_time();
        let stop = START[1] - WIDTH;
        let (x1, v1) = if START[0] + SPEED * t < stop { (START[0] + SPEED * t, SPEED) } else { (stop, 0.0) };
        let report = match self.stepper.step(&fingers(x1, v1)) {
            Ok(r) => r,
            Err(e) => {
                self.outcome = Some(Outcome::Failed(e));
                return None;
            }
        };
        self.events.record(&report);
        if v1 == 0.0 {
            self.stopped_at.get_or_insert(t);
        }
        let on_a_finger = self.stepper.frames().iter().any(|f| f.active);
        if report.state.theta.abs() > 0.35 || !on_a_finger {
            self.outcome = Some(Outcome::Fell);
        } else if self.stopped_at.is_some_and(|s| t - s >= 0.5) {
            self.outcome = Some(Outcome::Held);
        }
        Some(report)
    }
    fn outcome(&self) -> Option<Outcome> {
        self.outcome
    }
    fn shape(&self) -> BodyShape<f64> {
        BodyShape::Box { width: 1.0, height: 0.005 }
    }
    fn body(&self) -> Body<f64> {
        rod()
    }
    fn state(&self) -> &BodyState<f64> {
        self.stepper.state()
    }
    fn time(&self) -> f64 {
        self.stepper.time()
    }
    fn supports(&self) -> &[Support<f64>; 3] {
        self.stepper.supports()
    }
    fn frames(&self) -> &[ContactFrame<f64>; 3] {
        self.stepper.frames()
    }
    fn modes(&self) -> [ContactMode; 3] {
        self.stepper.modes()
    }
    fn stats(&self) -> &RunStats {
        self.stepper.stats()
    }
    fn events(&self) -> &[SwitchEvent<f64, 3>] {
        self.events.events()
    }
}

fn main() -> Result<(), ParamError> {
    let mut scene = ThreeFingers::new()?;
    let mut last = None;
    let outcome = scene.run(|r| last = Some(*r));
    println!(
        "three fingers: {outcome} at t = {:.3} s, centre of mass at x = {:+.4} m",
        scene.time(),
        scene.state().x
    );
    for e in scene.events() {
        println!("  t = {:6.3} s  finger {} -> {}", e.time, e.contact + 1, e.mode.name());
    }
    if let Some(r) = last {
        let total: f64 = r.contacts.iter().map(|c| c.normal_impulse).sum();
        let weight = 0.2 * 9.81 * 1e-3;
        println!(
            "last step: normal impulses {:?} N s, sum {total:.6e} = m g h {weight:.6e}",
            r.contacts.map(|c| c.normal_impulse)
        );
    }
    let s = scene.stats();
    println!(
        "{} steps, {} pivots, {} steps needed the full 12x12 layout",
        s.steps, s.pivots, s.reduced_check_fired
    );
    Ok(())
}
