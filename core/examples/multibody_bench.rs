//! Host nanoseconds per step of the multibody scenes (`meterstick_core::multibody::scenes`): the
//! default block-on-block run (255 steps, repeated) and the default 3-block stack (10,000 steps),
//! in f32 and f64, with the solver's counters. Wall-clock figures: run it on a quiet machine.
//!
//! `cargo run --release -p meterstick-core --example multibody_bench`
#![allow(clippy::print_stdout, clippy::expect_used)]

use std::time::Instant;

use meterstick_core::Real;
use meterstick_core::RunStats;
use meterstick_core::multibody::scenes::{
    BlockOnBlock, BlockOnBlockParams, MultibodyScene as _, Stack3, StackParams,
};

/// Runs `run` `repeats` times; the best of the repeats' ns/step and the last run's counters.
fn best(repeats: u32, mut run: impl FnMut() -> RunStats) -> (f64, RunStats) {
    let mut best = f64::INFINITY;
    let mut stats = RunStats::default();
    for _ in 0..repeats {
        let start = Instant::now();
        stats = run();
        let ns = start.elapsed().as_secs_f64() * 1e9 / stats.steps.max(1) as f64;
        best = best.min(ns);
    }
    (best, stats)
}

fn bench<T: Real>() {
    let (ns, stats) = best(40, || {
        let mut scene = BlockOnBlock::new(BlockOnBlockParams::<f64>::default().cast::<T>()).expect("valid");
        let outcome = scene.run(|_| {});
        assert_eq!(outcome.name(), "slid");
        *scene.stepper().stats()
    });
    println!("block-on-block {}: {ns:.0} ns/step  {stats:?}", T::NAME);
    let (ns, stats) = best(3, || {
        let mut scene = Stack3::new(StackParams::<f64>::default().cast::<T>()).expect("valid");
        let outcome = scene.run(|_| {});
        assert_eq!(outcome.name(), "held");
        *scene.stepper().stats()
    });
    println!("3-block stack  {}: {ns:.0} ns/step  {stats:?}", T::NAME);
}

fn main() {
    bench::<f32>();
    bench::<f64>();
}
