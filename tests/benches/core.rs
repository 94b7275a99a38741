//! `cargo bench -p meterstick-tests --bench core`: one Lemke solve (6x6 and 8x8, cold and
//! warm-started, f32 and f64) on a real step LCP of the slow scene, one scene step, and a whole
//! slow run, with throughput in steps per second.
#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use meterstick_core::Real;
use meterstick_core::lcp::{Lcp, Lemke};
use meterstick_core::planar::assemble::{StepInputs, assemble};
use meterstick_core::planar::{ContactFrame, Layout, Pose, Tangents};
use meterstick_core::scene::{MeterStick, MeterStickParams, Scene};

/// The step LCP of the slow scene while finger 1 slides under a resting rod (finger 1 at
/// -0.3 m, finger 2 at +0.4 m): both fingers touch, finger 1 on mu_k, finger 2 on mu_s.
fn step_lcp<T: Real, const N: usize>() -> Lcp<T, N> {
    let p = MeterStickParams::<T>::paper();
    let pose = Pose { com: [T::zero(), p.rod_thickness / T::of(2.0)], sin_cos: (T::zero(), T::one()) };
    let half = [p.rod_length / T::of(2.0), p.rod_thickness / T::of(2.0)];
    let frames = [-0.3, 0.4].map(|fx| ContactFrame::under_lower_face([T::of(fx), T::zero()], &pose, half));
    // Per unit mass, as the scene assembles it.
    let m_inv = [T::one(), T::one(), p.rod_mass / p.inertia()];
    let inputs = StepInputs {
        frames: &frames,
        mu: [p.mu_kinetic, p.mu_static],
        support_velocity: [[p.finger1_velocity, T::zero()], [T::zero(), T::zero()]],
        v_free: [T::zero(), -p.step * p.gravity, T::zero()],
        m_inv,
        h: p.step,
        gravity: p.gravity,
        gap_round_off: T::zero(),
    };
    let tangents = if N == 8 { [Tangents::Both; 2] } else { [Tangents::Plus, Tangents::Minus] };
    assemble(&Layout::<2, N>::try_new(tangents).expect("N is 6 or 8"), &inputs).lcp
}

fn lemke_case<T: Real, const N: usize>(c: &mut Criterion) {
    let lcp = step_lcp::<T, N>();
    let solver = Lemke::<T, N>::new();
    let cold = solver.solve(&lcp).unwrap();
    let mut g = c.benchmark_group(format!("lemke_{}_{}x{}", T::NAME, N, N));
    g.throughput(Throughput::Elements(1));
    g.bench_function(BenchmarkId::new("cold", format!("{} pivots", cold.pivots)), |b| {
        b.iter(|| black_box(solver.solve(black_box(&lcp))).unwrap());
    });
    let warm = solver.solve_warm(&lcp, cold.basis).unwrap();
    assert!(warm.warm_start_used && warm.pivots <= 1);
    g.bench_function(BenchmarkId::new("warm", format!("{} pivots", warm.pivots)), |b| {
        b.iter(|| black_box(solver.solve_warm(black_box(&lcp), black_box(cold.basis))).unwrap());
    });
    g.finish();
}

fn lemke(c: &mut Criterion) {
    lemke_case::<f32, 6>(c);
    lemke_case::<f32, 8>(c);
    lemke_case::<f64, 6>(c);
    lemke_case::<f64, 8>(c);
}

fn slow_params<T: Real>() -> MeterStickParams<T> {
    MeterStickParams { finger1_x: T::of(-0.35), ..MeterStickParams::paper() }
}

fn scene_case<T: Real, const N: usize>(c: &mut Criterion) {
    let name = format!("{} {}x{}", T::NAME, N, N);
    // One step, in the middle of the slow run (t = 2 s: finger 1 sticks, finger 2 slides).
    let mut mid = MeterStick::<T, N, 64>::new(slow_params()).unwrap();
    for _ in 0..2000 {
        mid.step().unwrap();
    }
    let mut g = c.benchmark_group("scene_step");
    g.throughput(Throughput::Elements(1));
    g.bench_function(&name, |b| {
        b.iter_batched_ref(|| mid.clone(), |s| black_box(s.step()), criterion::BatchSize::SmallInput);
    });
    g.finish();
    // The whole slow run (7,902 steps at h = 1 ms), in steps per second.
    let steps = {
        let mut s = MeterStick::<T, N, 64>::new(slow_params()).unwrap();
        s.run(|_| {});
        s.stats().steps
    };
    let mut g = c.benchmark_group("slow_run");
    g.throughput(Throughput::Elements(steps));
    g.sample_size(20);
    g.bench_function(&name, |b| {
        b.iter(|| {
            let mut s = MeterStick::<T, N, 64>::new(slow_params()).unwrap();
            black_box(s.run(|_| {}))
        });
    });
    g.finish();
}

fn scene(c: &mut Criterion) {
    scene_case::<f32, 6>(c);
    scene_case::<f32, 8>(c);
    scene_case::<f64, 6>(c);
    scene_case::<f64, 8>(c);
}

criterion_group!(benches, lemke, scene);
criterion_main!(benches);
