//! Do subnormal f32 values occur in the scenes, and does flushing them change anything? The question decides whether the Raspberry Pi
//! Pico (RP2040) can use its boot ROM's floating-point routines and still reproduce the host's f32
//! trajectory bit for bit: rp2040-hal maps `+ - * /` of f32 to them, and they round as IEEE 754
//! does (round to nearest even) except that they flush subnormal operands and results to zero
//! (docs/hardware.md). So the Pico computes what the host computes exactly when no addition,
//! subtraction, multiplication or division on the way meets or makes a subnormal.
//!
//! x86-64 records both in MXCSR's sticky flags: DE (a subnormal operand) and UE (underflow: a
//! tiny result; with flush-to-zero on, every tiny result, exact or not). Each run below is made
//! twice in f32: with IEEE arithmetic (flags cleared before, read after), and with FTZ and DAZ on
//! (flush-to-zero and denormals-are-zero: the ROM routines' treatment of subnormals, applied to
//! every SSE operation, comparisons and the f64 inside `libm` included, so a superset of what the
//! Pico flushes). The runs: the paper's meter-stick scenes (the five speeds of `host-sim run`,
//! fingers at -0.4 and, as the firmware and the rig's presets, finger 1 at -0.35), the incline
//! and the ladder, in 6x6 as the firmware runs them, and every case of the stress grid (`host-sim
//! stress`: stiff and extreme parameters) in 6x6 and 8x8.
//!
//! Changing MXCSR is outside what Rust's compiler assumes (it may fold constant expressions with
//! IEEE semantics); it is done here only around whole scene runs, whose operands are not
//! compile-time constants, to read the flags, never to compute a figure the project ships.
#![cfg(target_arch = "x86_64")]
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::arch::asm;

use meterstick_core::planar::Checksum;
use meterstick_core::scene::{
    Incline, InclineParams, Ladder, LadderParams, MeterStick, MeterStickParams, Scene,
};
use meterstick_host_sim::scenes::SceneParams;
use meterstick_host_sim::stress::cases::cases;

/// MXCSR bits: the sticky flags DE (denormal operand) and UE (underflow), and the modes DAZ and
/// FTZ.
const DE: u32 = 1 << 1;
const UE: u32 = 1 << 4;
const FLAGS: u32 = 0x3f;
const DAZ: u32 = 1 << 6;
const FTZ: u32 = 1 << 15;

#[allow(unsafe_code)]
fn mxcsr() -> u32 {
    let mut v = 0u32;
    // SAFETY: STMXCSR stores the 32-bit MXCSR into `v`, a valid, aligned u32.
    unsafe { asm!("stmxcsr [{}]", in(reg) &raw mut v, options(nostack, preserves_flags)) };
    v
}

#[allow(unsafe_code)]
fn set_mxcsr(v: u32) {
    // SAFETY: LDMXCSR loads a value built from the current MXCSR with only flag and mode bits
    // changed (no reserved bit set), so it cannot fault; exceptions stay masked.
    unsafe { asm!("ldmxcsr [{}]", in(reg) &raw const v, options(nostack, preserves_flags)) };
}

/// `a * b` (or `a + b`) by one SSE instruction under MXCSR `mode` (its flags cleared first),
/// with the flags it raised; MXCSR is restored after. One `asm!` block from the write of MXCSR to
/// its read: the compiler cannot move the arithmetic out of it (plain arithmetic on registers it
/// may move across separate MXCSR accesses, and did: the test then saw no flag).
#[allow(unsafe_code)]
fn sse_under(mode: u32, add: bool, mut a: f32, b: f32) -> (f32, u32) {
    let saved = mxcsr();
    let set = (mode & !FLAGS).to_le_bytes();
    let mut raised = 0u32;
    if add {
        // SAFETY: LDMXCSR of a value built from MXCSR with only flag and mode bits changed (no
        // reserved bit, exceptions masked: nothing faults), ADDSS on registers, STMXCSR into a
        // valid aligned u32, LDMXCSR of the saved value.
        unsafe {
            asm!("ldmxcsr [{set}]", "addss {a}, {b}", "stmxcsr [{raised}]", "ldmxcsr [{saved}]",
                set = in(reg) set.as_ptr(), raised = in(reg) &raw mut raised, saved = in(reg) &raw const saved,
                a = inout(xmm_reg) a, b = in(xmm_reg) b, options(nostack));
        }
    } else {
        // SAFETY: as above, with MULSS.
        unsafe {
            asm!("ldmxcsr [{set}]", "mulss {a}, {b}", "stmxcsr [{raised}]", "ldmxcsr [{saved}]",
                set = in(reg) set.as_ptr(), raised = in(reg) &raw mut raised, saved = in(reg) &raw const saved,
                a = inout(xmm_reg) a, b = in(xmm_reg) b, options(nostack));
        }
    }
    (a, raised & FLAGS)
}

/// What one run gave: its checksum, steps and outcome, and the sticky flags it raised.
#[derive(Debug, Clone, PartialEq)]
struct Run {
    checksum: u32,
    steps: u64,
    outcome: String,
    flags: u32,
}

/// Runs `make()`'s scene to its outcome with MXCSR's modes `modes` (flags cleared first).
fn run_with<S: Scene<f32, 2>>(modes: u32, make: &dyn Fn() -> Option<S>) -> Option<Run> {
    let mut scene = make()?;
    let saved = mxcsr();
    set_mxcsr((saved & !(FLAGS | DAZ | FTZ)) | modes);
    let mut sum = Checksum::new();
    let outcome = scene.run(|r| sum.add(&r.state));
    let flags = mxcsr() & FLAGS;
    set_mxcsr(saved);
    Some(Run { checksum: sum.value(), steps: scene.stats().steps, outcome: format!("{outcome:?}"), flags })
}

/// A run in IEEE and in FTZ/DAZ; `None` when the parameters are refused in f32.
fn both<S: Scene<f32, 2>>(make: &dyn Fn() -> Option<S>) -> Option<(Run, Run)> {
    Some((run_with(0, make)?, run_with(FTZ | DAZ, make)?))
}

/// The stress case `spec` (start raised by `dy`) in f32 with the `N`-row LCP.
fn stress_run<const N: usize>(spec: &SceneParams, dy: f64) -> Option<(Run, Run)> {
    match *spec {
        SceneParams::MeterStick(p) => both(&|| {
            let p = p.cast::<f32>();
            let mut start = p.resting_state();
            start.y += dy as f32;
            MeterStick::<f32, N, 0>::with_state(p, start).ok()
        }),
        SceneParams::Incline(p) => both(&|| Incline::<f32, N, 0>::new(p.cast()).ok()),
        SceneParams::Ladder(p) => both(&|| Ladder::<f32, N, 0>::new(p.cast()).ok()),
        _ => None, // the stress grid's scenes are the three above (`host-sim/src/stress/cases/one_body.rs`)
    }
}

/// Every run: the paper's scenes and the stress grid (`quick`: its subset). Returns (name, IEEE
/// run, FTZ/DAZ run).
fn all_runs(quick: bool) -> Vec<(String, Run, Run)> {
    let mut out = Vec::new();
    let mut push = |name: String, r: Option<(Run, Run)>| {
        if let Some((a, b)) = r {
            out.push((name, a, b));
        }
    };
    for x1 in [-0.4f32, -0.35] {
        for v in [0.1f32, 0.5, 1.0, 5.0, 10.0] {
            let p =
                MeterStickParams { finger1_velocity: v, finger1_x: x1, ..MeterStickParams::<f32>::paper() };
            push(
                format!("paper meter stick v={v} x1={x1} 6x6"),
                both(&|| MeterStick::<f32, 6, 0>::new(p).ok()),
            );
        }
    }
    push("paper incline 6x6".into(), both(&|| Incline::<f32, 6, 0>::new(InclineParams::default()).ok()));
    push("paper ladder 6x6".into(), both(&|| Ladder::<f32, 6, 0>::new(LadderParams::default()).ok()));
    for case in cases(quick) {
        push(format!("stress {} 6x6", case.name), stress_run::<6>(&case.spec, case.start_dy));
        push(format!("stress {} 8x8", case.name), stress_run::<8>(&case.spec, case.start_dy));
    }
    out
}

/// The flags of `r` in words.
fn flag_names(flags: u32) -> String {
    let mut v = Vec::new();
    if flags & DE != 0 {
        v.push("subnormal operand (DE)");
    }
    if flags & UE != 0 {
        v.push("tiny result (UE)");
    }
    if v.is_empty() { "none".into() } else { v.join(", ") }
}

/// The paper's scenes and the stress grid's quick subset (the test command; the scenes are
/// instantiated in this crate, at the test profile's optimisation).
#[test]
fn flush_to_zero_changes_no_trajectory_paper_scenes_and_quick_grid() {
    check(&all_runs(true));
}

/// The whole stress grid (77 cases, one of 10^6 steps): `cargo test --release -p meterstick-tests
/// --test subnormals -- --ignored`.
#[test]
#[ignore = "the whole stress grid, twice in two layouts: run with --release"]
fn flush_to_zero_changes_no_trajectory_whole_stress_grid() {
    let runs = all_runs(false);
    assert!(runs.len() > 100, "the stress grid runs in f32: {} runs", runs.len());
    check(&runs);
}

/// Every run gives the same checksum, steps and outcome with flush-to-zero as with IEEE
/// arithmetic; the runs that meet subnormals at all are printed (measured: the paper's meter stick
/// at 5 m/s with fingers at -0.4 m and the stress grid's start 0.1 mm into the fingers, in both
/// layouts: a subnormal operand and tiny results, which flushing leaves without effect on the
/// trajectory's bits).
fn check(runs: &[(String, Run, Run)]) {
    let paper = runs.iter().filter(|(n, _, _)| n.starts_with("paper")).count();
    assert_eq!(paper, 12, "the paper's scenes all run in f32");
    let (mut differ, mut met) = (Vec::new(), Vec::new());
    for (name, ieee, ftz) in runs {
        let line = format!(
            "{name}: IEEE {:08x} {} steps {} (subnormals: {}); FTZ/DAZ {:08x} {} steps {} (subnormals: {})",
            ieee.checksum,
            ieee.steps,
            ieee.outcome,
            flag_names(ieee.flags),
            ftz.checksum,
            ftz.steps,
            ftz.outcome,
            flag_names(ftz.flags)
        );
        if ieee.checksum != ftz.checksum || ieee.steps != ftz.steps || ieee.outcome != ftz.outcome {
            differ.push(line);
        } else if (ieee.flags | ftz.flags) & (DE | UE) != 0 {
            met.push(line);
        }
    }
    let steps: u64 = runs.iter().map(|(_, r, _)| r.steps).sum();
    println!("{} f32 runs, {steps} steps, each with IEEE and with FTZ/DAZ arithmetic", runs.len());
    println!("{} runs meet subnormals, with the same trajectory when they are flushed:", met.len());
    for line in &met {
        println!("  {line}");
    }
    assert!(differ.is_empty(), "runs that differ under flush-to-zero:\n{}", differ.join("\n"));
}

/// The instrument works: an operation on subnormals raises the flags, and FTZ/DAZ changes its
/// result.
#[test]
fn the_flags_see_a_subnormal() {
    let (tiny, third) = (f32::MIN_POSITIVE, 0.3f32);
    let ieee = mxcsr() & !(FTZ | DAZ);
    let (sub, made) = sse_under(ieee, false, tiny, third);
    let (twice, used) = sse_under(ieee, true, sub, sub);
    let (flushed, ftz) = sse_under(ieee | FTZ | DAZ, false, tiny, third);
    let (exact, _) = sse_under(ieee | FTZ | DAZ, false, tiny, 0.5);
    assert!(sub > 0.0 && sub < f32::MIN_POSITIVE && twice > sub, "{sub:e} is subnormal");
    assert_ne!(made & UE, 0, "IEEE: an inexact tiny result raises UE");
    assert_ne!(used & DE, 0, "IEEE: a subnormal operand raises DE");
    assert_eq!((flushed, exact), (0.0, 0.0), "FTZ flushes tiny results, exact ones too");
    assert_ne!(ftz & UE, 0, "FTZ: a flushed result raises UE");
}
