//! The QEMU board binding: the rig loop headless, with pins that count their edges and a start
//! button that reads pressed. Runs a small LCP, then the slow (0.1 m/s) and fast (5 m/s) meter-stick
//! scenes (finger 1 from -0.35 m) through the rig, and every other catalogue scene at its defaults
//! directly through the scene registry (`SceneParams::build_in`, the reduced layout: incline and
//! ladder 6x6, three fingers 9x9, cylinder and Painlevé's rod 3x3), all in f32, and prints for each its switch events, its outcome, statistics and the
//! trajectory checksum (`meterstick_core::planar::Checksum`), then the SysTick ticks the rig's
//! steps took (and, in a scene where the load rule decided some, those steps' and the others' apart:
//! `slow-decided`, `slow-determinate`) and a calibration of ticks against instructions. With `qemu-multibody` (M4F and M33F;
//! see firmware/Cargo.toml) also block-on-block, the 3-block stack and disc-on-board at their defaults
//! in f32 through the registry (`SceneParams::build_multibody`): outcome, steps, the checksum of every
//! step's states of all bodies in body order (`StepReport::add_to`) and the SysTick ticks of their
//! steps, and so the tablecloth at `mu = 2` with the ticks of its steps the rule flagged apart
//! (`tablecloth-mu2-flagged`: the rule's search, `docs/formulation.md`, "Several bodies: the
//! rule"); then the stack through the stack rig (`StackRig`, headless), held for 0.2 s at the
//! default overhang and falling at 1.02: outcome, checksum, each interface's lights at the end and
//! the ticks; each of these runs' ticks by the path that answered each step (`<name> path=..`) and
//! of a step that failed (`path=failed`); then two block-on-block runs whose step fails in f32
//! (`failing-heavy-top`, `failing-light-top`), timed the same way. Exit status: 0 when the LCP was
//! solved and every scene ended as physics says
//! (balanced, fell, slid, fell, held, rolled, jammed; block-on-block slid, the stack held, the disc
//! rolled, the tablecloth stayed; the stack rig held with every interface sticking and fell with
//! every one tipping; the failing runs failed). With `qemu-spatial` (M4F and M33F) also the puck,
//! the billiard ball and the curling stone at their defaults in f32 through the registry's view
//! (`SceneParams::build_view`): outcome, steps, the view's checksum and the ticks of their steps
//! (the puck stopped, the ball rolled, the stone stopped).

use meterstick_core::Real;
#[cfg(any(feature = "qemu-multibody", feature = "qemu-spatial"))]
use meterstick_core::RunStats;
use meterstick_core::lcp::{Lcp, Lemke};
#[cfg(feature = "qemu-multibody")]
use meterstick_core::multibody::StepError;
#[cfg(feature = "qemu-multibody")]
use meterstick_core::multibody::scenes::{BlockOnBlockParams, MultibodyScene, StackParams, TableclothParams};
use meterstick_core::planar::{Checksum, SolvePath, SwitchEvent};
#[cfg(feature = "qemu-multibody")]
use meterstick_core::scene::MultibodyVisitor;
#[cfg(any(feature = "qemu-multibody", feature = "qemu-spatial"))]
use meterstick_core::scene::Precision;
use meterstick_core::scene::{
    LcpLayout, MeterStickParams, Outcome, Scene, SceneKind, SceneParams, SceneVisitor,
};
#[cfg(feature = "qemu-spatial")]
use meterstick_core::scene::{SceneView, ViewVisitor};
#[cfg(feature = "qemu-multibody")]
use meterstick_rig::{InterfaceMode, StackRig};
use meterstick_rig::{MeterStickRig, NoDelay, RigConfig, RigState};

use crate::{stack_peak, systick};

/// Prints a run's switch events (1-based contacts).
fn print_events<T: Real, const K: usize>(name: &str, events: &[SwitchEvent<T, K>]) {
    for e in events {
        defmt::println!(
            "{=str} event t={=f32} contact={=u8} mode={=str} along1={=f32}",
            name,
            e.time.as_f64() as f32,
            e.contact + 1,
            e.mode.name(),
            e.along[0].as_f64() as f32,
        );
    }
}

/// Runs a scene to its outcome outside the rig and prints its checksum and outcome.
fn run_plain<T: Real, S: Scene<T, K>, const K: usize>(name: &str, scene: &mut S) -> Outcome {
    let mut checksum = Checksum::new();
    let outcome = scene.run(|r| checksum.add(&r.state));
    defmt::println!(
        "{=str} outcome={} t={=f32} steps={=u64} pivots={=u64} checks={=u64} checksum={=u32:08x}",
        name,
        outcome,
        scene.time().as_f64() as f32,
        scene.stats().steps,
        scene.stats().pivots,
        scene.stats().reduced_check_fired,
        checksum.value()
    );
    outcome
}

/// 0.1 mm per stepper pulse, so that the fast scene (5 mm per step) fits a tick's budget.
const CONFIG: RigConfig = RigConfig {
    steps_per_meter: 10_000.0,
    pulse_ns: 2_000,
    max_pulses_per_tick: 1_000,
    button_active_low: true,
    // One sample: the headless button is constant (no bounce to filter), so the run starts on
    // the first tick; not real time, so any step.
    debounce_ticks: 1,
    min_step: 0.0,
    max_step: f32::INFINITY,
};

/// Runs the paper's scene at `speed` (finger 1 starting at -0.35 m) through the rig and
/// reports it; `None` on a rig fault. Not inlined, so that the rig's frame is its own (not held on
/// the stack while later scenes run) and the code it times does not depend on its caller.
#[inline(never)]
fn run_scene(name: &str, speed: f32) -> Option<Outcome> {
    let params =
        MeterStickParams { finger1_velocity: speed, finger1_x: -0.35, ..MeterStickParams::<f32>::paper() };
    let mut rig = match MeterStickRig::<_, _, _, 6, 32>::headless(params, CONFIG, NoDelay) {
        Ok(rig) => rig,
        Err(e) => {
            defmt::println!("{=str}: rig not started: {}", name, e);
            return None;
        }
    };
    let mut checksum = Checksum::new();
    let (mut steps, mut all) = (0u64, Tally::default());
    // Per solve path (`SolvePath::ALL`'s order). A step is counted under the last path it needed
    // (a step that fell back to the full layout may use two).
    let mut by_path = [Tally::default(); 4];
    // Steps whose load the rule decided (`docs/formulation.md`, "The load: the least norm") and
    // the others, whose load the contacts decide.
    let (mut decided, mut determinate) = (Tally::default(), Tally::default());
    let state = loop {
        let before = *rig.scene().stats();
        let t0 = systick::now();
        let result = rig.tick();
        let t1 = systick::now();
        let state = match result {
            Ok(s) => s,
            Err(e) => {
                defmt::println!("{=str}: pin error {}", name, e);
                return None;
            }
        };
        if rig.scene().stats().steps > steps {
            steps = rig.scene().stats().steps;
            let used = systick::elapsed(t0, t1);
            all.add(used);
            checksum.add(rig.scene().state());
            let after = rig.scene().stats().paths;
            let path = SolvePath::ALL.iter().rposition(|&p| after.of(p) > before.paths.of(p)).unwrap_or(0);
            if let Some(slot) = by_path.get_mut(path) {
                slot.add(used);
            }
            if rig.scene().stats().load_decided_steps > before.load_decided_steps {
                decided.add(used);
            } else {
                determinate.add(used);
            }
        }
        if !matches!(state, RigState::WaitingForStart | RigState::Running) {
            break state;
        }
    };
    let scene = rig.scene();
    print_events(name, scene.events());
    let st = scene.stats();
    let outcome = match state {
        RigState::Finished(o) => o,
        other => {
            defmt::println!("{=str} rig stopped: {}", name, other);
            return None;
        }
    };
    defmt::println!(
        "{=str} outcome={} t={=f32} steps={=u64} pivots={=u64} checks={=u64} checksum={=u32:08x}",
        name,
        outcome,
        scene.time(),
        st.steps,
        st.pivots,
        st.reduced_check_fired,
        checksum.value()
    );
    for (path, t) in SolvePath::ALL.iter().zip(by_path) {
        defmt::println!(
            "{=str} path={=str} steps={=u64} systicks={=u64} worst_step_systicks={=u32}",
            name,
            path.name(),
            t.steps,
            t.ticks,
            t.worst
        );
    }
    if decided.steps > 0 {
        for (kind, t) in [("determinate", determinate), ("decided", decided)] {
            defmt::println!(
                "{=str}-{=str} timing systicks={=u64} worst_step_systicks={=u32} steps={=u64}",
                name,
                kind,
                t.ticks,
                t.worst,
                t.steps
            );
        }
    }
    let (_, carriage) = rig.release();
    defmt::println!(
        "{=str} rig pulses={=u32} systicks={=u64} worst_step_systicks={=u32} steps={=u64}",
        name,
        carriage.step.rises(),
        all.ticks,
        all.worst,
        steps
    );
    Some(outcome)
}

/// Steps timed, their SysTick ticks and the worst step's.
#[derive(Clone, Copy, Default)]
struct Tally {
    steps: u64,
    ticks: u64,
    worst: u32,
}

impl Tally {
    fn add(&mut self, used: u32) {
        self.steps += 1;
        self.ticks += u64::from(used);
        self.worst = self.worst.max(used);
    }
}

/// Prints the deepest the stack grew since the last [`stack_peak::paint`] (`<name> stack
/// peak_bytes=..`, for `host-sim qemu --json`). Painted and read outside the timed functions, so
/// that the measurement does not change the code whose instructions they count.
fn print_stack_peak(name: &str) {
    defmt::println!("{=str} stack peak_bytes={=u32}", name, stack_peak::peak_bytes());
}

/// What a scene outside the rig must end in, by the laws of `docs/scenes.md` at its defaults.
const fn expected(kind: SceneKind) -> Outcome {
    match kind {
        SceneKind::MeterStick => Outcome::Balanced,
        SceneKind::Incline => Outcome::Slid,
        SceneKind::Ladder => Outcome::Fell,
        SceneKind::ThreeFingers => Outcome::Held,
        SceneKind::Cylinder => Outcome::Rolled,
        SceneKind::Painleve => Outcome::Jammed,
        #[cfg(feature = "qemu-multibody")]
        SceneKind::BlockOnBlock => Outcome::Slid,
        #[cfg(feature = "qemu-multibody")]
        SceneKind::Stack => Outcome::Held,
        #[cfg(feature = "qemu-multibody")]
        SceneKind::Tablecloth => Outcome::Stayed,
        #[cfg(feature = "qemu-multibody")]
        SceneKind::DiscOnBoard => Outcome::Rolled,
        #[cfg(feature = "qemu-spatial")]
        SceneKind::Puck => Outcome::Stopped,
        #[cfg(feature = "qemu-spatial")]
        SceneKind::Billiard => Outcome::Rolled,
        #[cfg(feature = "qemu-spatial")]
        SceneKind::Curling => Outcome::Stopped,
        #[cfg(feature = "qemu-spatial")]
        SceneKind::MeterStick3d => Outcome::Balanced,
    }
}

/// Runs the scene it is handed outside the rig (`run_plain`), prints its events, and counts 1
/// when it ended other than `expected`.
struct CheckPlain {
    name: &'static str,
    expected: Outcome,
}

impl SceneVisitor for CheckPlain {
    type Output = i32;

    /// Not inlined, so that each scene's stack frame is its own (the micro:bit has 16 KiB of RAM).
    #[inline(never)]
    fn visit<T: Real, const K: usize, const N: usize, S: Scene<T, K>>(self, mut scene: S) -> i32 {
        let outcome = run_plain(self.name, &mut scene);
        print_events(self.name, scene.events());
        i32::from(outcome != self.expected)
    }
}

/// Every catalogue scene but the meter stick (which the rig runs) at its defaults, in f32 and the
/// reduced layout, through the scene registry; the number that were refused or ended otherwise.
fn check_other_scenes() -> i32 {
    let mut failures = 0;
    for kind in SceneKind::ALL {
        // The rig's, and the engines of several bodies and of three dimensions (their own checks).
        if kind == SceneKind::MeterStick || !kind.has_layout_choice() {
            continue;
        }
        let check = CheckPlain { name: kind.name(), expected: expected(kind) };
        stack_peak::paint();
        failures += match SceneParams::defaults(kind).build_in::<f32, 16, _>(LcpLayout::Reduced, check) {
            Ok(failed) => failed,
            Err(e) => {
                defmt::println!("{=str}: {}", kind.name(), e);
                1
            }
        };
        print_stack_peak(kind.name());
    }
    failures
}

/// Runs the scene of several bodies it is handed to its outcome, timing each step in SysTick
/// ticks, and prints its outcome, statistics and checksum, then the ticks (`<name> timing ..`, as
/// the rig's scenes print theirs, for `host-sim qemu --icount`); counts 1 when it ended other than
/// `expected`.
#[cfg(feature = "qemu-multibody")]
struct CheckMultibody {
    name: &'static str,
    expected: Outcome,
    /// Also time the steps the rule flagged (`Stats::rule_checked_steps`) apart and print them
    /// as a scene of their own, `<name>-flagged timing ..`.
    flagged: bool,
}

#[cfg(feature = "qemu-multibody")]
impl MultibodyVisitor for CheckMultibody {
    type Output = i32;

    /// Not inlined, so that each scene's stack frame is its own.
    #[inline(never)]
    fn visit<T: Real, const B: usize, const P: usize, S: MultibodyScene<T, B, P>>(self, mut scene: S) -> i32 {
        let mut checksum = Checksum::new();
        let (mut steps, mut ticks, mut worst) = (0u64, 0u64, 0u32);
        let (mut flagged, mut flagged_ticks, mut flagged_worst) = (0u64, 0u64, 0u32);
        // Per solve path (`SolvePath::ALL`'s order), and the step that failed (every path tried,
        // `StepError`), if one did.
        let (mut by_path, mut failed) = ([Tally::default(); 4], Tally::default());
        loop {
            let checked = scene.stats().rule_checked_steps;
            let before = scene.stats().paths;
            let t0 = systick::now();
            let report = scene.step();
            let used = systick::elapsed(t0, systick::now());
            let Some(report) = report else {
                if matches!(scene.outcome(), Some(Outcome::Failed(_))) {
                    failed.add(used);
                }
                break;
            };
            steps += 1;
            ticks += u64::from(used);
            worst = worst.max(used);
            let after = scene.stats().paths;
            if let Some(slot) = SolvePath::ALL
                .iter()
                .rposition(|&p| after.of(p) > before.of(p))
                .and_then(|path| by_path.get_mut(path))
            {
                slot.add(used);
            }
            if scene.stats().rule_checked_steps > checked {
                flagged += 1;
                flagged_ticks += u64::from(used);
                flagged_worst = flagged_worst.max(used);
            }
            report.add_to(&mut checksum);
        }
        let outcome = scene.outcome().unwrap_or(Outcome::Unfinished);
        let time = scene.time().as_f64() as f32;
        print_run(self.name, outcome, time, scene.stats(), checksum.value(), (ticks, worst, steps));
        if self.flagged {
            defmt::println!(
                "{=str}-flagged timing systicks={=u64} worst_step_systicks={=u32} steps={=u64}",
                self.name,
                flagged_ticks,
                flagged_worst,
                flagged
            );
        }
        print_paths(self.name, &by_path, failed);
        // A run meant to fail ends in some failure (its error printed above).
        let wrong = match self.expected {
            Outcome::Failed(_) => !matches!(outcome, Outcome::Failed(_)),
            expected => outcome != expected,
        };
        i32::from(wrong)
    }
}

/// Prints a run's steps by the path that answered them (`<name> path=<path> steps=.. systicks=..
/// worst_step_systicks=..`, `SolvePath::ALL`'s order, as the rig's scenes print theirs), then the
/// step that failed (`path=failed`: every path tried, the step's `StepError`), for `host-sim qemu
/// --icount`.
#[cfg(feature = "qemu-multibody")]
fn print_paths(name: &str, by_path: &[Tally; 4], failed: Tally) {
    for (path, t) in SolvePath::ALL.iter().zip(by_path) {
        defmt::println!(
            "{=str} path={=str} steps={=u64} systicks={=u64} worst_step_systicks={=u32}",
            name,
            path.name(),
            t.steps,
            t.ticks,
            t.worst
        );
    }
    defmt::println!(
        "{=str} path=failed steps={=u64} systicks={=u64} worst_step_systicks={=u32}",
        name,
        failed.steps,
        failed.ticks,
        failed.worst
    );
}

/// Runs `params` in f32 through the registry with `check`, its stack's peak printed after; the
/// failures `check` counts, 1 when the parameters are refused. Inlined into each caller, so that
/// the peak painted and read is the run's frame as the caller's own.
#[cfg(feature = "qemu-multibody")]
#[inline(always)]
#[allow(clippy::inline_always)] // the stack peak's frame, as said above
fn run_checked(name: &str, params: SceneParams, check: CheckMultibody) -> i32 {
    stack_peak::paint();
    let failed = match params.build_multibody(Precision::F32, check) {
        Ok(failed) => failed,
        Err(e) => {
            defmt::println!("{=str}: {}", name, e);
            1
        }
    };
    print_stack_peak(name);
    failed
}

/// Block-on-block, the stack (3 blocks) and disc-on-board (on block-on-block's stepper) at their
/// defaults, in f32, through the registry; the number that were refused or ended otherwise.
#[cfg(feature = "qemu-multibody")]
fn check_multibody_scenes() -> i32 {
    let mut failures = 0;
    for kind in [SceneKind::BlockOnBlock, SceneKind::Stack, SceneKind::DiscOnBoard] {
        let check = CheckMultibody { name: kind.name(), expected: expected(kind), flagged: false };
        failures += run_checked(kind.name(), SceneParams::defaults(kind), check);
    }
    // The tablecloth at `mu = 2`, whose steps the rule flags (the block tipping about its corner
    // on the board): its flagged steps timed apart (`tablecloth-mu2-flagged`).
    let name = "tablecloth-mu2";
    let params = SceneParams::Tablecloth(TableclothParams {
        mu_static: 2.0,
        mu_kinetic: 2.0,
        ..TableclothParams::default()
    });
    let check = CheckMultibody { name, expected: Outcome::Stayed, flagged: true };
    failures += run_checked(name, params, check);
    failures += check_failing_steps();
    failures
}

/// Runs that fail, to time a step that tries every path and returns `StepError` (its ticks under
/// `path=failed`): each must end in `Outcome::Failed`.
#[cfg(feature = "qemu-multibody")]
#[inline(never)]
fn check_failing_steps() -> i32 {
    // Block-on-block with masses f32 does not hold apart: a 1e6 kg top block riding on a 1 kg
    // bottom one (pulled at 0.45 (m + M) g: fails on the first step, a Lemke ray; f64 rides), and a
    // 1 kg top block on a 1e12 kg bottom one sliding (2.9 (m + M) g: fails on the second; `m / M`
    // far below f32's `eps`, the top block's weight lost in the sums of the bottom block's
    // impulses; f64 slides).
    let failing = [
        (
            "failing-heavy-top",
            SceneParams::BlockOnBlock(BlockOnBlockParams {
                top_mass: 1e6,
                bottom_mass: 1.0,
                force: 0.45 * (1e6 + 1.0) * 9.81,
                ..BlockOnBlockParams::default()
            }),
        ),
        (
            "failing-light-top",
            SceneParams::BlockOnBlock(BlockOnBlockParams {
                top_mass: 1.0,
                bottom_mass: 1e12,
                force: 2.9 * (1e12 + 1.0) * 9.81,
                ..BlockOnBlockParams::default()
            }),
        ),
    ];
    let mut failures = 0;
    for (name, params) in failing {
        let expected = Outcome::Failed(StepError::NonFinite);
        let check = CheckMultibody { name, expected, flagged: false };
        failures += run_checked(name, params, check);
    }
    failures
}

/// A run of several bodies or in three dimensions: `<name> outcome=.. t=.. steps=.. pivots=..
/// max_active=.. checksum=..`, then `<name> timing systicks=.. worst_step_systicks=.. steps=..`
/// (`timed`: the ticks of its steps, the worst one's, the steps timed), for `host-sim qemu`.
#[cfg(any(feature = "qemu-multibody", feature = "qemu-spatial"))]
fn print_run(name: &str, outcome: Outcome, time: f32, st: &RunStats, checksum: u32, timed: (u64, u32, u64)) {
    defmt::println!(
        "{=str} outcome={} t={=f32} steps={=u64} pivots={=u64} max_active={=u8} checksum={=u32:08x}",
        name,
        outcome,
        time,
        st.steps,
        st.pivots,
        st.most_lcp_contacts.unwrap_or(0),
        checksum
    );
    let (ticks, worst, steps) = timed;
    defmt::println!(
        "{=str} timing systicks={=u64} worst_step_systicks={=u32} steps={=u64}",
        name,
        ticks,
        worst,
        steps
    );
}

/// A scene in three dimensions through the registry's view ([`SceneParams::build_view`]): each
/// step timed (the view's `dyn` call and bookkeeping included), then its outcome, steps, pivots and
/// the view's trajectory checksum (every body's state after every step), and its ticks, in the
/// lines the scenes of several bodies print; counts 1 unless it ended in `expected`.
#[cfg(feature = "qemu-spatial")]
struct CheckView {
    name: &'static str,
    expected: Outcome,
}

#[cfg(feature = "qemu-spatial")]
impl ViewVisitor for CheckView {
    type Output = i32;

    /// Not inlined, so that each scene's stack frame is its own.
    #[inline(never)]
    fn visit<T: Real>(self, view: &mut dyn SceneView<T>) -> i32 {
        let (mut steps, mut ticks, mut worst) = (0u64, 0u64, 0u32);
        loop {
            let t0 = systick::now();
            let stepped = view.step();
            let used = systick::elapsed(t0, systick::now());
            if !stepped {
                break;
            }
            steps += 1;
            ticks += u64::from(used);
            worst = worst.max(used);
        }
        let outcome = view.outcome().unwrap_or(Outcome::Unfinished);
        let time = view.time().as_f64() as f32;
        print_run(self.name, outcome, time, &view.summary(), view.checksum(), (ticks, worst, steps));
        i32::from(outcome != self.expected)
    }
}

/// The puck, the billiard ball, the curling stone and the meter stick in three dimensions at their
/// defaults, in f32, through the registry's view; the number refused or ended otherwise than
/// physics says (the puck stops, the ball rolls, the stone stops, the rod balances).
#[cfg(feature = "qemu-spatial")]
fn check_spatial_scenes() -> i32 {
    let mut failures = 0;
    for kind in [SceneKind::Puck, SceneKind::Billiard, SceneKind::Curling, SceneKind::MeterStick3d] {
        let check = CheckView { name: kind.name(), expected: expected(kind) };
        stack_peak::paint();
        failures +=
            match SceneParams::defaults(kind).build_view::<0, _>(Precision::F32, LcpLayout::Reduced, check) {
                Ok(failed) => failed,
                Err(e) => {
                    defmt::println!("{=str}: {}", kind.name(), e);
                    1
                }
            };
        print_stack_peak(kind.name());
    }
    failures
}

/// Runs the 3-block stack through the stack rig (`StackRig` on headless pins, the start button
/// pressed on the first tick), timing each tick that stepped, and prints its outcome, steps and
/// the checksum of every step's states of all bodies (as the plain runs), each interface's mode
/// at the end, then its ticks (`<name> rig ..`, for `host-sim qemu --icount`); counts 1 unless
/// it ended in `expected` with every interface showing `shown` and the fault light never on.
/// Not inlined, so that the rig's frame is its own.
#[cfg(feature = "qemu-multibody")]
#[inline(never)]
fn run_stack_rig(name: &str, params: StackParams<f32>, expected: Outcome, shown: InterfaceMode) -> i32 {
    let mut rig = match StackRig::headless(params, CONFIG) {
        Ok(rig) => rig,
        Err(e) => {
            defmt::println!("{=str}: rig not started: {}", name, e);
            return 1;
        }
    };
    let mut checksum = Checksum::new();
    let (mut steps, mut ticks, mut worst) = (0u64, 0u64, 0u32);
    let mut by_path = [Tally::default(); 4];
    let state = loop {
        let before = rig.scene().stats().paths;
        let t0 = systick::now();
        let result = rig.tick();
        let used = systick::elapsed(t0, systick::now());
        let state = match result {
            Ok(s) => s,
            Err(e) => {
                defmt::println!("{=str}: pin error {}", name, e);
                return 1;
            }
        };
        if rig.scene().stats().steps > steps {
            steps = rig.scene().stats().steps;
            ticks += u64::from(used);
            worst = worst.max(used);
            for body in rig.scene().states() {
                checksum.add(body);
            }
            let after = rig.scene().stats().paths;
            if let Some(slot) = SolvePath::ALL
                .iter()
                .rposition(|&p| after.of(p) > before.of(p))
                .and_then(|path| by_path.get_mut(path))
            {
                slot.add(used);
            }
        }
        if !matches!(state, RigState::WaitingForStart | RigState::Running) {
            break state;
        }
    };
    let modes = *rig.shown();
    let outcome = match state {
        RigState::Finished(o) => o,
        other => {
            defmt::println!("{=str} rig stopped: {}", name, other);
            return 1;
        }
    };
    defmt::println!(
        "{=str} outcome={} t={=f32} steps={=u64} checksum={=u32:08x}",
        name,
        outcome,
        rig.scene().time(),
        steps,
        checksum.value()
    );
    for (i, mode) in modes.iter().enumerate() {
        defmt::println!(
            "{=str} interface={=usize} shown={=str}",
            name,
            i,
            mode.map_or("off", InterfaceMode::name)
        );
    }
    defmt::println!(
        "{=str} rig systicks={=u64} worst_step_systicks={=u32} steps={=u64}",
        name,
        ticks,
        worst,
        steps
    );
    // A failed step stops the rig (`Fault`, counted a failure above): none here.
    print_paths(name, &by_path, Tally::default());
    let faulted = rig.release().0.fault.rises() > 0;
    i32::from(outcome != expected || modes != [Some(shown); 3] || faulted)
}

/// The stack rig, kept short: the catalogue's stack for 0.2 s (it holds, every interface
/// sticking), and at overhang 1.02 (it falls in 0.2 s, every block tipping over an edge); the
/// number that ended otherwise. Not inlined: `main`'s frame is held under every scene.
#[cfg(feature = "qemu-multibody")]
#[inline(never)]
fn check_stack_rig() -> i32 {
    let held = StackParams { max_time: 0.2, ..StackParams::default() };
    let fell = StackParams { overhang: 1.02, ..StackParams::default() };
    let mut failures = 0;
    for (name, params, expected, shown) in [
        ("stack-rig-held", held, Outcome::Held, InterfaceMode::Sticking),
        ("stack-rig-fell", fell, Outcome::Fell, InterfaceMode::Tipping),
    ] {
        stack_peak::paint();
        failures += run_stack_rig(name, params, expected, shown);
        print_stack_peak(name);
    }
    failures
}

pub fn main() -> ! {
    defmt::println!("meterstick-firmware {} core {}", env!("CARGO_PKG_VERSION"), meterstick_core::VERSION);
    let Some(mut cp) = cortex_m::Peripherals::take() else {
        defmt::println!("core peripherals already taken");
        semihosting::process::exit(103)
    };
    systick::start(&mut cp.SYST, systick::MASK);
    // Calibration: `asm::delay(n)` runs `subs; bne` n + 1 times.
    let (n, t0) = (1_000_000u32, systick::now());
    cortex_m::asm::delay(n);
    let ticks = systick::elapsed(t0, systick::now());
    defmt::println!("calibration instructions={=u32} systicks={=u32}", 2 * (n + 1), ticks);
    defmt::println!("ram stack_room_bytes={=u32}", stack_peak::room_bytes());

    let mut failures = 0i32;
    // Kostreva's cycling example in f32: z = (1/3, 1/3, 1/3).
    let lcp =
        Lcp::<f32, 3>::from_rows(&[[1.0, 2.0, 0.0], [0.0, 1.0, 2.0], [2.0, 0.0, 1.0]], &[-1.0, -1.0, -1.0]);
    match Lemke::<f32, 3>::new().solve(&lcp) {
        Ok(sol) => defmt::println!(
            "lcp3 z = [{=f32}, {=f32}, {=f32}] pivots={=u32}",
            sol.z[0],
            sol.z[1],
            sol.z[2],
            sol.pivots
        ),
        Err(e) => {
            defmt::println!("lcp3 error: {}", e);
            failures += 1;
        }
    }
    for (name, speed, expected) in [("slow", 0.1, Outcome::Balanced), ("fast", 5.0, Outcome::Fell)] {
        stack_peak::paint();
        if run_scene(name, speed) != Some(expected) {
            failures += 1;
        }
        print_stack_peak(name);
    }
    failures += check_other_scenes();
    #[cfg(feature = "qemu-multibody")]
    {
        failures += check_multibody_scenes();
        failures += check_stack_rig();
    }
    #[cfg(feature = "qemu-spatial")]
    {
        failures += check_spatial_scenes();
    }
    defmt::println!("exit {=i32}", failures);
    semihosting::process::exit(failures)
}
