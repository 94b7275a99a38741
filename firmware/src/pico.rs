//! The demo rig on a Raspberry Pi Pico 2 (`board-pico2`: RP2350, Cortex-M33 with FPU,
//! rp235x-hal) or a Raspberry Pi Pico (`board-pico`: RP2040, Cortex-M0+ without FPU,
//! rp2040-hal). The two HALs share their API for what the rig uses (clocks, GPIO, UART), so one
//! binding serves both; the pins are the same on both boards' header.
//!
//! | signal | GPIO | header pin | notes |
//! |---|---|---|---|
//! | host link (`link`): UART0 TX / RX | GP0 / GP1 | 1 / 2 | 921,600 baud 8N1, 3.3 V, to a USB-serial adapter |
//! | stepper STEP / DIR | GP2 / GP3 | 4 / 5 | e.g. an A4988/DRV8825 driver; DIR high = toward finger 2 |
//! | finger 1 lights: sticking / sliding / separated | GP6 / GP7 / GP8 | 9 / 10 / 11 | active high |
//! | finger 2 lights: sticking / sliding / separated | GP9 / GP10 / GP11 | 12 / 14 / 15 | active high |
//! | start button | GP14 | 19 | to ground (pin 18), internal pull-up: active low |
//! | preset button | GP15 | 20 | to ground (pin 18), internal pull-up: each press selects the next preset |
//! | stack's block 2 / block 3 lights (`link`): sticking / sliding / separated | GP16 / GP17 / GP18 | 21 / 22 / 24 | active high; off while the meter stick runs |
//! | fault light | GP25 | (on board) | the board's LED |
//!
//! With `link` the rig runs both scenes, one at a time ([`crate::realtime_stack::run_both_scenes`]):
//! the meter stick at boot and the 3-block stack when the host selects it (`SelectScene`, as
//! `host-sim monitor --scene stack` does), and back. The stack moves nothing (the teacher builds
//! the real stack at the overhang the model is given): its interfaces' lights are finger 1's
//! (the table / block 1 interface), finger 2's (block 1 / block 2) and GP16-18 (block 2 / block
//! 3); the buttons are the same (the preset button toggles the overhang, 0.98 / 1.02). One build
//! serves both, as a classroom's one board runs both; without `link` nothing can select the
//! stack, and the build is the meter stick's alone.
//!
//! With `rig-stick-3d` (no `link`) the rig runs the meter stick in three dimensions instead
//! (`crate::realtime_stick_3d`): the same pins, the carriage on a rail laid at the path's heading
//! to the rod, the preset button cycling the heading.
//!
//! Clocks: the boards' 12 MHz crystal; the HALs' default PLL settings give a 150 MHz core on the
//! Pico 2 and 125 MHz on the Pico. The loop is [`crate::realtime`]'s, as on the Black Pill: one
//! scene step per SysTick period `h` (1 ms by default) on the core clock, the real-time margin
//! logged with `log` (defmt over RTT, which needs a debug probe) and sent to the host with
//! `link`, the buttons between runs.
//!
//! Boot: the RP2350's boot ROM starts an image only if it finds an IMAGE_DEF block in the first
//! 4 KiB of flash ([`IMAGE_DEF`], placed after the vector table by `firmware/memory/rp2350.x`);
//! the RP2040's boot ROM runs the 256-byte second-stage boot loader at the start of flash
//! (`BOOT2`, the one for the Pico's W25Q flash), which sets up execute-in-place. Both are flashed
//! without a probe from a `.uf2` file (docs/hardware.md, "Flashing a Pico without a probe").

#[cfg(feature = "log")]
use defmt_rtt as _;
use embedded_hal::digital::InputPin;
use meterstick_rig::{ModeLights, RigPins};

#[cfg(feature = "board-pico2")]
use rp235x_hal as hal;
#[cfg(feature = "board-pico")]
use rp2040_hal as hal;

use hal::clocks::Clock;
use hal::gpio::{DynPinId, FunctionSioInput, FunctionSioOutput, Pin, PullDown, PullUp, bank0::Gpio14};

use crate::realtime::{self, halt};

/// The Picos' crystal (Hz).
const XTAL_HZ: u32 = 12_000_000;

/// Tells the RP2350's boot ROM that this is an Arm executable to run in Secure state.
#[cfg(feature = "board-pico2")]
#[allow(unsafe_code)] // `link_section` is an unsafe attribute: the section is the one the layout keeps.
#[unsafe(link_section = ".start_block")]
#[used]
pub static IMAGE_DEF: hal::block::ImageDef = hal::block::ImageDef::secure_exe();

/// The RP2040's second-stage boot loader for the Pico's flash (Winbond W25Q16JV, W25Q080
/// compatible): quad-SPI execute-in-place.
#[cfg(feature = "board-pico")]
#[allow(unsafe_code)] // `link_section` is an unsafe attribute: the section is the one the layout keeps.
#[unsafe(link_section = ".boot2")]
#[used]
pub static BOOT2: [u8; 256] = rp2040_boot2::BOOT_LOADER_W25Q080;

type Out = Pin<DynPinId, FunctionSioOutput, PullDown>;
type StartButton = Pin<Gpio14, FunctionSioInput, PullUp>;

pub fn main() -> ! {
    let (Some(mut pac), Some(cp)) = (hal::pac::Peripherals::take(), cortex_m::Peripherals::take()) else {
        halt()
    };
    let mut watchdog = hal::Watchdog::new(pac.WATCHDOG);
    let Ok(clocks) = hal::clocks::init_clocks_and_plls(
        XTAL_HZ,
        pac.XOSC,
        pac.CLOCKS,
        pac.PLL_SYS,
        pac.PLL_USB,
        &mut pac.RESETS,
        &mut watchdog,
    ) else {
        halt()
    };
    let sysclk_hz = clocks.system_clock.freq().to_Hz();
    let sio = hal::Sio::new(pac.SIO);
    let gp = hal::gpio::Pins::new(pac.IO_BANK0, pac.PADS_BANK0, sio.gpio_bank0, &mut pac.RESETS);
    let mut preset_button = gp.gpio15.into_pull_up_input();
    let step = gp.gpio2.into_push_pull_output().into_dyn_pin();
    let dir = gp.gpio3.into_push_pull_output().into_dyn_pin();
    let pins: RigPins<StartButton, Out, 2> = RigPins {
        start: gp.gpio14.into_pull_up_input(),
        lights: [
            ModeLights {
                sticking: gp.gpio6.into_push_pull_output().into_dyn_pin(),
                sliding: gp.gpio7.into_push_pull_output().into_dyn_pin(),
                separated: gp.gpio8.into_push_pull_output().into_dyn_pin(),
            },
            ModeLights {
                sticking: gp.gpio9.into_push_pull_output().into_dyn_pin(),
                sliding: gp.gpio10.into_push_pull_output().into_dyn_pin(),
                separated: gp.gpio11.into_push_pull_output().into_dyn_pin(),
            },
        ],
        fault: gp.gpio25.into_push_pull_output().into_dyn_pin(),
    };
    #[cfg(not(feature = "rig-stick-3d"))]
    let Some(rig) = realtime::new_rig(pins, step, dir, sysclk_hz) else { halt() };
    #[cfg(feature = "rig-stick-3d")]
    let Some(rig) = crate::realtime_stick_3d::new_rig(pins, step, dir, sysclk_hz) else { halt() };
    #[cfg(not(feature = "link"))]
    {
        #[cfg(not(feature = "rig-stick-3d"))]
        let mut buttons = realtime::Buttons::new();
        #[cfg(feature = "rig-stick-3d")]
        let mut buttons = crate::realtime_stick_3d::Buttons::new();
        realtime::run(
            rig,
            move |rig, state| buttons.between_runs(rig, state, preset_button.is_low().unwrap_or(false)),
            cp.SYST,
            sysclk_hz,
        )
    }
    #[cfg(feature = "link")]
    {
        let Some(port) = uart::UartPort::new(
            pac.UART0,
            (gp.gpio0.into_function(), gp.gpio1.into_function()),
            &mut pac.RESETS,
            clocks.peripheral_clock.freq(),
        ) else {
            halt()
        };
        // The stack's third light set (block 2 / block 3), off until the stack runs.
        let stack_lights = ModeLights {
            sticking: gp.gpio16.into_push_pull_output().into_dyn_pin(),
            sliding: gp.gpio17.into_push_pull_output().into_dyn_pin(),
            separated: gp.gpio18.into_push_pull_output().into_dyn_pin(),
        };
        crate::realtime_stack::run_both_scenes(
            rig,
            stack_lights,
            move || preset_button.is_low().unwrap_or(false),
            cp.SYST,
            sysclk_hz,
            port,
        )
    }
}

/// The host link on UART0 (`link`): GP0 TX, GP1 RX, 921,600 baud 8N1, polled.
#[cfg(feature = "link")]
mod uart {
    use super::hal;
    use hal::fugit::{HertzU32, RateExtU32 as _};
    use hal::gpio::bank0::{Gpio0, Gpio1};
    use hal::gpio::{FunctionUart, Pin, PullDown};
    use hal::uart::{DataBits, Enabled, StopBits, UartConfig, UartPeripheral};

    use meterstick_rig::session::Port;

    /// Baud rate: the PL011's fractional divider gets within 0.1 % of it from 125 or 150 MHz.
    const BAUD: u32 = 921_600;

    type Pins = (Pin<Gpio0, FunctionUart, PullDown>, Pin<Gpio1, FunctionUart, PullDown>);

    /// UART0 as the link's port.
    pub struct UartPort {
        uart: UartPeripheral<Enabled, hal::pac::UART0, Pins>,
        /// Receive errors (overrun, framing, parity, break) seen.
        errors: u32,
    }

    impl UartPort {
        /// UART0 on GP0/GP1 (`None` if the HAL refuses the configuration).
        pub fn new(
            device: hal::pac::UART0,
            pins: Pins,
            resets: &mut hal::pac::RESETS,
            peripheral_clock: HertzU32,
        ) -> Option<Self> {
            let config = UartConfig::new(BAUD.Hz(), DataBits::Eight, None, StopBits::One);
            let uart = UartPeripheral::new(device, pins, resets).enable(config, peripheral_clock).ok()?;
            Some(Self { uart, errors: 0 })
        }
    }

    /// Nothing to service while waiting.
    impl crate::realtime::LinkPort for UartPort {}

    impl Port for UartPort {
        fn read(&mut self, buf: &mut [u8]) -> usize {
            match self.uart.read_raw(buf) {
                Ok(n) => n,
                Err(nb::Error::WouldBlock) => 0,
                // A lost or damaged byte: the frame decoder drops its frame. The bytes read
                // before the error are in `buf`.
                Err(nb::Error::Other(e)) => {
                    self.errors = self.errors.wrapping_add(1);
                    e.discarded.len()
                }
            }
        }

        fn write(&mut self, bytes: &[u8]) -> usize {
            // A byte at a time: the HAL's slice write re-slices its input by a count the
            // compiler cannot bound (a panic path); for one byte it can.
            let mut n = 0;
            for b in bytes {
                if self.uart.write_raw(core::slice::from_ref(b)).is_err() {
                    break;
                }
                n += 1;
            }
            n
        }
    }
}
