//! The demo rig on an STM32F411CEU6 "Black Pill" (WeAct), with stm32f4xx-hal.
//!
//! | signal | pin | notes |
//! |---|---|---|
//! | start button | PA0 (on-board KEY) | to ground, internal pull-up: active low |
//! | preset button | PA1 | to ground, internal pull-up: each press selects the next preset |
//! | stepper STEP / DIR | PB0 / PB1 | e.g. an A4988/DRV8825 driver; DIR high = toward finger 2 |
//! | finger 1 lights: sticking / sliding / separated | PB12 / PB13 / PB14 | active high |
//! | finger 2 lights: sticking / sliding / separated | PB15 / PA8 / PA9 | active high |
//! | fault light | PA10 | active high |
//! | host link (`link`): USB D- / D+ | PA11 / PA12 | the board's USB-C port, USB CDC (a serial port on the host) |
//! | host link (`uart-link`): USART2 TX / RX | PA2 / PA3 | 921,600 baud 8N1, 3.3 V, to a USB-serial adapter |
//!
//! Clocks: the board's 25 MHz crystal; 100 MHz core, or 96 MHz with the USB link (USB needs an
//! exact 48 MHz from the same PLL, which 100 MHz excludes). SysTick wraps every `h` (the scene's
//! step; 1 ms by default, reprogrammed when `h` changes); each wrap runs one [`Rig::tick`], i.e.
//! one scene step in real time. The time a tick took is read from SysTick: the worst is logged
//! (with `log`) every second as the real-time margin, and sent to the host (with `link`) in
//! `Report::Margin`; a tick that overran its period is counted.
//!
//! Buttons: a press of the start button starts a run; once the run has ended, a press resets it
//! (the carriage drives back to its origin) and the next press starts it again. While no run is
//! in progress, the preset button cycles slow / fast / near the fall threshold, shown on finger
//! 1's lights (sticking / sliding / separated). With `link`, the host may do all of this and
//! more (`meterstick-link` commands; see [`crate::session`]); the USB device is serviced while
//! the loop waits for the next tick.

use embedded_hal::delay::DelayNs;
use meterstick_core::rig::{ModeLights, Preset, PressDetector, Rig, RigConfig, RigError, RigPins, RigState};
use stm32f4xx_hal::gpio::{AnyPin, Input, Output, PA0};
use stm32f4xx_hal::pac;
use stm32f4xx_hal::prelude::*;
use stm32f4xx_hal::rcc::Config;

#[cfg(feature = "log")]
use defmt_rtt as _;

use crate::systick;

/// Core clock (Hz).
#[cfg(not(all(feature = "link", not(feature = "uart-link"))))]
const SYSCLK_HZ: u32 = 100_000_000;
/// Core clock (Hz): 96 MHz, so that the PLL also gives USB its 48 MHz.
#[cfg(all(feature = "link", not(feature = "uart-link")))]
const SYSCLK_HZ: u32 = 96_000_000;
/// Scene steps per second at boot (h = 1 ms); one SysTick period per step.
const STEP_HZ: u32 = 1_000;
/// Button samples (ticks) that must agree before a press counts.
const DEBOUNCE_TICKS: u16 = 20;

/// Busy-wait delay on the core clock (`asm::delay` waits at least the cycles asked).
struct CycleDelay;

impl DelayNs for CycleDelay {
    fn delay_ns(&mut self, ns: u32) {
        cortex_m::asm::delay(ns.saturating_mul(SYSCLK_HZ / 1_000_000) / 1_000);
    }
}

type Out = AnyPin<Output>;

/// SysTick reload for a step of `h` seconds (at least 1,000 cycles, at most the 24-bit range).
fn period_of(h: f32) -> u32 {
    let cycles = h * SYSCLK_HZ as f32;
    // A valid `h` is positive; the cast saturates (and maps NaN to 0), the clamp bounds it.
    #[allow(clippy::cast_sign_loss)]
    let cycles = cycles as u32;
    cycles.clamp(1_000, systick::MASK)
}

pub fn main() -> ! {
    let (Some(dp), Some(mut cp)) = (pac::Peripherals::take(), cortex_m::Peripherals::take()) else { halt() };
    #[cfg(not(all(feature = "link", not(feature = "uart-link"))))]
    let mut rcc = dp.RCC.freeze(Config::hse(25.MHz()).sysclk(SYSCLK_HZ.Hz()));
    #[cfg(all(feature = "link", not(feature = "uart-link")))]
    let mut rcc = dp.RCC.freeze(Config::hse(25.MHz()).sysclk(SYSCLK_HZ.Hz()).require_pll48clk());
    let gpioa = dp.GPIOA.split(&mut rcc);
    let gpiob = dp.GPIOB.split(&mut rcc);
    let preset_button = gpioa.pa1.into_pull_up_input();
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
    let mut rig = new_rig(pins);
    #[cfg(feature = "link")]
    let (mut port, mut session) = {
        #[cfg(not(feature = "uart-link"))]
        let Some(port) = usb::UsbPort::new(
            (dp.OTG_FS_GLOBAL, dp.OTG_FS_DEVICE, dp.OTG_FS_PWRCLK),
            (gpioa.pa11, gpioa.pa12),
            &rcc.clocks,
        ) else {
            halt()
        };
        #[cfg(feature = "uart-link")]
        let Some(port) = uart::UartPort::new(dp.USART2, (gpioa.pa2, gpioa.pa3), &mut rcc) else { halt() };
        let mut session = crate::session::Session::new(0, crate::session::build_id(env!("MS_BUILD_ID")));
        session.boot(&rig);
        (port, session)
    };
    let mut period = period_of(rig.params().step);
    systick::start(&mut cp.SYST, period - 1);
    #[cfg(feature = "link")]
    session.set_period(period);
    #[cfg(feature = "log")]
    let mut margin = Margin::default();
    let mut buttons = Buttons {
        preset: Preset::Slow,
        preset_press: PressDetector::new(DEBOUNCE_TICKS),
        start_press: PressDetector::new(DEBOUNCE_TICKS),
    };
    loop {
        while !cp.SYST.has_wrapped() {
            #[cfg(feature = "link")]
            port.poll();
        }
        #[cfg(feature = "link")]
        if let Err(RigError::Pin(never)) = session.poll(&mut port, &mut rig) {
            match never {}
        }
        let start = systick::now();
        #[cfg(feature = "link")]
        let state = rig.tick_with(|r| session.record(r));
        #[cfg(not(feature = "link"))]
        let state = rig.tick();
        let used = systick::elapsed(start, systick::now());
        #[cfg(feature = "log")]
        margin.record(used, cp.SYST.has_wrapped(), period);
        #[cfg(feature = "link")]
        {
            session.end_tick(&rig, used);
            session.flush(&mut port);
        }
        #[cfg(not(feature = "link"))]
        let _ = used;
        let state = match state {
            Ok(s) => s,
            // `Params` only comes from `new` and `reset`; pins on this HAL cannot fail.
            Err(RigError::Params(_)) => continue,
            Err(RigError::Pin(never)) => match never {},
        };
        buttons.between_runs(&mut rig, state, preset_button.is_low());
        // A new `h` (from the host or a preset): a new tick period.
        let want = period_of(rig.params().step);
        if want != period && !matches!(state, RigState::Running) {
            period = want;
            systick::start(&mut cp.SYST, period - 1);
            #[cfg(feature = "link")]
            session.set_period(period);
        }
    }
}

/// The buttons between runs: the preset button cycles the presets (shown on finger 1's
/// lights), the start button resets a finished run (the next press starts it).
struct Buttons {
    preset: Preset,
    preset_press: PressDetector,
    start_press: PressDetector,
}

impl Buttons {
    fn between_runs<P: embedded_hal::digital::OutputPin<Error = core::convert::Infallible>, D: DelayNs>(
        &mut self,
        rig: &mut Rig<PA0<Input>, P, D, 6>,
        state: RigState,
        preset_pressed: bool,
    ) {
        // Pins on this HAL cannot fail (`Infallible`); parameters of a preset are valid.
        if self.preset_press.sample(preset_pressed) && !matches!(state, RigState::Running) {
            self.preset = self.preset.next();
            let _ = rig.reset(self.preset.params(rig.params().step));
            let _ = rig.indicate(Some(self.preset.index()));
        }
        let ended = matches!(state, RigState::Finished(_) | RigState::Fault(_));
        if ended && self.start_press.sample(rig.start_pressed().unwrap_or(false)) {
            let _ = rig.reset(*rig.params());
        }
    }
}

/// The host link on USART2 (`uart-link`): PA2 TX, PA3 RX, 921,600 baud 8N1, polled.
#[cfg(feature = "uart-link")]
mod uart {
    use embedded_hal_nb::serial::{Read as _, Write as _};
    use stm32f4xx_hal::pac::USART2;
    use stm32f4xx_hal::prelude::*;
    use stm32f4xx_hal::rcc::Rcc;
    use stm32f4xx_hal::serial::{Serial, config::Config};

    use crate::session::Port;

    /// Baud rate: 100 MHz / (16 x 6.8125) = 917,431 baud (-0.45 %), within the +-2 % a UART
    /// tolerates; common USB-serial adapters (CP2102, FT232R, CH340) run at 921,600.
    const BAUD: u32 = 921_600;

    /// USART2 as the link's port.
    pub struct UartPort {
        serial: Serial<USART2>,
        /// Receive errors (overrun, framing, noise) seen.
        errors: u32,
    }

    impl UartPort {
        /// USART2 on PA2/PA3 (`None` if the HAL refuses the configuration).
        pub fn new(
            usart: USART2,
            pins: (stm32f4xx_hal::gpio::PA2, stm32f4xx_hal::gpio::PA3),
            rcc: &mut Rcc,
        ) -> Option<Self> {
            let serial = Serial::new(usart, pins, Config::default().baudrate(BAUD.bps()), rcc).ok()?;
            Some(Self { serial, errors: 0 })
        }

        /// Nothing to service (the USB port's counterpart).
        pub fn poll(&mut self) {
            let _ = self.errors;
        }
    }

    impl Port for UartPort {
        fn read(&mut self, buf: &mut [u8]) -> usize {
            let mut n = 0;
            for slot in buf {
                match self.serial.read() {
                    Ok(b) => {
                        *slot = b;
                        n += 1;
                    }
                    Err(nb::Error::WouldBlock) => break,
                    // A lost or damaged byte: the frame decoder drops its frame.
                    Err(nb::Error::Other(_)) => self.errors = self.errors.wrapping_add(1),
                }
            }
            n
        }

        fn write(&mut self, bytes: &[u8]) -> usize {
            let mut n = 0;
            for &b in bytes {
                if self.serial.write(b).is_err() {
                    break;
                }
                n += 1;
            }
            n
        }
    }
}

/// The host link over the Black Pill's USB-C port: a USB CDC ACM serial port
/// (`usb-device` + `usbd-serial`), polled from the main loop.
#[cfg(all(feature = "link", not(feature = "uart-link")))]
mod usb {
    use stm32f4xx_hal::otg_fs::{USB, UsbBus, UsbBusType};
    use stm32f4xx_hal::pac;
    use stm32f4xx_hal::rcc::Clocks;
    use usb_device::bus::UsbBusAllocator;
    use usb_device::prelude::{StringDescriptors, UsbDevice, UsbDeviceBuilder, UsbVidPid};
    use usbd_serial::SerialPort;

    use crate::session::Port;

    /// The USB device and its CDC ACM class.
    pub struct UsbPort {
        dev: UsbDevice<'static, UsbBusType>,
        serial: SerialPort<'static, UsbBusType>,
    }

    impl UsbPort {
        /// The USB device on PA11/PA12 (`None` if called twice, or if the descriptors do not
        /// fit).
        pub fn new(
            periphs: (pac::OTG_FS_GLOBAL, pac::OTG_FS_DEVICE, pac::OTG_FS_PWRCLK),
            pins: (stm32f4xx_hal::gpio::PA11, stm32f4xx_hal::gpio::PA12),
            clocks: &Clocks,
        ) -> Option<Self> {
            let ep_memory = cortex_m::singleton!(: [u32; 1024] = [0; 1024])?;
            let usb = USB::new(periphs, pins, clocks);
            let bus: &'static UsbBusAllocator<UsbBusType> =
                cortex_m::singleton!(: UsbBusAllocator<UsbBusType> = UsbBus::new(usb, ep_memory))?;
            let serial = SerialPort::new(bus);
            // pid.codes' test PID for CDC ACM devices (0x1209/0x0001 is reserved for tests);
            // a rig that ships would register its own.
            let dev = UsbDeviceBuilder::new(bus, UsbVidPid(0x1209, 0x0001))
                .device_class(usbd_serial::USB_CLASS_CDC)
                .strings(&[StringDescriptors::default()
                    .manufacturer("meterstick")
                    .product("meter-stick rig")
                    .serial_number("rig-1")])
                .ok()?
                .build();
            Some(Self { dev, serial })
        }

        /// Services the USB device (enumeration, transfers); call often.
        pub fn poll(&mut self) {
            self.dev.poll(&mut [&mut self.serial]);
        }
    }

    impl Port for UsbPort {
        fn read(&mut self, buf: &mut [u8]) -> usize {
            self.serial.read(buf).unwrap_or(0)
        }

        fn write(&mut self, bytes: &[u8]) -> usize {
            self.serial.write(bytes).unwrap_or(0)
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
                self.worst * 100 / period.max(1),
                self.overruns
            );
        }
    }
}

/// The rig on `pins` with the slow preset at h = 1 ms (halts if it cannot start).
fn new_rig(pins: RigPins<PA0<Input>, Out>) -> Rig<PA0<Input>, Out, CycleDelay, 6> {
    let params = Preset::Slow.params(1.0 / STEP_HZ as f32);
    match Rig::<_, _, _, 6>::new(params, RigConfig::default_rig(), pins, CycleDelay) {
        Ok(rig) => rig,
        #[cfg_attr(not(feature = "log"), allow(unused_variables))]
        Err(e) => {
            #[cfg(feature = "log")]
            defmt::error!("rig not started: {}", e);
            halt()
        }
    }
}

fn halt() -> ! {
    loop {
        cortex_m::asm::nop();
    }
}
