//! The Pico without a board (#23): the Pico firmware's `.uf2` (path in `MS_PICO_UF2`; a
//! `builtins-float` build, `scripts/lib.sh`) runs on an emulated RP2040 (`tests/pico/harness.mjs`
//! on rp2040js, `node_modules` installed by `scripts/setup.sh`), its buttons pressed as a teacher
//! presses them; what its pins did is checked against the host core running the same rig
//! (`meterstick_rig::MeterStickRig` on recording pins, the same preset, the same `RigConfig`):
//!
//! - the run: the same number of scene steps, ended the same way (balanced / fault);
//! - STEP: the same pulses in every tick (the first differing step is named), in all
//!   `round(finger travel x steps_per_meter)`, every pulse high and low for at least `pulse_ns`;
//! - DIR, the lights and the fault light: the same edges in the same ticks (the first difference
//!   is named by pin and step); each light change at a switch event of the scene, in order;
//!   exactly one light per finger while running; the fault light off (the fast preset, which the
//!   rig's carriage cannot perform, is refused and the preset button skips it);
//! - the tick: SysTick's period `h` x 125 MHz, each tick's work measured in cycles (printed:
//!   cycles per step, mean and worst, against the period).
//!
//! With the host link (`MS_PICO_LINK_UF2`, the build tagged `emu-link`): the harness bridges
//! UART0 to a TCP port and the link's checks of the QEMU test (`link_checks/`, as for
//! `qemu_link.rs`: handshake, refusals, a run bit for bit against the host, garbage and a flood,
//! stop on command) run against the emulated Pico.
//!
//! The meter stick in three dimensions (`MS_PICO_3D_UF2`, the build tagged `emu-3d`,
//! `rig-stick-3d`): its first steps' STEP pulses and edges against the host's rig of the same
//! scene, and its cycles a step (it needs several 1 ms periods a step on the RP2040: the rig runs
//! late, a step per tick, and counts the overruns).
//!
//! `scripts/pico-emu.sh` runs them (`--test-threads=1`); ignored in a plain `cargo test`.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, clippy::cast_possible_truncation)]

mod link_checks;

use std::cell::RefCell;
use std::collections::BTreeMap;
use std::convert::Infallible;
use std::path::PathBuf;
use std::process::{Child, Command, Stdio};
use std::rc::Rc;
use std::time::{Duration, Instant};

use embedded_hal::digital::{ErrorType, InputPin, OutputPin};
use meterstick_core::planar::ContactMode;
use meterstick_core::scene::spatial::{MeterStick3d, MeterStick3dParams};
use meterstick_core::scene::{MeterStick6, MeterStickParams, Outcome, Scene};
use meterstick_link::OutcomeCode;
use meterstick_link::host::Link;
use meterstick_rig::{
    Carriage, MeterStickRig, ModeLights, NoDelay, Preset, PresetScene as _, Rig, RigConfig, RigFault,
    RigPins, RigState,
};
use serde_json::Value;

/// The firmware's step at boot: `STEP_HZ` = 1 kHz (firmware/src/realtime.rs, `new_rig`).
const H: f32 = 1.0 / 1000.0;
/// The Pico's core clock (firmware/src/pico.rs), at which the harness counts cycles.
const CORE_HZ: f64 = 125e6;
/// The wiring (firmware/src/pico.rs): STEP, DIR, fault, and each finger's sticking / sliding /
/// separated lights.
const STEP: u8 = 2;
const DIR: u8 = 3;
const FAULT: u8 = 25;
const LIGHTS: [[u8; 3]; 2] = [[6, 7, 8], [9, 10, 11]];
/// The stack's block 2 / block 3 interface lights (the link build's: sticking / sliding /
/// separated).
const STACK_LIGHTS: [u8; 3] = [16, 17, 18];

fn pin_name(pin: u8) -> String {
    for (f, pins) in LIGHTS.iter().enumerate() {
        if let Some(i) = pins.iter().position(|&p| p == pin) {
            return format!("GP{pin} (finger {} {})", f + 1, ["sticking", "sliding", "separated"][i]);
        }
    }
    match pin {
        STEP => "GP2 (STEP)".into(),
        DIR => "GP3 (DIR)".into(),
        FAULT => "GP25 (fault)".into(),
        _ => format!("GP{pin}"),
    }
}

/// What the host rig's pins did: edges (tick, pin, level) of every pin but STEP, and STEP's
/// rises per tick. Tick 0 is the start; tick k is the k-th scene step.
#[derive(Default)]
struct Record {
    tick: i64,
    levels: BTreeMap<u8, bool>,
    edges: Vec<(i64, u8, bool)>,
    rises: BTreeMap<i64, u64>,
}

#[derive(Clone)]
struct RecPin(u8, Rc<RefCell<Record>>);

impl ErrorType for RecPin {
    type Error = Infallible;
}

impl OutputPin for RecPin {
    fn set_low(&mut self) -> Result<(), Infallible> {
        self.set(false);
        Ok(())
    }
    fn set_high(&mut self) -> Result<(), Infallible> {
        self.set(true);
        Ok(())
    }
}

impl RecPin {
    fn set(&self, high: bool) {
        let mut r = self.1.borrow_mut();
        let was = r.levels.insert(self.0, high).unwrap_or(false);
        if was == high {
            return;
        }
        let tick = r.tick;
        if self.0 == STEP {
            if high {
                *r.rises.entry(tick).or_default() += 1;
            }
        } else {
            r.edges.push((tick, self.0, high));
        }
    }
}

/// The start button, never read pressed: the host run is started with `Rig::start`.
struct Released;

impl ErrorType for Released {
    type Error = Infallible;
}

impl InputPin for Released {
    fn is_high(&mut self) -> Result<bool, Infallible> {
        Ok(true)
    }
    fn is_low(&mut self) -> Result<bool, Infallible> {
        Ok(false)
    }
}

/// The host core's run of the rig after `presses` presses of the preset button: as the
/// firmware does (firmware/src/realtime.rs: `new_rig`, then per press `reset` and `indicate`),
/// then the start and a tick per step until the run ends.
struct HostRun {
    /// The preset loaded (a preset the rig refuses is skipped, as the firmware's button does).
    preset: Preset,
    params: MeterStickParams<f32>,
    config: RigConfig,
    state: RigState,
    /// Ticks that stepped the scene (the last one is the run's last step).
    steps: u64,
    last_step_tick: i64,
    pulses: i64,
    travel: f32,
    record: Record,
}

/// The rig's pins and carriage as the Pico wires them (firmware/src/pico.rs), recording into `rec`.
fn recording_rig(rec: &Rc<RefCell<Record>>) -> (RigPins<Released, RecPin, 2>, Carriage<RecPin, NoDelay>) {
    let pin = |p: u8| RecPin(p, rec.clone());
    let lights = |f: usize| ModeLights {
        sticking: pin(LIGHTS[f][0]),
        sliding: pin(LIGHTS[f][1]),
        separated: pin(LIGHTS[f][2]),
    };
    let carriage = Carriage::new(pin(STEP), pin(DIR), NoDelay);
    (RigPins { start: Released, lights: [lights(0), lights(1)], fault: pin(FAULT) }, carriage)
}

fn host_run(presses: usize) -> HostRun {
    let rec = Rc::new(RefCell::new(Record { tick: -1, ..Record::default() }));
    let (pins, carriage) = recording_rig(&rec);
    let config = RigConfig::default_rig();
    let mut rig = MeterStickRig::<_, _, _, 6>::new(Preset::Slow.params(H), config, pins, carriage).unwrap();
    let mut preset = Preset::Slow;
    for _ in 0..presses {
        // As the firmware's preset button (firmware/src/realtime.rs, `Buttons::between_runs`): the
        // next preset the rig can perform.
        let mut next = preset;
        for _ in 0..Preset::ALL.len() {
            next = next.next();
            if rig.reset(next.params(H)).is_ok() {
                preset = next;
                rig.indicate(Some(next.index())).unwrap();
                break;
            }
        }
    }
    let params = *rig.params();
    rec.borrow_mut().tick = 0;
    assert!(rig.start().unwrap(), "the host rig did not start");
    let (mut steps, mut last_step_tick) = (0u64, 0i64);
    let mut tick = 0i64;
    let state = loop {
        tick += 1;
        assert!(tick < 1_000_000, "the host run does not end");
        rec.borrow_mut().tick = tick;
        let mut stepped = false;
        let s = rig.tick_with(|_| stepped = true).unwrap();
        if stepped {
            steps += 1;
            last_step_tick = tick;
        }
        if !matches!(s, RigState::Running) {
            break s;
        }
    };
    let travel = rig.scene().fingers()[0] - params.finger1_x;
    let pulses = rig.pulses();
    drop(rig);
    let record = Rc::try_unwrap(rec).ok().unwrap().into_inner();
    HostRun { preset, params, config, state, steps, last_step_tick, pulses, travel, record }
}

const fn light_index(m: ContactMode) -> u8 {
    match m {
        ContactMode::Sticking => 0,
        ContactMode::Sliding(_) => 1,
        ContactMode::Separated => 2,
    }
}

/// The scene's light changes: from its switch events (a scene with room for all of them), per
/// step `round(t / h)` each finger's light class after the step where it differs from before:
/// (step, finger, class), in order.
fn light_changes_from_events(params: MeterStickParams<f32>) -> Vec<(i64, usize, u8)> {
    let mut scene = MeterStick6::<f32, 256>::new(params).unwrap();
    let mut class = scene.modes().map(light_index);
    while scene.step().is_some() {}
    assert_eq!(scene.events_dropped(), 0, "the event buffer is too small");
    let mut by_step: BTreeMap<i64, [Option<u8>; 2]> = BTreeMap::new();
    for e in scene.events() {
        let k = (e.time / params.step).round() as i64;
        by_step.entry(k).or_default()[usize::from(e.contact)] = Some(light_index(e.mode));
    }
    let mut out = Vec::new();
    for (k, new) in by_step {
        for f in 0..2 {
            if let Some(c) = new[f]
                && c != class[f]
            {
                class[f] = c;
                out.push((k, f, c));
            }
        }
    }
    out
}

fn harness(presses: usize, max_ticks: u64) -> Value {
    harness_with(presses, max_ticks, &[])
}

/// [`harness`] with more of the harness's options (`tests/pico/harness.mjs`).
fn harness_with(presses: usize, max_ticks: u64, options: &[&str]) -> Value {
    harness_of("MS_PICO_UF2", presses, (max_ticks as f64 * f64::from(H) * CORE_HZ).ceil(), options)
}

/// The harness on the `.uf2` named by the environment variable `uf2_var`, stopped after at most
/// `max_cycles`; its JSON kept in `target/pico-emu/`.
fn harness_of(uf2_var: &str, presses: usize, max_cycles: f64, options: &[&str]) -> Value {
    let uf2 =
        std::env::var(uf2_var).unwrap_or_else(|_| panic!("{uf2_var} is not set: run scripts/pico-emu.sh"));
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
    let script = root.join("tests/pico/harness.mjs");
    let out = Command::new("node")
        .arg(&script)
        .args(["--uf2", &uf2, "--presets", &presses.to_string(), "--max-cycles", &max_cycles.to_string()])
        .args(["--wall-s", "150"])
        .args(options)
        .output()
        .expect("running node");
    assert!(
        out.status.success(),
        "the harness failed ({}): {}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    let v: Value = serde_json::from_slice(&out.stdout).expect("the harness printed one JSON object");
    let dir = root.join("target/pico-emu");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join(format!("{uf2_var}-presets{presses}.json")), &out.stdout).unwrap();
    v
}

/// The firmware touched nothing the emulator does not model (rp2040js's warnings and errors,
/// counted by the harness).
fn nothing_unmodelled(name: &str, emu: &Value) {
    let logged = &emu["emulated"]["logged"];
    assert!(
        logged["warn"] == 0 && logged["error"] == 0,
        "{name}: the firmware used what rp2040js does not model: {logged}"
    );
}

fn int(v: &Value, what: &str) -> i64 {
    v.as_i64().unwrap_or_else(|| panic!("{what}: {v} is not an integer"))
}

/// Runs preset `presses` on the emulated Pico and checks it against the host core; returns the
/// harness's result.
fn check(presses: usize) -> (Value, HostRun) {
    let host = host_run(presses);
    // Enough ticks for the button script, the run and the idle ticks after it; the harness
    // stops by itself once the run has ended.
    let max_ticks = 500 + 100 * presses as u64 + host.last_step_tick as u64;
    let emu = harness(presses, max_ticks);
    let name = format!("{:?} (preset button pressed {presses}x)", host.preset);

    // The tick: SysTick reloads every h on the 125 MHz core clock, the loop sees every wrap.
    // (rp2040js 1.4.1 wraps SysTick every RVR cycles where the Cortex-M0+ takes RVR + 1: its
    // mean interval is 124,999 cycles, hence the tolerance of 2 cycles.)
    let period = (f64::from(H) * CORE_HZ).round() as i64;
    assert_eq!(int(&emu["ticks"]["systick_period_cycles"], "period"), period, "{name}: SysTick period");
    let mean = emu["ticks"]["interval_cycles"]["mean"].as_f64().unwrap();
    assert!((mean - period as f64).abs() <= 2.0, "{name}: mean tick interval {mean} cycles, not {period}");

    nothing_unmodelled(&name, &emu);
    let start = int(&emu["run"]["start_tick"], "start tick (DIR high)");
    let expect_end = match host.state {
        RigState::Fault(_) => "fault",
        _ => "run-ended",
    };
    assert_eq!(
        emu["stopped"], expect_end,
        "{name}: the emulated run stopped as {}, the host's {:?}",
        emu["stopped"], host.state
    );

    check_step(&name, &emu, &host, start);
    let edges = check_edges(&name, &emu, &host, start);
    if let RigState::Finished(_) = host.state {
        check_lights(&name, &emu, &host, &edges);
    }
    print_figures(&name, &emu, &host, period);
    (emu, host)
}

/// The run's steps and STEP: every tick's pulses, the total, the finger travel, the widths.
fn check_step(name: &str, emu: &Value, host: &HostRun, start: i64) {
    let rel = |t: &Value| int(t, "tick") - start;
    let last = if host.state == RigState::Fault(RigFault::ActuatorOverrun) {
        rel(&emu["run"]["fault_tick"])
    } else {
        rel(&emu["run"]["last_step_tick"])
    };
    assert_eq!(
        last, host.last_step_tick,
        "{name}: the run's last step is tick {last} on the Pico, {} on the host",
        host.last_step_tick
    );

    // STEP: every tick's pulses, the total, the finger travel.
    let rises = emu["step"]["rises_per_tick"].as_array().unwrap();
    assert_eq!(
        i64::try_from(rises.len()).unwrap(),
        host.last_step_tick + 1,
        "{name}: STEP recorded for {} ticks",
        rises.len()
    );
    for (k, r) in rises.iter().enumerate() {
        let want = host.record.rises.get(&i64::try_from(k).unwrap()).copied().unwrap_or(0);
        assert_eq!(
            int(r, "rises") as u64,
            want,
            "{name}: GP2 (STEP) pulses in step {k}: Pico {r}, host {want}"
        );
    }
    let pulses = int(&emu["step"]["pulses_dir_high"], "pulses");
    assert_eq!(int(&emu["step"]["pulses_dir_low"], "pulses"), 0, "{name}: GP2 (STEP) pulsed with DIR low");
    assert_eq!(pulses, host.pulses, "{name}: GP2 (STEP) pulses: Pico {pulses}, host rig {}", host.pulses);
    if let RigState::Finished(_) = host.state {
        // A finished run's carriage is where the finger is (a fault stops it short).
        let from_travel = (host.travel * host.config.steps_per_meter).round() as i64;
        assert_eq!(
            pulses, from_travel,
            "{name}: {pulses} pulses for {} m at {} steps/m",
            host.travel, host.config.steps_per_meter
        );
    }
    if pulses > 0 {
        for k in ["min_high_ns", "min_low_ns"] {
            let w = int(&emu["step"][k], k);
            assert!(
                w >= i64::from(host.config.pulse_ns),
                "{name}: GP2 (STEP) {k} {w} < pulse_ns {}",
                host.config.pulse_ns
            );
        }
    }
}

/// Edges of DIR, the lights and the fault light from the start to the end of the run, and none
/// after it, against the host's; returns the Pico's (step, pin, level) from the start.
fn check_edges(name: &str, emu: &Value, host: &HostRun, start: i64) -> Vec<(i64, u8, bool)> {
    let rel = |t: &Value| int(t, "tick") - start;
    let emu_edges: Vec<(i64, u8, bool)> = emu["edges"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| (rel(&e["tick"]), int(&e["pin"], "pin") as u8, int(&e["level"], "level") == 1))
        .filter(|e| e.0 >= 0)
        .collect();
    let host_edges: Vec<(i64, u8, bool)> = host.record.edges.iter().copied().filter(|e| e.0 >= 0).collect();
    for (i, (a, b)) in emu_edges.iter().zip(&host_edges).enumerate() {
        assert_eq!(
            a,
            b,
            "{name}: edge {i}: Pico {} {} in step {}, host {} {} in step {}",
            pin_name(a.1),
            if a.2 { "high" } else { "low" },
            a.0,
            pin_name(b.1),
            if b.2 { "high" } else { "low" },
            b.0
        );
    }
    assert_eq!(
        emu_edges.len(),
        host_edges.len(),
        "{name}: {} edges on the Pico, {} on the host (first extra: {:?})",
        emu_edges.len(),
        host_edges.len(),
        emu_edges.get(host_edges.len()).or(host_edges.get(emu_edges.len()))
    );

    emu_edges
}

/// The lights of a finished run against the scene's switch events, in order; one light per
/// finger while running; the fault light off, DIR high.
fn check_lights(name: &str, emu: &Value, host: &HostRun, emu_edges: &[(i64, u8, bool)]) {
    {
        let want = light_changes_from_events(host.params);
        let got: Vec<(i64, usize, u8)> = emu_edges
            .iter()
            .filter(|e| e.0 > 0 && e.2)
            .filter_map(|e| {
                LIGHTS
                    .iter()
                    .enumerate()
                    .find_map(|(f, pins)| pins.iter().position(|&p| p == e.1).map(|c| (e.0, f, c as u8)))
            })
            .collect();
        assert!(!want.is_empty(), "{name}: the scene has no switch event to check the lights against");
        for (i, (g, w)) in got.iter().zip(&want).enumerate() {
            assert_eq!(
                g, w,
                "{name}: light change {i}: Pico (step, finger, light) {g:?}, the scene's events {w:?}"
            );
        }
        assert_eq!(
            got.len(),
            want.len(),
            "{name}: {} light changes on the Pico, {} switches in the scene",
            got.len(),
            want.len()
        );
        assert_eq!(
            emu["lights_on_per_finger_while_running"],
            serde_json::json!([[1], [1]]),
            "{name}: not exactly one light per finger while running"
        );
        assert_eq!(emu["fault_level"], 0, "{name}: GP25 (fault) is on");
        assert_eq!(emu["dir_level"], 1, "{name}: GP3 (DIR) is low at the end of the run");
    }
}

/// The measured figures, on stdout (`--nocapture`).
fn print_figures(name: &str, emu: &Value, host: &HostRun, period: i64) {
    let w = &emu["run"]["cycles_per_step"];
    let pulses = &emu["step"]["pulses_dir_high"];
    println!(
        "{name}: {} steps, outcome {:?}, {pulses} pulses (min high {} ns, low {} ns), tick {} cycles (jitter {} cycles); \
         cycles per step mean {:.0}, worst {} of {period} ({:.1}%); {:.1} s emulated in {:.1} s ({:.0} Mcycles/s)",
        host.steps,
        host.state,
        emu["step"]["min_high_ns"],
        emu["step"]["min_low_ns"],
        emu["ticks"]["systick_period_cycles"],
        emu["ticks"]["jitter_cycles"],
        w["mean"].as_f64().unwrap_or(f64::NAN),
        w["max"],
        100.0 * w["max"].as_f64().unwrap_or(f64::NAN) / period as f64,
        emu["emulated"]["seconds_at_125mhz"].as_f64().unwrap(),
        emu["emulated"]["wall_s"].as_f64().unwrap(),
        emu["emulated"]["mcycles_per_wall_s"].as_f64().unwrap(),
    );
}

/// One press of the preset button: the fast preset (5 m/s) asks for more pulses in a tick than
/// the default rig's carriage can give (400 against 100), so the rig refuses it and the button
/// skips it (the lights show the preset loaded); the next is near the fall threshold (0.3 m/s),
/// the short balanced run.
#[test]
#[ignore = "needs node, tests/pico/node_modules and MS_PICO_UF2 (scripts/pico-emu.sh)"]
fn the_fast_preset_is_skipped_and_near_threshold_runs_as_on_the_host() {
    let (emu, host) = check(1);
    assert_eq!(host.preset, Preset::NearThreshold, "the host rig did not skip the fast preset");
    assert_eq!(host.state, RigState::Finished(Outcome::Balanced));
    assert_eq!(emu["fault_level"], 0, "GP25 (fault) is on");
}

/// The boot preset (slow, 0.1 m/s, 7.9 s): the paper's slow finger.
#[test]
#[ignore = "needs node, tests/pico/node_modules and MS_PICO_UF2 (scripts/pico-emu.sh); 7.9 s emulated"]
fn slow_preset_runs_as_on_the_host() {
    let (_, host) = check(0);
    assert_eq!(host.state, RigState::Finished(Outcome::Balanced));
}

/// The steps of the meter stick in three dimensions the emulated Pico runs: its first 0.3 s (the
/// pad slides from its first step, finger 2 sticks), about 250 M emulated cycles.
const STEPS_3D: i64 = 300;

/// The meter stick in three dimensions (`rig-stick-3d`) at its boot heading (0): the emulated
/// Pico's first [`STEPS_3D`] steps pulse STEP and switch the lights in the same steps as the host
/// core's rig of the same scene; its cycles a step are printed against the 1 ms period.
#[test]
#[ignore = "needs node, tests/pico/node_modules and MS_PICO_3D_UF2 (scripts/pico-emu.sh)"]
fn the_meter_stick_in_three_dimensions_runs_as_on_the_host() {
    let rec = Rc::new(RefCell::new(Record { tick: -1, ..Record::default() }));
    let (pins, carriage) = recording_rig(&rec);
    // As firmware/src/realtime_stick_3d.rs's `new_rig`: the catalogue's scene at h = 1 ms.
    let params = MeterStick3dParams { step: H, ..MeterStick3dParams::default() };
    let mut rig: Rig<MeterStick3d<f32>, _, _, _, 2> =
        Rig::new(params, RigConfig::default_rig(), pins, carriage).unwrap();
    rec.borrow_mut().tick = 0;
    assert!(rig.start().unwrap(), "the host rig did not start");
    for tick in 1..=STEPS_3D + 1 {
        rec.borrow_mut().tick = tick;
        assert_eq!(rig.tick().unwrap(), RigState::Running, "the host run ended at step {tick}");
    }
    drop(rig);
    let host = Rc::try_unwrap(rec).ok().unwrap().into_inner();

    // The boot and the start button take about 70 ticks of 125,000 cycles; a step about 0.9 M.
    let emu = harness_of("MS_PICO_3D_UF2", 0, 2e7 + 0.9e6 * STEPS_3D as f64, &[]);
    let name = "the meter stick in three dimensions";
    nothing_unmodelled(name, &emu);
    assert_eq!(emu["fault_level"], 0, "{name}: GP25 (fault) is on");
    let start = int(&emu["run"]["start_tick"], "start tick (DIR high)");
    let rises = emu["step"]["rises_per_tick"].as_array().unwrap();
    // The cycle cap stops the run inside a step: the steps before it are whole (and the host ran
    // STEPS_3D + 1).
    let whole = (i64::try_from(rises.len()).unwrap() - 1).min(STEPS_3D + 1);
    assert!(whole >= STEPS_3D * 9 / 10, "{name}: only {whole} steps ran within the cycle cap");
    for (k, r) in rises.iter().enumerate().take(usize::try_from(whole).unwrap()) {
        let want = host.rises.get(&i64::try_from(k).unwrap()).copied().unwrap_or(0);
        assert_eq!(
            int(r, "rises") as u64,
            want,
            "{name}: GP2 (STEP) pulses in step {k}: Pico {r}, host {want}"
        );
    }
    let emu_edges: Vec<(i64, u8, bool)> = emu["edges"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| {
            (int(&e["tick"], "tick") - start, int(&e["pin"], "pin") as u8, int(&e["level"], "level") == 1)
        })
        .filter(|e| e.0 >= 0 && e.0 < whole)
        .collect();
    let host_edges: Vec<(i64, u8, bool)> =
        host.edges.iter().copied().filter(|e| e.0 >= 0 && e.0 < whole).collect();
    assert!(!host_edges.is_empty(), "{name}: the host's rig switched no light");
    assert_eq!(emu_edges, host_edges, "{name}: the edges (step, pin, high) differ");
    let w = &emu["run"]["cycles_per_step"];
    let period = (f64::from(H) * CORE_HZ).round();
    println!(
        "{name}: {whole} steps as on the host; cycles per step mean {:.0}, worst {} against the {period} of \
         h = 1 ms ({:.1} periods a step at the worst)",
        w["mean"].as_f64().unwrap_or(f64::NAN),
        w["max"],
        w["max"].as_f64().unwrap_or(f64::NAN) / period,
    );
}

/// The harness, killed if the test fails before it ends.
struct Harness(Option<Child>);

impl Drop for Harness {
    fn drop(&mut self) {
        if let Some(mut c) = self.0.take() {
            c.kill().ok();
            c.wait().ok();
        }
    }
}

/// The host link over the emulated UART0: the QEMU link test's checks (`link_checks/`).
#[test]
#[ignore = "needs node, tests/pico/node_modules and MS_PICO_LINK_UF2 (scripts/pico-emu.sh)"]
fn link_end_to_end_on_the_emulated_pico() {
    let uf2 = std::env::var("MS_PICO_LINK_UF2")
        .unwrap_or_else(|_| panic!("MS_PICO_LINK_UF2 is not set: run scripts/pico-emu.sh"));
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
    let dir = root.join("target/pico-emu");
    std::fs::create_dir_all(&dir).unwrap();
    let port_file = dir.join("link-port.json");
    std::fs::remove_file(&port_file).ok();
    let started = Instant::now();
    // At most 60 emulated seconds and 240 s of wall time: the checks take about 12 s emulated.
    let mut harness = Harness(Some(
        Command::new("node")
            .arg(root.join("tests/pico/harness.mjs"))
            .args(["--uf2", &uf2, "--uart-tcp", "0", "--max-cycles", "7.5e9", "--wall-s", "240"])
            .arg("--port-file")
            .arg(&port_file)
            .stdout(Stdio::piped())
            .spawn()
            .expect("running node"),
    ));
    let deadline = Instant::now() + Duration::from_secs(30);
    let port = loop {
        if let Ok(text) = std::fs::read_to_string(&port_file)
            && let Ok(v) = serde_json::from_str::<Value>(&text)
        {
            break u16::try_from(int(&v["port"], "port")).unwrap();
        }
        let exited = harness.0.as_mut().unwrap().try_wait().unwrap();
        assert!(exited.is_none(), "the harness ended ({exited:?}) before it listened");
        assert!(Instant::now() < deadline, "the harness did not listen within 30 s");
        std::thread::sleep(Duration::from_millis(50));
    };
    let stream = std::net::TcpStream::connect(("127.0.0.1", port)).unwrap();
    let closer = stream.try_clone().unwrap();
    let mut link = Link::tcp(stream, "emulated Pico").unwrap();
    link_checks::all(&mut link, "emulated Pico");
    // The near-threshold preset: the Pico's rig refuses the fast one (400 pulses due in a tick, at
    // most 100: `the_fast_preset_is_skipped_and_near_threshold_runs_as_on_the_host`).
    link_checks::still_runs_and_stops(&mut link, Preset::NearThreshold, OutcomeCode::Balanced);
    // The stack (a rig of both scenes, firmware/src/realtime_stack.rs), its bodies' telemetry
    // every 2 steps: three `Body` frames a step (123 bytes, 1.3 ms at 921,600 baud) are more
    // than a 1 ms step carries on a real UART (the emulated one sends at once).
    let stack = link_checks::stack_over_the_link(&mut link, 2, Preset::NearThreshold, OutcomeCode::Balanced);
    println!("emulated Pico: host side: {:?}", link.host_stats());
    closer.shutdown(std::net::Shutdown::Both).ok();
    drop(link);
    let out = harness.0.take().unwrap().wait_with_output().unwrap();
    assert!(out.status.success(), "the harness failed: {}", out.status);
    std::fs::write(dir.join("link.json"), &out.stdout).unwrap();
    let emu: Value = serde_json::from_slice(&out.stdout).expect("the harness printed one JSON object");
    assert_eq!(emu["stopped"], "link-closed", "the harness stopped as {}", emu["stopped"]);
    nothing_unmodelled("emulated Pico with the link", &emu);
    assert_eq!(emu["fault_level"], 0, "GP25 (fault) is on after the link's runs");
    // At least the flood's pings came in through UART0.
    let flood = link_checks::FLOOD as usize
        * link_checks::frame(meterstick_link::Command::Ping { nonce: 1000 }).len();
    let rx = int(&emu["uart"]["rx_bytes"], "rx");
    assert!(rx >= i64::try_from(flood).unwrap(), "UART0 received {rx} bytes, the flood alone is {flood}");
    stack_cycles(&emu, &stack);
    let w = &emu["ticks"]["interval_cycles"];
    println!(
        "emulated Pico with the link: {:.1} s emulated in {:.1} s ({:.1} s in all), UART0 {} bytes in, {} out; \
         loop body worst {} cycles (a step, the link's poll, telemetry, flush), tick interval {}..{}",
        emu["emulated"]["seconds_at_125mhz"].as_f64().unwrap(),
        emu["emulated"]["wall_s"].as_f64().unwrap(),
        started.elapsed().as_secs_f64(),
        emu["uart"]["rx_bytes"],
        emu["uart"]["tx_bytes"],
        emu["run"]["cycles_per_step"]["max"],
        w["min"],
        w["max"],
    );
}

/// The stack's steps on the emulated Pico, from the harness's work per tick: the run starts in
/// the tick that lights the third interface's lights (GP16-18, which only the stack drives; the
/// host's `Start` is carried out in the tick's poll, and its first step follows in the same tick)
/// and takes one tick per step (an overrun's next tick starts at once). Prints the cycles per
/// step, mean and worst, against the 1 kHz tick, and the rig's own margin (`Report::Margin`:
/// the step alone, timed by SysTick).
fn stack_cycles(emu: &Value, stack: &link_checks::StackRun) {
    let start = emu["edges"]
        .as_array()
        .unwrap()
        .iter()
        .find(|e| STACK_LIGHTS.contains(&(int(&e["pin"], "pin") as u8)) && e["level"] == 1)
        .map(|e| usize::try_from(int(&e["tick"], "tick")).unwrap())
        .expect("the stack's lights (GP16-18) never lit");
    let work: Vec<f64> = emu["uart"]["tick_work_cycles"].as_array().unwrap()
        [start..start + stack.steps as usize]
        .iter()
        .map(|w| w.as_f64().unwrap())
        .collect();
    let period = (f64::from(H) * CORE_HZ).round();
    let mean = work.iter().sum::<f64>() / work.len() as f64;
    let worst = work.iter().copied().fold(0.0, f64::max);
    let over = work.iter().filter(|&&w| w > period).count();
    let margin = stack.margin.expect("the rig's margin after the stack's run");
    assert_eq!(i64::from(margin.period_cycles), period as i64, "the stack's tick period");
    println!(
        "emulated Pico, the 3-block stack (overhang 1.02, falls): {} steps, checksum {:08x}, cycles per step (the tick's work: the \
         link's poll and the step) mean {mean:.0}, worst {worst:.0} of {period:.0} ({:.1}%), {over} over the \
         period; the rig's margin: worst step {} cycles (step {}), {} overruns",
        stack.steps,
        stack.checksum,
        100.0 * worst / period,
        margin.worst_cycles,
        margin.worst_step,
        margin.overruns,
    );
}
