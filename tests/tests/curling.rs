//! The curling scene (`meterstick_core::scene::spatial::Curling`, `docs/scenes.md`, "curling")
//! against the physics, independent of the code: a ring or a uniform disc launched sliding and
//! spinning on a level table stops sliding and spinning together (Farkas, Bartels, Unger & Wolf,
//! PRL 90, 248302 (2003)), and its `v / (R omega)` tends to a value of its shape whatever the
//! launch: 1 for a ring, 0.653 for a uniform disc (`docs/scenes.md` derives it).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::cast_precision_loss, clippy::print_stdout)]

use meterstick_core::Real;
use meterstick_core::scene::Outcome;
use meterstick_core::scene::spatial::{Curling, CurlingParams, SpatialScene};

/// Runs a stone to its outcome: `(terminal_ratio, slide_stop_s, spin_stop_s, outcome)`.
fn run<T: Real>(ring: bool, points: f64, speed: f64, spin: f64) -> (f64, f64, f64, Outcome) {
    let p = CurlingParams::<f64> {
        shape: if ring { 0.0 } else { 1.0 },
        points,
        speed,
        spin,
        ..Default::default()
    };
    let mut s = Curling::<T>::new(p.cast::<T>()).unwrap();
    while s.step().is_some() {}
    let m = s.measured().map(|x| x.map_or(f64::NAN, Real::as_f64));
    (m[0], m[1], m[2], s.outcome().unwrap())
}

/// A ring of four points, launched four ways: it stops sliding and spinning in the same step,
/// with `v / (R omega)` within `tolerance` of 1 ten steps of friction before.
fn ring<T: Real>(tolerance: f64) {
    for (v, w) in [(1.0, 5.0), (1.0, 20.0), (2.0, 2.0), (0.5, 10.0)] {
        let (ratio, slide, spin, outcome) = run::<T>(true, 4.0, v, w);
        println!("ring, 4 points, {v} m/s, {w} rad/s: ratio {ratio}, slides {slide} s, spins {spin} s");
        assert_eq!(outcome, Outcome::Stopped, "{v} m/s, {w} rad/s");
        // The same step: the two ends less than half a step `h = 1e-3` s apart.
        let same = slide.is_finite() && (slide - spin).abs() < 0.5e-3;
        assert!(same, "{v} m/s, {w} rad/s: slides {slide} s, spins {spin} s");
        assert!((ratio - 1.0).abs() <= tolerance, "{v} m/s, {w} rad/s: ratio {ratio}");
    }
}

#[test]
fn a_ring_stops_sliding_and_spinning_together_at_the_ratio_one() {
    ring::<f64>(1e-3);
    ring::<f32>(1e-3);
}

/// The radius, over `R`, of the centroid of one of `n` equal sectors of a disc:
/// `(2 / 3) sin(pi / n) / (pi / n)` (the disc's points, `docs/scenes.md`, "curling"), from the
/// sector's area `R^2 pi / n` and first moment `(2 / 3) R^3 sin(pi / n)`.
fn sector_centroid(n: usize) -> f64 {
    let half = std::f64::consts::PI / n as f64;
    2.0 / 3.0 * half.sin() / half
}

/// The uniform disc of 8 points (the defaults), launched four ways: it stops sliding and spinning
/// in the same step, every step verified; launched at the defaults (1 m/s, 5 rad/s) and at
/// (0.5 m/s, 10 rad/s) it ends turning about one of its points, its ratio that point's radius and
/// within 2 % of the law's 0.653; the other two launches reach that pivot only after the ratio is
/// read (`docs/scenes.md`, "curling"), their ratio below it.
fn disc<T: Real>() {
    let pivot = sector_centroid(8);
    for (v, w) in [(1.0, 5.0), (1.0, 20.0), (2.0, 2.0), (0.5, 10.0)] {
        let (ratio, slide, spin, outcome) = run::<T>(false, 8.0, v, w);
        println!("disc, 8 points, {v} m/s, {w} rad/s: ratio {ratio}, slides {slide} s, spins {spin} s");
        assert_eq!(outcome, Outcome::Stopped, "{v} m/s, {w} rad/s");
        let same = slide.is_finite() && (slide - spin).abs() < 0.5e-3;
        assert!(same, "{v} m/s, {w} rad/s: slides {slide} s, spins {spin} s");
        assert!(ratio <= pivot + 1e-4, "{v} m/s, {w} rad/s: ratio {ratio}, pivot {pivot}");
        if (v, w) == (1.0, 5.0) || (v, w) == (0.5, 10.0) {
            assert!((ratio - pivot).abs() <= 1e-4, "{v} m/s, {w} rad/s: ratio {ratio}, pivot {pivot}");
            assert!((ratio - 0.653).abs() <= 0.02 * 0.653, "{v} m/s, {w} rad/s: ratio {ratio}");
        }
    }
}

#[test]
fn a_uniform_disc_stops_sliding_and_spinning_together_within_two_percent_of_the_law() {
    disc::<f64>();
    disc::<f32>();
}

/// The ratio `v / (R omega)` the disc's layout itself gives, with no time step and no solver: `n`
/// equal point loads `m g / n` at the sector centroids (`sector_centroid`), each's friction
/// `mu m g / n` against its own slip, integrated by RK4 in steps of `0.002 min(v, R omega) / (mu
/// g)`, read as the scene reads it (the last ratio while both speeds are at least `10 mu g h`,
/// `h = 1e-3`). Defaults `R = 0.145`, `mu = 0.1`, `g = 9.81` (`docs/scenes.md`, "curling").
fn layout_ratio(n: usize, speed: f64, spin: f64) -> f64 {
    let (radius, mu_g) = (0.145, 0.1 * 9.81);
    let rho = sector_centroid(n) * radius;
    let points: Vec<(f64, f64)> = (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            (rho * a.cos(), rho * a.sin())
        })
        .collect();
    // (vx, vy, omega, turn) -> its rate: the disc's `I = m R^2 / 2`.
    let rate = |s: [f64; 4]| -> [f64; 4] {
        let (c, sn) = (s[3].cos(), s[3].sin());
        let (mut fx, mut fy, mut torque) = (0.0, 0.0, 0.0);
        for &(px, py) in &points {
            let (rx, ry) = (c * px - sn * py, sn * px + c * py);
            let (ux, uy) = (s[0] - s[2] * ry, s[1] + s[2] * rx);
            let size = ux.hypot(uy);
            if size > 0.0 {
                let (ux, uy) = (ux / size, uy / size);
                fx += ux;
                fy += uy;
                torque += rx * uy - ry * ux;
            }
        }
        let k = mu_g / n as f64;
        [-k * fx, -k * fy, -k * torque * 2.0 / (radius * radius), s[2]]
    };
    let floor = 10.0 * mu_g * 1e-3;
    let (mut s, mut ratio) = ([speed, 0.0, spin, 0.0], f64::NAN);
    loop {
        let (v, w) = (s[0].hypot(s[1]), radius * s[2].abs());
        if v < floor || w < floor {
            return ratio;
        }
        ratio = v / w;
        let dt = 0.002 * v.min(w) / mu_g;
        let at = |s: [f64; 4], k: [f64; 4], f: f64| core::array::from_fn(|i| s[i] + f * k[i]);
        let k1 = rate(s);
        let k2 = rate(at(s, k1, dt / 2.0));
        let k3 = rate(at(s, k2, dt / 2.0));
        let k4 = rate(at(s, k3, dt));
        s = core::array::from_fn(|i| s[i] + dt / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
    }
}

/// The disc of 4 to 8 points, launched four ways: its ratio is its layout's (`layout_ratio`,
/// independent of the core) within 1e-2, in f64 and f32: what keeps a launch off 0.653 is the
/// layout, not the step. Launched at (0.5 m/s, 10 rad/s) it ends turning about one of its points:
/// its ratio is then that point's radius, the sector's centroid, within 5e-3 (at 7 points it is
/// still closing in when read).
#[test]
fn a_disc_of_n_points_reaches_its_layouts_ratio() {
    for n in 4..=8 {
        for (v, w) in [(1.0, 5.0), (1.0, 20.0), (2.0, 2.0), (0.5, 10.0)] {
            let layout = layout_ratio(n, v, w);
            let (a, b) = (run::<f64>(false, n as f64, v, w).0, run::<f32>(false, n as f64, v, w).0);
            println!("{n} points, {v} m/s, {w} rad/s: layout {layout:.4}, f64 {a:.4}, f32 {b:.4}");
            for ratio in [a, b] {
                assert!((ratio - layout).abs() <= 1e-2, "{n} points, {v} m/s, {w} rad/s: {ratio}, {layout}");
            }
            if (v, w) == (0.5, 10.0) {
                let pivot = sector_centroid(n);
                for ratio in [a, b, layout] {
                    assert!((ratio - pivot).abs() <= 5e-3, "{n} points: ratio {ratio}, centroid {pivot}");
                }
            }
        }
    }
}

/// The disc's terminal ratio against `--points` (`docs/scenes.md`, "curling": the table); run with
/// `--ignored --nocapture`.
#[test]
#[ignore = "a table for the docs, not a check"]
fn table() {
    for ring in [true, false] {
        for points in [4.0, 5.0, 6.0, 7.0, 8.0] {
            for (v, w) in [(1.0, 5.0), (1.0, 20.0), (2.0, 2.0), (0.5, 10.0)] {
                let a = run::<f64>(ring, points, v, w);
                let b = run::<f32>(ring, points, v, w);
                println!("ring {ring} points {points} v {v} w {w}: f64 {a:?} f32 {b:?}");
            }
        }
    }
}

/// Stones spun fast or launched slow, in f64 and f32, discs and rings of 8 points: each stops
/// (`Outcome::Stopped`), sliding and spinning in the same step. Near its stop a flat base's friction
/// directions settle slowly or swing between two sets from one try to the next, and the lines of
/// the contacts' LCP flip its open load between vertices: these launches ended
/// `ConeNotConverged` (and a ring in f32 `ConeUnverified`: its friction held along the slip tighter
/// than the slip's direction is known) before `crate::spatial::load`'s patient, damped last try.
#[test]
fn stones_spun_fast_stop_sliding_and_spinning_together() {
    fn stop<T: Real>(ring: bool, speed: f64, spin: f64) {
        let p = CurlingParams::<f64> {
            shape: if ring { 0.0 } else { 1.0 },
            speed,
            spin,
            max_time: 300.0,
            ..Default::default()
        };
        let mut s = Curling::<T>::new(p.cast::<T>()).unwrap();
        while s.step().is_some() {}
        let [_, slide, spin_stop, ..] = s.measured().map(|x| x.map_or(f64::NAN, Real::as_f64));
        let label =
            format!("f{} {} {speed} m/s {spin} rad/s", 8 * T::BYTES, if ring { "ring" } else { "disc" });
        println!("{label}: {:?}, slides {slide} s, spins {spin_stop} s", s.outcome());
        assert_eq!(s.outcome(), Some(Outcome::Stopped), "{label}");
        assert!(slide.is_finite() && (slide - spin_stop).abs() < 0.5e-3, "{label}: {slide} {spin_stop}");
    }
    for (ring, speed, spin) in
        [(false, 0.1, -100.0), (false, 0.1, 30.0), (false, 1.0, 300.0), (false, 1.0, 1000.0)]
    {
        stop::<f64>(ring, speed, spin);
    }
    for (ring, speed, spin) in [(true, 3.0, 30.0), (true, 0.1, 1000.0)] {
        stop::<f32>(ring, speed, spin);
    }
}
