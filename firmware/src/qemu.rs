//! The QEMU board binding: the rig loop headless, with pins that count their edges and a start
//! button that reads pressed. Runs a small LCP, then the slow (0.1 m/s) and fast (5 m/s) meter-stick
//! scenes (finger 1 from -0.35 m) through the rig, and every other catalogue scene this build has at
//! its defaults in f32 through the core's one scene interface ([`SceneView`], built by
//! [`SceneParams::build_view_in`] and driven by [`Check`] as the view's concrete type: the scenes of
//! one body in the reduced layout, incline and ladder 6x6, three fingers 9x9, cylinder and
//! Painlevé's rod 3x3; with `qemu-multibody`, M4F and M33F, block-on-block, the 3-block stack and
//! disc-on-board; with `qemu-spatial`, M4F and M33F, the puck, the billiard ball, the curling stone
//! and the meter stick in three dimensions). For each run it prints its outcome, statistics and
//! the trajectory checksum (`meterstick_core::planar::Checksum` over every body's state after every
//! step), its switch events, and the SysTick ticks its steps took: all of them (`<name> timing`
//! or, through a rig, `<name> rig`), by the path that answered each step (`<name> path=..`) and
//! the step that failed (`path=failed`), and, in a run where the load rule decided some steps,
//! those and the others apart (`<name>-decided`, `<name>-determinate`); then a calibration of ticks
//! against instructions. With `qemu-multibody` also the tablecloth at `mu = 2` with the ticks of
//! its steps the rule flagged apart (`tablecloth-mu2-flagged`: the rule's search,
//! `docs/formulation.md`, "Several bodies: the rule"); two block-on-block runs whose step fails
//! in f32 (`failing-heavy-top`, `failing-light-top`); and the stack through the stack rig
//! (`StackRig`, headless), held for 0.2 s at the default overhang and falling at 1.02: outcome,
//! checksum, each interface's lights at the end and the ticks. Exit status: 0 when the LCP was
//! solved and every run ended as physics says (`docs/scenes.md`: balanced, fell, slid, fell, held,
//! rolled, jammed; block-on-block slid, the stack held, the disc rolled, the tablecloth stayed; the
//! stack rig held with every interface sticking and fell with every one tipping; the failing runs
//! failed; the puck stopped, the ball rolled, the stone stopped, the rod balanced).

use meterstick_core::Real;
use meterstick_core::RunStats;
use meterstick_core::lcp::{Lcp, Lemke};
#[cfg(feature = "qemu-multibody")]
use meterstick_core::multibody::StepError;
#[cfg(feature = "qemu-multibody")]
use meterstick_core::multibody::scenes::{BlockOnBlockParams, MultibodyScene, StackParams, TableclothParams};
use meterstick_core::planar::{Checksum, SolvePath};
use meterstick_core::scene::{
    EventView, LcpLayout, MeterStickParams, Outcome, Scene, SceneKind, SceneParams, SceneView, ViewVisitor,
};
#[cfg(feature = "qemu-multibody")]
use meterstick_rig::{InterfaceMode, StackRig};
use meterstick_rig::{MeterStickRig, NoDelay, RigConfig, RigState};

use crate::{stack_peak, systick};

/// Prints a run's switch event (1-based contact; its coordinate along its support).
fn print_event<T: Real>(name: &str, e: EventView<T>) {
    defmt::println!(
        "{=str} event t={=f32} contact={=usize} mode={=str} along={=f32}",
        name,
        e.time.as_f64() as f32,
        e.contact + 1,
        e.mode.name(),
        e.along.as_f64() as f32,
    );
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

/// A run's steps timed, sorted by what the engine's counters ([`RunStats`]) say each step did:
/// every one, by the path that answered it, whether the rule flagged it, whether the load rule
/// decided its load; and the step that failed.
#[derive(Clone, Copy, Default)]
struct StepTimes {
    all: Tally,
    /// Per solve path, `SolvePath::ALL`'s order: a step is counted under the last path it needed
    /// (a step of one body that fell back to the full layout may use two); a step no path counted
    /// (an engine that does not count them) under none.
    by_path: [Tally; 4],
    /// The step that failed (every path tried), if one did.
    failed: Tally,
    /// Steps the rule flagged as possibly having several motions (`RunStats::rule_checked_steps`).
    flagged: Tally,
    /// Steps whose load the rule decided (`docs/formulation.md`, "The load: the least norm"), and
    /// the others, whose load the contacts decide.
    decided: Tally,
    determinate: Tally,
}

impl StepTimes {
    /// A step that took `used` ticks, the engine's counters `before` and `after` it.
    fn add(&mut self, used: u32, before: &Marks, after: &Marks) {
        self.all.add(used);
        // The last path whose count rose.
        let mut path = None;
        for (i, (a, b)) in after.paths.iter().zip(&before.paths).enumerate() {
            if a > b {
                path = Some(i);
            }
        }
        if let Some(slot) = path.and_then(|i| self.by_path.get_mut(i)) {
            slot.add(used);
        }
        if after.flagged > before.flagged {
            self.flagged.add(used);
        }
        if after.decided > before.decided {
            self.decided.add(used);
        } else {
            self.determinate.add(used);
        }
    }

    /// Prints the steps by the path that answered them (`<name> path=<path> steps=.. systicks=..
    /// worst_step_systicks=..`, `SolvePath::ALL`'s order), then, with `failed`, the step that failed
    /// (`path=failed`), for `host-sim qemu --icount`; nothing for an engine that counts no paths.
    fn print_paths(&self, name: &str, failed: bool) {
        if self.by_path.iter().chain([&self.failed]).all(|t| t.steps == 0) {
            return;
        }
        for (path, t) in SolvePath::ALL.iter().zip(self.by_path) {
            defmt::println!(
                "{=str} path={=str} steps={=u64} systicks={=u64} worst_step_systicks={=u32}",
                name,
                path.name(),
                t.steps,
                t.ticks,
                t.worst
            );
        }
        if failed {
            defmt::println!(
                "{=str} path=failed steps={=u64} systicks={=u64} worst_step_systicks={=u32}",
                name,
                self.failed.steps,
                self.failed.ticks,
                self.failed.worst
            );
        }
    }

    /// In a run where the load rule decided some steps and the contacts others, prints the two
    /// apart, as scenes of their own (`<name>-determinate timing ..`, `<name>-decided timing ..`).
    fn print_load_split(&self, name: &str) {
        if self.decided.steps == 0 || self.determinate.steps == 0 {
            return;
        }
        for (kind, t) in [("determinate", self.determinate), ("decided", self.decided)] {
            print_timing(name, kind, t);
        }
    }
}

/// The engine's counters ([`RunStats`]) that sort the steps [`StepTimes`] times: read before and
/// after each step (a few words, not the whole record, kept on the stack across the step).
#[derive(Clone, Copy)]
struct Marks {
    steps: u64,
    /// Solves per path, `SolvePath::ALL`'s order.
    paths: [u64; 4],
    /// Steps the rule flagged.
    flagged: u64,
    /// Steps whose load the rule decided.
    decided: u64,
}

impl Marks {
    fn of(st: &RunStats) -> Self {
        Self {
            steps: st.steps,
            paths: SolvePath::ALL.map(|p| st.paths.of(p)),
            flagged: st.rule_checked_steps,
            decided: st.load_decided_steps,
        }
    }
}

/// `<name><-kind> timing systicks=.. worst_step_systicks=.. steps=..` (`kind` empty: the run's
/// own line), for `host-sim qemu --icount`.
fn print_timing(name: &str, kind: &str, t: Tally) {
    let dash = if kind.is_empty() { "" } else { "-" };
    defmt::println!(
        "{=str}{=str}{=str} timing systicks={=u64} worst_step_systicks={=u32} steps={=u64}",
        name,
        dash,
        kind,
        t.ticks,
        t.worst,
        t.steps
    );
}

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
    let mut times = StepTimes::default();
    let state = loop {
        let before = Marks::of(rig.scene().stats());
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
        let after = Marks::of(rig.scene().stats());
        if after.steps > before.steps {
            times.add(systick::elapsed(t0, t1), &before, &after);
            checksum.add(rig.scene().state());
        }
        if !matches!(state, RigState::WaitingForStart | RigState::Running) {
            break state;
        }
    };
    let scene = rig.scene();
    for e in scene.events() {
        print_event(name, EventView::from(e));
    }
    let st = scene.stats();
    let steps = st.steps;
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
    // A failed step stops the rig (`Fault`, a `None` above): no `path=failed`.
    times.print_paths(name, false);
    times.print_load_split(name);
    let (_, carriage) = rig.release();
    defmt::println!(
        "{=str} rig pulses={=u32} systicks={=u64} worst_step_systicks={=u32} steps={=u64}",
        name,
        carriage.step.rises(),
        times.all.ticks,
        times.all.worst,
        steps
    );
    Some(outcome)
}

/// Prints the deepest the stack grew since the last [`stack_peak::paint`] (`<name> stack
/// peak_bytes=..`, for `host-sim qemu --json`). Painted and read outside the timed functions, so
/// that the measurement does not change the code whose instructions they count.
fn print_stack_peak(name: &str) {
    defmt::println!("{=str} stack peak_bytes={=u32}", name, stack_peak::peak_bytes());
}

/// What a scene must end in at its defaults, by the laws of `docs/scenes.md`.
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

/// The switch events a scene of one body keeps for the firmware to print.
const EVENTS: usize = 16;

/// Runs the scene it is handed, of any engine, to its outcome, timing each step in SysTick ticks
/// (the view's `step`: the scene's step and the view's bookkeeping of it, its checksum), and
/// prints its outcome, counters and checksum ([`print_run`]); its switch events; its ticks
/// ([`StepTimes`]: `<name> timing ..`, by path, the load rule's steps apart, with `flagged` the
/// rule's flagged steps apart, `<name>-flagged timing ..`). Counts 1 unless it ended in
/// `expected` (for a run meant to fail: in some failure).
struct Check {
    name: &'static str,
    expected: Outcome,
    flagged: bool,
}

impl Check {
    fn drive<T: Real, V: SceneView<T> + ?Sized>(self, view: &mut V) -> i32 {
        let mut times = StepTimes::default();
        let mut before = Marks::of(&view.summary());
        loop {
            let t0 = systick::now();
            let stepped = view.step();
            let used = systick::elapsed(t0, systick::now());
            if !stepped {
                if matches!(view.outcome(), Some(Outcome::Failed(_))) {
                    times.failed.add(used);
                }
                break;
            }
            let after = Marks::of(&view.summary());
            times.add(used, &before, &after);
            before = after;
        }
        let outcome = view.outcome().unwrap_or(Outcome::Unfinished);
        print_run(self.name, outcome, view.time().as_f64() as f32, &view.summary(), view.checksum());
        for e in (0..view.event_count()).filter_map(|i| view.event(i)) {
            print_event(self.name, e);
        }
        self.finish(outcome, &times)
    }

    /// Prints the run's ticks and counts 1 unless it ended as expected. Not generic: one copy for
    /// every scene (the micro:bit's 256 KiB of flash).
    #[inline(never)]
    fn finish(&self, outcome: Outcome, times: &StepTimes) -> i32 {
        let name = self.name;
        print_timing(name, "", times.all);
        if self.flagged {
            print_timing(name, "flagged", times.flagged);
        }
        times.print_load_split(name);
        times.print_paths(name, true);
        let wrong = match self.expected {
            Outcome::Failed(_) => !matches!(outcome, Outcome::Failed(_)),
            expected => outcome != expected,
        };
        i32::from(wrong)
    }
}

/// A run's `<name> outcome=.. t=.. steps=.. pivots=..`, then `checks=..` (the reduced layout's
/// check fired: an engine whose every LCP holds all its contacts) or `max_active=..` (the most
/// candidate contacts an LCP held), and `checksum=..`.
#[inline(never)]
fn print_run(name: &str, outcome: Outcome, time: f32, st: &RunStats, checksum: u32) {
    match st.most_lcp_contacts {
        Some(active) => defmt::println!(
            "{=str} outcome={} t={=f32} steps={=u64} pivots={=u64} max_active={=u8} checksum={=u32:08x}",
            name,
            outcome,
            time,
            st.steps,
            st.pivots,
            active,
            checksum
        ),
        None => defmt::println!(
            "{=str} outcome={} t={=f32} steps={=u64} pivots={=u64} checks={=u64} checksum={=u32:08x}",
            name,
            outcome,
            time,
            st.steps,
            st.pivots,
            st.reduced_check_fired,
            checksum
        ),
    }
}

impl ViewVisitor for Check {
    type Output = i32;

    /// The same check through `dyn`; [`SceneParams::build_view_in`] calls
    /// [`Self::visit_concrete`] instead, so this one is never compiled into the firmware.
    fn visit<T: Real>(self, view: &mut dyn SceneView<T>) -> i32 {
        self.drive(view)
    }

    /// Not inlined, so that each scene's stack frame is its own (the micro:bit has 16 KiB of RAM).
    #[inline(never)]
    fn visit_concrete<T: Real, V: SceneView<T>>(self, view: &mut V) -> i32 {
        self.drive(view)
    }
}

/// Runs `params` in f32 (the scenes of one body in the reduced layout) through the core's scene
/// interface with `check`, its stack's peak printed after; the failures `check` counts, 1 when the
/// parameters are refused. Inlined into each caller, so that the peak painted and read is the
/// run's frame as the caller's own.
#[inline(always)]
#[allow(clippy::inline_always)] // the stack peak's frame, as said above
fn run_checked(params: SceneParams, check: Check) -> i32 {
    let name = check.name;
    stack_peak::paint();
    let failed = match params.build_view_in::<f32, EVENTS, _>(LcpLayout::Reduced, check) {
        Ok(failed) => failed,
        Err(e) => {
            defmt::println!("{=str}: {}", name, e);
            1
        }
    };
    print_stack_peak(name);
    failed
}

/// Every catalogue scene this build has at its defaults but the meter stick (the rig runs it) and
/// the tablecloth (run at `mu = 2`: [`check_tablecloth`]); the number that were refused or ended
/// otherwise.
fn check_scenes() -> i32 {
    let mut failures = 0;
    for kind in SceneKind::ALL {
        #[cfg(feature = "qemu-multibody")]
        if kind == SceneKind::Tablecloth {
            continue;
        }
        if kind == SceneKind::MeterStick {
            continue;
        }
        let check = Check { name: kind.name(), expected: expected(kind), flagged: false };
        failures += run_checked(SceneParams::defaults(kind), check);
    }
    failures
}

/// The tablecloth at `mu = 2`, whose steps the rule flags (the block tipping about its corner on
/// the board): its flagged steps timed apart (`tablecloth-mu2-flagged`); counts 1 unless it stayed.
#[cfg(feature = "qemu-multibody")]
fn check_tablecloth() -> i32 {
    let params = SceneParams::Tablecloth(TableclothParams {
        mu_static: 2.0,
        mu_kinetic: 2.0,
        ..TableclothParams::default()
    });
    run_checked(params, Check { name: "tablecloth-mu2", expected: Outcome::Stayed, flagged: true })
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
        failures += run_checked(params, Check { name, expected, flagged: false });
    }
    failures
}

/// Runs the 3-block stack through the stack rig (`StackRig` on headless pins, the start button
/// pressed on the first tick), timing each tick that stepped, and prints its outcome, steps and
/// the checksum of every step's states of all bodies (as the runs through the view), each
/// interface's mode at the end, then its ticks (`<name> rig ..`, for `host-sim qemu --icount`);
/// counts 1 unless it ended in `expected` with every interface showing `shown` and the fault light
/// never on. Not inlined, so that the rig's frame is its own.
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
    let mut times = StepTimes::default();
    let state = loop {
        let before = Marks::of(rig.scene().stats());
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
        let after = Marks::of(rig.scene().stats());
        if after.steps > before.steps {
            times.add(used, &before, &after);
            for body in rig.scene().states() {
                checksum.add(body);
            }
        }
        if !matches!(state, RigState::WaitingForStart | RigState::Running) {
            break state;
        }
    };
    let (modes, steps) = (*rig.shown(), rig.scene().stats().steps);
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
        times.all.ticks,
        times.all.worst,
        steps
    );
    // A failed step stops the rig (`Fault`, counted a failure above): `path=failed` is 0 here.
    times.print_paths(name, true);
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
    // The algebra's comparison alone (`crate::algebra_bench`), not the scenes.
    if cfg!(feature = "qemu-algebra") {
        #[cfg(feature = "qemu-algebra")]
        crate::algebra_bench::run();
        semihosting::process::exit(0)
    }

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
    failures += check_scenes();
    #[cfg(feature = "qemu-multibody")]
    {
        failures += check_tablecloth();
        failures += check_failing_steps();
        failures += check_stack_rig();
    }
    defmt::println!("exit {=i32}", failures);
    semihosting::process::exit(failures)
}
