//! The page's workloads, natively: steps per second of a whole run (the page's benchmark: the
//! meter stick at x1 = -0.35 m, 0.1 m/s, f32 6x6, run to its outcome again and again for about
//! two seconds) and the time of the page's outcome map at its default resolution (one thread),
//! through the same `Session` API the wasm exports wrap. Compare with the page's `?bench=1`.
//!
//! `cargo run --release -p meterstick-web --example bench [map]` (`map` also prints the map).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::time::Instant;

use meterstick_web::config::{LcpLayout, Precision};
use meterstick_web::flags::{SceneKind, flag_index};
use meterstick_web::session::Session;
use meterstick_web::sim::OUTCOMES;

/// The map's axes: finger speed (m/s) and mu_k/mu_s, as `web/page/map.js` has them (exact
/// decimals `i / 100`).
fn axes() -> (Vec<f64>, Vec<f64>) {
    let speeds = (0..=90).map(|i| f64::from(10 + i) / 100.0).collect();
    let ratios = (0..=16).map(|j| f64::from(20 + 5 * j) / 100.0).collect();
    (speeds, ratios)
}

fn session(given: &[(&str, f64)]) -> Session {
    let mut s = Session::new();
    s.configure(SceneKind::MeterStick);
    for (long, v) in given {
        assert!(s.give(flag_index(long).unwrap(), *v));
    }
    s.create(Precision::F32, LcpLayout::Reduced).expect("valid");
    s
}

fn main() {
    let print_map = std::env::args().any(|a| a == "map");
    let start = Instant::now();
    let (mut steps, mut runs) = (0u64, 0u32);
    while start.elapsed().as_secs_f64() < 2.0 {
        let mut s = session(&[("x1", -0.35), ("speed", 0.1)]);
        steps += s.sim_mut().unwrap().run(u64::MAX);
        runs += 1;
    }
    let secs = start.elapsed().as_secs_f64();
    println!(
        "native f32 6x6, slow meter stick (x1 = -0.35 m, 0.1 m/s): {runs} runs, {steps} steps in {secs:.2} s = {:.2} M steps/s",
        steps as f64 / secs / 1e6
    );
    let (speeds, ratios) = axes();
    let start = Instant::now();
    let mut grid = vec![vec![0u8; speeds.len()]; ratios.len()];
    let mut map_steps = 0;
    for (j, r) in ratios.iter().enumerate() {
        for (i, v) in speeds.iter().enumerate() {
            let mut s = session(&[("speed", *v), ("mu-k", 0.6 * r)]);
            let sim = s.sim_mut().unwrap();
            map_steps += sim.run(u64::MAX);
            grid[j][i] = sim.outcome().map_or(5, meterstick_web::sim::outcome_code);
        }
    }
    println!(
        "native outcome map {} x {} (speed 0.1..1 m/s x mu_k/mu_s 0.2..1, mu_s 0.6, fingers at -/+0.4 m): {map_steps} steps in {:.2} s, one thread",
        speeds.len(),
        ratios.len(),
        start.elapsed().as_secs_f64()
    );
    if print_map {
        for (j, row) in grid.iter().enumerate().rev() {
            let line: String = row
                .iter()
                .map(|&o| {
                    if o == 0 {
                        'B'
                    } else {
                        OUTCOMES[o as usize].chars().next().unwrap_or('?').to_ascii_lowercase()
                    }
                })
                .collect();
            println!("{:.2} {line}", ratios[j]);
        }
        println!("     speed 0.1 .. 1.0 m/s by 0.01 (B balanced, f fell, u unfinished)");
    }
}
