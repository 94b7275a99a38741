//! `cargo run --release -p meterstick-tests --example profile_run [-- f32|f64 6|8 [runs]]`: the
//! slow scene (x1 = -0.35 m, v = 0.1 m/s), run start to end `runs` times, for a profiler
//! (`valgrind --tool=callgrind target/release/examples/profile_run`). Prints steps, pivots and
//! the outcome so the run can be checked against `host-sim run`.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::print_stdout, clippy::print_stderr, missing_docs)]

use std::hint::black_box;

use meterstick_core::Real;
use meterstick_core::scene::{MeterStick, MeterStickParams, Scene};

fn run<T: Real, const N: usize>(runs: u32) {
    let params = MeterStickParams { finger1_x: T::of(-0.35), ..MeterStickParams::<T>::paper() };
    let mut steps = 0;
    let mut pivots = 0;
    let mut outcome = None;
    for _ in 0..runs {
        let mut scene = MeterStick::<T, N, 64>::new(black_box(params)).expect("valid parameters");
        outcome = Some(scene.run(|_| {}));
        steps += scene.stats().steps;
        pivots += scene.stats().pivots;
    }
    println!("{} {N}x{N}: {runs} runs, {steps} steps, {pivots} pivots, outcome {outcome:?}", T::NAME);
}

fn main() -> std::process::ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let real = args.first().map_or("f32", String::as_str);
    let n = args.get(1).map_or("6", String::as_str);
    let runs = args.get(2).map_or(1, |s| s.parse().expect("runs: a number"));
    match (real, n) {
        ("f32", "6") => run::<f32, 6>(runs),
        ("f32", "8") => run::<f32, 8>(runs),
        ("f64", "6") => run::<f64, 6>(runs),
        ("f64", "8") => run::<f64, 8>(runs),
        _ => {
            eprintln!("usage: profile_run [f32|f64] [6|8] [runs]");
            return std::process::ExitCode::FAILURE;
        }
    }
    std::process::ExitCode::SUCCESS
}
