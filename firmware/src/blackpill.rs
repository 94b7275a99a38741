//! The demo rig on an STM32F411CEU6 "Black Pill" (WeAct), with stm32f4xx-hal.
//!
//! | signal | pin | notes |
//! |---|---|---|
//! | start button | PA0 (on-board KEY) | to ground, internal pull-up: active low |
//! | stepper STEP / DIR | PB0 / PB1 | e.g. an A4988/DRV8825 driver; DIR high = toward finger 2 |
//! | finger 1 lights: sticking / sliding / separated | PB12 / PB13 / PB14 | active high |
//! | finger 2 lights: sticking / sliding / separated | PB15 / PA8 / PA9 | active high |
//! | fault light | PA10 | active high |
//!
//! Clocks: the board's 25 MHz crystal, 100 MHz core. SysTick wraps every h = 1 ms (100,000
//! core cycles); each wrap runs one [`Rig::tick`], i.e. one scene step in real time. The time a
//! tick took is read from SysTick: the worst is logged (with `log`) every second as the
//! real-time margin, and a tick that overran its period is counted.

use embedded_hal::delay::DelayNs;
use meterstick_core::rig::{ModeLights, Rig, RigConfig, RigError, RigPins, RigState};
use meterstick_core::scene::MeterStickParams;
use stm32f4xx_hal::gpio::{AnyPin, Input, Output, PA0};
use stm32f4xx_hal::pac;
use stm32f4xx_hal::prelude::*;
use stm32f4xx_hal::rcc::Config;

#[cfg(feature = "log")]
use defmt_rtt as _;

use crate::systick;

/// Core clock (Hz).
const SYSCLK_HZ: u32 = 100_000_000;
/// Scene steps per second (h = 1 ms); one SysTick period per step.
const STEP_HZ: u32 = 1_000;

/// Busy-wait delay on the core clock (`asm::delay` waits at least the cycles asked).
struct CycleDelay;

impl DelayNs for CycleDelay {
    fn delay_ns(&mut self, ns: u32) {
        cortex_m::asm::delay(ns.saturating_mul(SYSCLK_HZ / 1_000_000) / 1_000);
    }
}

type Out = AnyPin<Output>;

pub fn main() -> ! {
    let (Some(dp), Some(mut cp)) = (pac::Peripherals::take(), cortex_m::Peripherals::take()) else { halt() };
    let mut rcc = dp.RCC.freeze(Config::hse(25.MHz()).sysclk(SYSCLK_HZ.Hz()));
    let gpioa = dp.GPIOA.split(&mut rcc);
    let gpiob = dp.GPIOB.split(&mut rcc);
    let pins: RigPins<PA0<Input>, Out> = RigPins {
        start: gpioa.pa0.into_pull_up_input(),
        step: gpiob.pb0.into_push_pull_output().erase(),
        dir: gpiob.pb1.into_push_pull_output().erase(),
        lights: [
            ModeLights {
                sticking: gpiob.pb12.into_push_pull_output().erase(),
                sliding: gpiob.pb13.into_push_pull_output().erase(),
                separated: gpiob.pb14.into_push_pull_output().erase(),
            },
            ModeLights {
                sticking: gpiob.pb15.into_push_pull_output().erase(),
                sliding: gpioa.pa8.into_push_pull_output().erase(),
                separated: gpioa.pa9.into_push_pull_output().erase(),
            },
        ],
        fault: gpioa.pa10.into_push_pull_output().erase(),
    };
    let params = MeterStickParams { finger1_x: -0.35, step: 1.0 / STEP_HZ as f32, ..MeterStickParams::<f32>::paper() };
    let mut rig = match Rig::<_, _, _, 6>::new(params, RigConfig::default_rig(), pins, CycleDelay) {
        Ok(rig) => rig,
        #[cfg_attr(not(feature = "log"), allow(unused_variables))]
        Err(e) => {
            #[cfg(feature = "log")]
            defmt::error!("rig not started: {}", e);
            halt()
        }
    };
    let period = SYSCLK_HZ / STEP_HZ;
    systick::start(&mut cp.SYST, period - 1);
    #[cfg(feature = "log")]
    let mut margin = Margin::default();
    loop {
        while !cp.SYST.has_wrapped() {}
        #[cfg(feature = "log")]
        let start = systick::now();
        let state: Result<RigState, _> = rig.tick();
        #[cfg(feature = "log")]
        margin.record(systick::elapsed(start, systick::now()), cp.SYST.has_wrapped(), period);
        match state {
            Ok(RigState::WaitingForStart | RigState::Running) => {}
            // Finished or fault (the rig shows it), or `Params`, which only `new` returns.
            Ok(RigState::Finished(_) | RigState::Fault(_)) | Err(RigError::Params(_)) => idle(),
            // Pins on this HAL cannot fail (`Infallible`).
            Err(RigError::Pin(never)) => match never {},
        }
    }
}

/// The real-time margin: the worst tick and the ticks that overran their period.
#[cfg(feature = "log")]
#[derive(Default)]
struct Margin {
    worst: u32,
    overruns: u32,
    ticks: u32,
}

#[cfg(feature = "log")]
impl Margin {
    /// Records a tick that took `used` cycles (`overran`: SysTick wrapped during it), and logs
    /// the margin once a second.
    fn record(&mut self, used: u32, overran: bool, period: u32) {
        self.worst = self.worst.max(used);
        self.overruns += u32::from(overran);
        self.ticks += 1;
        if self.ticks == STEP_HZ {
            self.ticks = 0;
            defmt::info!(
                "real time: worst tick {=u32} of {=u32} cycles ({=u32}% used), {=u32} overruns",
                self.worst,
                period,
                self.worst * 100 / period,
                self.overruns
            );
        }
    }
}

fn idle() -> ! {
    loop {
        cortex_m::asm::wfi();
    }
}

fn halt() -> ! {
    loop {
        cortex_m::asm::nop();
    }
}

#[panic_handler]
fn panic(_info: &core::panic::PanicInfo<'_>) -> ! {
    #[cfg(feature = "log")]
    defmt::error!("panic");
    halt()
}
