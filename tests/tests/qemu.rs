//! The firmware, cross-built by `scripts/test.sh`, run under QEMU: its decoded defmt output
//! and its exit status are checked. Ignored in a plain `cargo test` (they need the ELFs);
//! `scripts/test.sh` builds them and runs these with `--ignored`, passing the paths in
//! `MS_FIRMWARE_M4`, `MS_FIRMWARE_M0` and `MS_FIRMWARE_M33` (and the spatial builds' in
//! `MS_FIRMWARE_M4_SPATIAL` and `MS_FIRMWARE_M33_SPATIAL`).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::path::PathBuf;
use std::time::Duration;

use meterstick_core::Real;
use meterstick_core::multibody::scenes::{
    BlockOnBlockParams, MultibodyScene, Stack3, StackParams, TableclothParams,
};
use meterstick_core::planar::Checksum;
use meterstick_core::scene::{
    Cylinder, CylinderParams, Incline, InclineParams, Ladder, LadderParams, LcpLayout, MeterStick6,
    MeterStickParams, MultibodyVisitor, Outcome, Painleve, PainleveParams, Precision, Scene, SceneKind,
    SceneParams, SceneView, ThreeFingers, ThreeFingersParams, ViewVisitor,
};
use meterstick_host_sim::qemu::{self, FirmwareRun, Machine};

fn run(var: &str, machine: Machine) -> FirmwareRun {
    let elf =
        PathBuf::from(std::env::var(var).unwrap_or_else(|_| panic!("{var} is not set: run scripts/test.sh")));
    let run = qemu::run(&elf, machine, Duration::from_secs(120), false).expect("QEMU run");
    for line in &run.lines {
        println!("[{}] {line}", machine.qemu_name());
    }
    assert!(!run.timed_out, "firmware hung (killed after the timeout)");
    assert_eq!(run.exit_code, Some(0), "firmware exit status; output: {:#?}", run.lines);
    run
}

fn check_common(run: &FirmwareRun) {
    assert!(
        run.lines.first().is_some_and(|l| l.starts_with("meterstick-firmware ")),
        "banner: {:?}",
        run.lines
    );
    let lcp = run.lines.iter().find(|l| l.starts_with("lcp3 z = ")).expect("the LCP line");
    // z = (1/3, 1/3, 1/3) in f32.
    let inner = lcp.trim_start_matches("lcp3 z = [").split(']').next().unwrap();
    let z: Vec<f32> = inner.split(", ").map(|x| x.parse().unwrap()).collect();
    assert_eq!(z.len(), 3);
    for v in z {
        assert!((v - 1.0 / 3.0).abs() < 1e-6, "{lcp}");
    }
    assert_eq!(run.lines.last().map(String::as_str), Some("exit 0"));
    for (name, speed, outcome) in [("slow", 0.1f32, "Balanced"), ("fast", 5.0, "Fell")] {
        let line = run.lines.iter().find(|l| l.starts_with(&format!("{name} outcome="))).expect("scene line");
        assert!(line.starts_with(&format!("{name} outcome={outcome} ")), "{line}");
        let host = host_run(speed);
        let steps = host.stats().steps;
        assert!(line.contains(&format!(" steps={steps} ")), "{line}: host took {steps} steps");
        let checksum = host_checksum(speed);
        assert!(
            line.ends_with(&format!("checksum={checksum:08x}")),
            "{line}: the host f32 build's trajectory checksum is {checksum:08x}"
        );
        // The switch events: same steps (f32 times bit-identical), fingers and modes.
        let events: Vec<&String> =
            run.lines.iter().filter(|l| l.starts_with(&format!("{name} event "))).collect();
        assert_eq!(events.len(), host.events().len(), "{name}: {events:#?}");
        for (line, e) in events.iter().zip(host.events()) {
            let field = |key: &str| line.split(' ').find_map(|w| w.strip_prefix(key)).unwrap().to_owned();
            assert_eq!(field("t=").parse::<f32>().unwrap().to_bits(), e.time.to_bits(), "{line} vs {e:?}");
            assert_eq!(field("contact="), (e.contact + 1).to_string(), "{line}");
            assert_eq!(field("mode="), e.mode.name(), "{line}");
        }
        // The rig drove the carriage to finger 1's end position: 0.1 mm per pulse.
        let rig = run.lines.iter().find(|l| l.starts_with(&format!("{name} rig "))).expect("rig line");
        let travel = host.fingers()[0] - (-0.35f32);
        assert!(rig.contains(&format!(" pulses={} ", (travel * 10_000.0).round())), "{rig}: travel {travel}");
    }
}

fn host_run(speed: f32) -> MeterStick6<f32, 32> {
    let params =
        MeterStickParams { finger1_velocity: speed, finger1_x: -0.35, ..MeterStickParams::<f32>::paper() };
    let mut scene = MeterStick6::<f32, 32>::new(params).unwrap();
    scene.run(|_| {});
    scene
}

/// The same f32 6x6 scene on the host, with the firmware's checksum ([`Checksum`]): bit-identical
/// IEEE f32 arithmetic gives the same value.
fn host_checksum(speed: f32) -> u32 {
    let params =
        MeterStickParams { finger1_velocity: speed, finger1_x: -0.35, ..MeterStickParams::<f32>::paper() };
    checksum_of(MeterStick6::<f32, 32>::new(params).unwrap())
}

fn checksum_of<S: Scene<f32, K>, const K: usize>(mut scene: S) -> u32 {
    let mut sum = Checksum::new();
    scene.run(|r| sum.add(&r.state));
    sum.value()
}

/// A scene the firmware runs outside the rig: outcome, steps, checksum and every switch event
/// equal to the host's f32 run of the same scene, built by `make` (the firmware's `N`).
fn check_plain_scene<S: Scene<f32, K>, const K: usize>(run: &FirmwareRun, name: &str, make: impl Fn() -> S) {
    let sum = checksum_of(make());
    let mut scene = make();
    scene.run(|_| {});
    let (outcome, steps) = (scene.outcome().unwrap(), scene.stats().steps);
    let line = run.lines.iter().find(|l| l.starts_with(&format!("{name} outcome="))).expect("scene line");
    assert!(line.starts_with(&format!("{name} outcome={} ", outcome.name())), "{line}: host {outcome:?}");
    assert!(line.contains(&format!(" steps={steps} ")), "{line}: host took {steps} steps");
    assert!(line.ends_with(&format!("checksum={sum:08x}")), "{line}: the host's checksum is {sum:08x}");
    let lines: Vec<&String> = run.lines.iter().filter(|l| l.starts_with(&format!("{name} event "))).collect();
    let events = scene.events();
    assert_eq!(lines.len(), events.len(), "{name}: {lines:#?}");
    for (line, e) in lines.iter().zip(events) {
        let field = |key: &str| line.split(' ').find_map(|w| w.strip_prefix(key)).unwrap().to_owned();
        assert_eq!(field("t=").parse::<f32>().unwrap().to_bits(), e.time.to_bits(), "{line} vs {e:?}");
        assert_eq!(field("contact="), (e.contact + 1).to_string(), "{line}");
        assert_eq!(field("mode="), e.mode.name(), "{line}");
    }
}

/// Every scene but the meter stick, run outside the rig at its defaults, each with the
/// firmware's LCP size (firmware/src/qemu.rs).
fn check_other_scenes(run: &FirmwareRun) {
    check_plain_scene(run, "incline", || Incline::<f32, 6, 32>::new(InclineParams::default()).unwrap());
    check_plain_scene(run, "ladder", || Ladder::<f32, 6, 32>::new(LadderParams::default()).unwrap());
    check_plain_scene(run, "three-fingers", || {
        ThreeFingers::<f32, 9, 32>::new(ThreeFingersParams::default()).unwrap()
    });
    check_plain_scene(run, "cylinder", || Cylinder::<f32, 3, 32>::new(CylinderParams::default()).unwrap());
    check_plain_scene(run, "painleve", || Painleve::<f32, 3, 32>::new(PainleveParams::default()).unwrap());
}

/// The host's f32 run of a scene of several bodies, built by the registry as the firmware builds
/// it: outcome, steps and the checksum of every step's states of all bodies in body order.
struct HostMultibody;

impl MultibodyVisitor for HostMultibody {
    type Output = (Outcome, u64, u32);

    fn visit<T: Real, const B: usize, const P: usize, S: MultibodyScene<T, B, P>>(
        self,
        mut scene: S,
    ) -> Self::Output {
        let mut sum = Checksum::new();
        let mut steps = 0;
        while let Some(report) = scene.step() {
            steps += 1;
            report.add_to(&mut sum);
        }
        (scene.outcome().unwrap(), steps, sum.value())
    }
}

/// The firmware's `<name> outcome=..` and `<name> timing ..` lines of a run: its outcome, steps
/// and checksum the host's, and a timing line for every step.
fn check_run_lines(run: &FirmwareRun, name: &str, outcome: Outcome, steps: u64, sum: u32) {
    let line = run.lines.iter().find(|l| l.starts_with(&format!("{name} outcome="))).expect("scene line");
    assert!(line.starts_with(&format!("{name} outcome={} ", outcome.name())), "{line}: host {outcome:?}");
    assert!(line.contains(&format!(" steps={steps} ")), "{line}: host took {steps} steps");
    assert!(line.ends_with(&format!("checksum={sum:08x}")), "{line}: the host's checksum is {sum:08x}");
    let timing = run.lines.iter().find(|l| l.starts_with(&format!("{name} timing "))).expect("timing line");
    assert!(timing.ends_with(&format!(" steps={steps}")), "{timing}: host took {steps} steps");
}

/// Block-on-block, the 3-block stack and disc-on-board at their defaults, and the tablecloth at
/// `mu = 2` (firmware/src/qemu.rs, `qemu-multibody`):
/// the outcome physics says (`docs/scenes.md`), and outcome, steps and checksum equal to the
/// host's f32 run (bit-identical IEEE f32 arithmetic); a timing line for every step.
fn check_multibody_scenes(run: &FirmwareRun) {
    for (kind, expected) in [
        (SceneKind::BlockOnBlock, Outcome::Slid),
        (SceneKind::Stack, Outcome::Held),
        (SceneKind::DiscOnBoard, Outcome::Rolled),
    ] {
        let (outcome, steps, sum) =
            SceneParams::defaults(kind).build_multibody(Precision::F32, HostMultibody).unwrap();
        assert_eq!(outcome, expected, "{kind} on the host");
        check_run_lines(run, kind.name(), outcome, steps, sum);
    }
    // The tablecloth at `mu = 2`, whose flagged steps are timed apart.
    let params =
        SceneParams::Tablecloth(TableclothParams { mu_static: 2.0, mu_kinetic: 2.0, ..Default::default() });
    let (outcome, steps, sum) = params.build_multibody(Precision::F32, HostMultibody).unwrap();
    assert_eq!(outcome, Outcome::Stayed, "tablecloth-mu2 on the host");
    let line = run.lines.iter().find(|l| l.starts_with("tablecloth-mu2 outcome=")).expect("scene line");
    assert!(line.contains(&format!(" steps={steps} ")), "{line}: host took {steps} steps");
    assert!(line.ends_with(&format!("checksum={sum:08x}")), "{line}: the host's checksum is {sum:08x}");
    let flagged = run
        .lines
        .iter()
        .find(|l| l.starts_with("tablecloth-mu2-flagged timing "))
        .expect("flagged timing line");
    assert!(!flagged.ends_with(" steps=0"), "{flagged}: no step flagged");
    // Every run's steps by path sum to its steps; the runs meant to fail fail as the host's f32 run
    // does, at the same step, timed under `path=failed`.
    for (name, failing) in ["block-on-block", "stack", "disc-on-board", "tablecloth-mu2"]
        .map(|n| (n, None))
        .into_iter()
        .chain([("failing-heavy-top", Some((1e6, 1.0, 0.45))), ("failing-light-top", Some((1.0, 1e12, 2.9)))])
    {
        let line = run.lines.iter().find(|l| l.starts_with(&format!("{name} outcome="))).expect("scene line");
        let count = |path: &str| -> u64 {
            let prefix = format!("{name} path={path} steps=");
            let l =
                run.lines.iter().find(|l| l.starts_with(&prefix)).unwrap_or_else(|| panic!("no {prefix}"));
            l[prefix.len()..].split(' ').next().unwrap().parse().unwrap()
        };
        let answered: u64 = ["free", "warm", "candidate", "lemke"].map(count).iter().sum();
        assert!(line.contains(&format!(" steps={answered} ")), "{line}: the paths answered {answered}");
        let Some((top, bottom, k)) = failing else {
            assert_eq!(count("failed"), 0, "{name}");
            continue;
        };
        let params = SceneParams::BlockOnBlock(BlockOnBlockParams {
            top_mass: top,
            bottom_mass: bottom,
            force: k * (top + bottom) * 9.81,
            ..Default::default()
        });
        let (outcome, host_steps, _) = params.build_multibody(Precision::F32, HostMultibody).unwrap();
        assert!(matches!(outcome, Outcome::Failed(_)), "{name} on the host: {outcome:?}");
        assert!(line.starts_with(&format!("{name} outcome=Failed(")), "{line}");
        assert_eq!((answered, count("failed")), (host_steps, 1), "{line}: host took {host_steps} steps");
    }
}

/// The stack rig (firmware/src/qemu.rs, `qemu-multibody`: `StackRig` on headless pins): held for
/// 0.2 s at the default overhang with every interface sticking, falling at 1.02 with every one
/// tipping; outcome, steps and checksum equal to the host's f32 run of the same stack (the rig
/// steps the scene and nothing else), and a timing line for every step.
fn check_stack_rig(run: &FirmwareRun) {
    for (name, params, expected, shown) in [
        (
            "stack-rig-held",
            StackParams { max_time: 0.2, ..StackParams::default() },
            Outcome::Held,
            "sticking",
        ),
        (
            "stack-rig-fell",
            StackParams { overhang: 1.02, ..StackParams::default() },
            Outcome::Fell,
            "tipping",
        ),
    ] {
        let (outcome, steps, sum) = HostMultibody.visit(Stack3::<f32>::new(params).unwrap());
        assert_eq!(outcome, expected, "{name} on the host");
        let line = run.lines.iter().find(|l| l.starts_with(&format!("{name} outcome="))).expect("rig line");
        assert!(line.starts_with(&format!("{name} outcome={} ", outcome.name())), "{line}: host {outcome:?}");
        assert!(line.contains(&format!(" steps={steps} ")), "{line}: host took {steps} steps");
        assert!(line.ends_with(&format!("checksum={sum:08x}")), "{line}: the host's checksum is {sum:08x}");
        for i in 0..3 {
            let want = format!("{name} interface={i} shown={shown}");
            assert!(run.lines.contains(&want), "no line {want:?}");
        }
        let timing = run.lines.iter().find(|l| l.starts_with(&format!("{name} rig "))).expect("timing line");
        assert!(timing.ends_with(&format!(" steps={steps}")), "{timing}: host took {steps} steps");
    }
}

/// The host's f32 run of a scene through the registry's view, as the spatial firmware runs it:
/// outcome, steps and the view's checksum.
struct HostView;

impl ViewVisitor for HostView {
    type Output = (Outcome, u64, u32);

    fn visit<T: Real>(self, view: &mut dyn SceneView<T>) -> Self::Output {
        let mut steps = 0;
        while view.step() {
            steps += 1;
        }
        (view.outcome().unwrap(), steps, view.checksum())
    }
}

/// The puck, the billiard ball, the curling stone and the meter stick in three dimensions at their
/// defaults (firmware/src/qemu.rs, `qemu-spatial`): the outcome physics says (the puck and the
/// stone stop, the ball rolls, the rod balances: `docs/scenes.md`), and outcome, steps
/// and checksum equal to the host's f32 run (bit-identical IEEE f32 arithmetic); a timing line
/// for every step.
fn check_spatial_scenes(run: &FirmwareRun) {
    for (kind, expected) in [
        (SceneKind::Puck, Outcome::Stopped),
        (SceneKind::Billiard, Outcome::Rolled),
        (SceneKind::Curling, Outcome::Stopped),
        (SceneKind::MeterStick3d, Outcome::Balanced),
    ] {
        let (outcome, steps, sum) = SceneParams::defaults(kind)
            .build_view::<0, _>(Precision::F32, LcpLayout::Reduced, HostView)
            .unwrap();
        assert_eq!(outcome, expected, "{kind} on the host");
        check_run_lines(run, kind.name(), outcome, steps, sum);
    }
}

/// The spatial builds: the scenes of one body as every build runs them, and the puck and the
/// billiard ball (the Cortex-M4F and the Cortex-M33F).
#[test]
#[ignore = "needs the cross-built firmware and qemu-system-arm: run scripts/test.sh"]
fn spatial_scenes_on_the_m4f_and_the_m33f() {
    for (var, machine) in
        [("MS_FIRMWARE_M4_SPATIAL", Machine::Mps2An386), ("MS_FIRMWARE_M33_SPATIAL", Machine::Mps2An505)]
    {
        let run = run(var, machine);
        check_common(&run);
        check_other_scenes(&run);
        check_spatial_scenes(&run);
    }
}

#[test]
#[ignore = "needs the cross-built firmware and qemu-system-arm: run scripts/test.sh"]
fn cortex_m4f_on_mps2_an386() {
    let run = run("MS_FIRMWARE_M4", Machine::Mps2An386);
    check_common(&run);
    check_other_scenes(&run);
    check_multibody_scenes(&run);
    check_stack_rig(&run);
}

/// The Cortex-M33 with FPU (the Raspberry Pi Pico 2's core, `thumbv8m.main-none-eabihf`) on
/// QEMU's mps2-an505, in Secure state: the same checksums and events as the host.
#[test]
#[ignore = "needs the cross-built firmware and qemu-system-arm: run scripts/test.sh"]
fn cortex_m33_on_mps2_an505() {
    let run = run("MS_FIRMWARE_M33", Machine::Mps2An505);
    check_common(&run);
    check_other_scenes(&run);
    check_multibody_scenes(&run);
    check_stack_rig(&run);
}

#[test]
#[ignore = "needs the cross-built firmware and qemu-system-arm: run scripts/test.sh"]
fn cortex_m0_on_microbit() {
    let run = run("MS_FIRMWARE_M0", Machine::Microbit);
    check_common(&run);
    check_other_scenes(&run);
}

/// The instruction-count method: under `-icount shift=0` the firmware's SysTick calibration
/// (a loop of 2,000,002 instructions) reads 1e9 / f_SysTick instructions per tick:
/// 40 on mps2-an386 (25 MHz), 62.5 on the micro:bit (16 MHz), 50 on mps2-an505 (20 MHz).
/// Deterministic: two runs agree.
#[test]
#[ignore = "needs the cross-built firmware and qemu-system-arm: run scripts/test.sh"]
fn icount_calibration_is_exact_and_deterministic() {
    for (var, machine, per_tick) in [
        ("MS_FIRMWARE_M4", Machine::Mps2An386, 40.0),
        ("MS_FIRMWARE_M0", Machine::Microbit, 62.5),
        ("MS_FIRMWARE_M33", Machine::Mps2An505, 50.0),
    ] {
        let elf = PathBuf::from(
            std::env::var(var).unwrap_or_else(|_| panic!("{var} is not set: run scripts/test.sh")),
        );
        let runs: Vec<FirmwareRun> = (0..2)
            .map(|_| qemu::run(&elf, machine, Duration::from_secs(120), true).expect("QEMU run"))
            .collect();
        let cal = |r: &FirmwareRun| r.lines.iter().find(|l| l.starts_with("calibration ")).unwrap().clone();
        let line = cal(&runs[0]);
        assert_eq!(line, cal(&runs[1]), "icount runs differ");
        let nums: Vec<f64> =
            line.split(' ').filter_map(|w| w.split_once('=')).map(|(_, v)| v.parse().unwrap()).collect();
        // Exact up to the few instructions around the loop (reading SysTick, the call).
        let measured = nums[0] / nums[1];
        assert!((measured / per_tick - 1.0).abs() < 1e-4, "{line}: {measured} instructions per tick");
        let rig = |r: &FirmwareRun| r.lines.iter().find(|l| l.starts_with("slow rig ")).unwrap().clone();
        assert_eq!(rig(&runs[0]), rig(&runs[1]), "the slow scene's tick count is not deterministic");
    }
}
