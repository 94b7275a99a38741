//! The rig of the meter stick in three dimensions (feature `spatial`; `docs/scenes.md`,
//! "meter-stick-3d"): the carriage runs along finger 1's path (its pulses the path's travel),
//! each finger's light follows its points' modes, and the run ends as the scene alone does.
#![cfg(feature = "spatial")]
#![allow(clippy::unwrap_used, clippy::cast_possible_truncation, clippy::float_cmp)]

use meterstick_core::scene::spatial::{MeterStick3d, MeterStick3dParams};
use meterstick_core::spatial::Mode;
use meterstick_rig::{Carriage, HeadlessPin, NoDelay, Rig, RigConfig, RigScene as _, RigState};

type Stick3dRig = Rig<MeterStick3d<f32>, Carriage<HeadlessPin, NoDelay>, HeadlessPin, HeadlessPin, 2>;

/// At 0 and 10 degrees the rig's run ends as the scene's own run (Balanced), in as many steps;
/// the carriage has pulsed the path's travel, `|finger 1's (x, y) travel| x steps_per_meter`,
/// rounded; each finger's light rose once at the start and once per change of its shown mode.
#[test]
fn the_carriage_travels_along_the_path_and_the_run_ends_as_the_scene() {
    for heading_deg in [0.0f32, 10.0] {
        let params =
            MeterStick3dParams { heading: heading_deg.to_radians(), ..MeterStick3dParams::default() };
        let mut alone = MeterStick3d::new(params).unwrap();
        let mut modes = vec![alone.finger_modes()];
        while let Some(report) = alone.step() {
            modes.push(MeterStick3d::modes_of(&report));
        }
        let config = RigConfig::default_rig();
        let mut rig = Stick3dRig::headless(params, config, NoDelay).unwrap();
        let mut ticks = 0u64;
        let state = loop {
            let s = rig.tick().unwrap();
            ticks += 1;
            if matches!(s, RigState::Finished(_) | RigState::Fault(_)) || ticks > 100_000 {
                break s;
            }
        };
        let outcome = alone.outcome().unwrap();
        assert_eq!(state, RigState::Finished(outcome), "{heading_deg} deg");
        assert_eq!(rig.scene().stepper().time(), alone.stepper().time(), "{heading_deg} deg");
        let [start, now] = [params.finger1_x, rig.scene().tips()[0][0]];
        let (sin, cos) = params.heading_sin_cos();
        let path = (now - start) / cos;
        let dy = rig.scene().tips()[0][1];
        assert!((path * sin - dy).abs() <= 1e-6, "{heading_deg} deg: finger 1 off its path ({dy} m across)");
        assert_eq!(rig.pulses(), (path * config.steps_per_meter).round() as i64, "{heading_deg} deg");
        assert!(rig.pulses() > 50_000, "{heading_deg} deg: {} pulses", rig.pulses());
        let (pins, _) = rig.release();
        for finger in 0..2 {
            let shown: Vec<u8> = modes.iter().map(|m| light(m[finger])).collect();
            let changes = shown.windows(2).filter(|w| w[0] != w[1]).count() as u32;
            let l = &pins.lights[finger];
            let rises = l.sticking.rises() + l.sliding.rises() + l.separated.rises();
            assert_eq!(rises, 1 + changes, "{heading_deg} deg: finger {} light rises", finger + 1);
        }
    }
}

const fn light(m: Mode) -> u8 {
    match m {
        Mode::Sticking => 0,
        Mode::Sliding => 1,
        Mode::Separated => 2,
    }
}
