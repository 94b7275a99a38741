//! The README's first scene: the meter stick of the paper's fig. 2 in f32 with the 6x6 LCP (as the
//! firmware runs it), and a block sliding down an incline in f64.
//! `cargo run -p meterstick-core --example first_scene`
//!
//! README.md quotes the lines between `// README begin` and `// README end`; `scripts/test.sh`
//! (its "docs" step) checks that the two agree, and CI builds this file (clippy, tests).
// README begin
use meterstick_core::ParamError;
use meterstick_core::scene::{Incline, InclineParams, MeterStick6, MeterStickParams, Outcome, Scene};

fn main() -> Result<(), ParamError> {
    // The paper's rod (L = 1 m, t = 5 mm, m = 0.2 kg) on fingers at -0.35 m and +0.4 m; finger 1
    // moves toward finger 2 at 0.1 m/s, h = 1 ms.
    let params = MeterStickParams::<f32> { finger1_x: -0.35, ..MeterStickParams::paper() };
    let mut stick = MeterStick6::<f32>::new(params)?; // a refused parameter is a ParamError
    let outcome = stick.run(|_step| {}); // each step's StepReport: modes, impulses, pivots
    assert_eq!(outcome, Outcome::Balanced);
    if let Some(meeting) = stick.meeting() {
        println!(
            "met at t = {:.3} s, COM {:.2} mm off their midpoint",
            meeting.time,
            meeting.com_offset * 1e3
        );
    }

    // A 10 x 5 cm block at 0.6 rad (34 degrees), mu_s 0.6, mu_k 0.4: it slides at g (sin a - mu_k cos a).
    let mut block = Incline::<f64>::new(InclineParams { angle: 0.6, ..InclineParams::default() })?;
    assert_eq!(block.run(|_| {}), Outcome::Slid);
    println!("the block slid at {:.4} m/s^2", block.acceleration().unwrap_or(f64::NAN));
    Ok(())
}
// README end
