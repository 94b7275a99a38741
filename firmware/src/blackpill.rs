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
//! With `rig-stack` the board runs the rig of the 3-block stack (`meterstick_rig::StackRig`,
//! [`crate::realtime_stack`]) instead: no stepper, a light set per interface, the same buttons
//! and fault light; the first two light sets on the meter-stick rig's finger light pins.
//!
//! | signal (`rig-stack`) | pin | notes |
//! |---|---|---|
//! | start button | PA0 (on-board KEY) | active low, as above |
//! | preset button | PA1 | active low: each press toggles the overhang, 0.98 / 1.02 |
//! | table / block 1 lights: sticking / sliding / separated | PB12 / PB13 / PB14 | active high (finger 1's) |
//! | block 1 / block 2 lights: sticking / sliding / separated | PB15 / PA8 / PA9 | active high (finger 2's) |
//! | block 2 / block 3 lights: sticking / sliding / separated | PB6 / PB7 / PB8 | active high |
//! | fault light | PA10 | active high |
//!
//! Clocks: the board's 25 MHz crystal; 100 MHz core, or 96 MHz with the USB link (USB needs an
//! exact 48 MHz from the same PLL, which 100 MHz excludes). The loop is [`crate::realtime`]'s,
//! shared with the Picos: one scene step per SysTick period `h` (1 ms by default), the real-time
//! margin logged (with `log`) and sent to the host (with `link`), the buttons between runs. With
//! `link`, the host may do all of this and more (`meterstick-link` commands; see
//! `meterstick_rig::session`); the USB device is serviced while the loop waits for the next tick.

use meterstick_rig::ModeLights;
use meterstick_rig::RigPins;
use stm32f4xx_hal::gpio::{AnyPin, Input, Output, PA0};
use stm32f4xx_hal::pac;
use stm32f4xx_hal::prelude::*;
use stm32f4xx_hal::rcc::Config;

#[cfg(feature = "log")]
use defmt_rtt as _;

use crate::realtime::{self, halt};
#[cfg(feature = "rig-stack")]
use crate::realtime_stack;

/// Core clock (Hz).
#[cfg(not(all(feature = "link", not(feature = "uart-link"))))]
const SYSCLK_HZ: u32 = 100_000_000;
/// Core clock (Hz): 96 MHz, so that the PLL also gives USB its 48 MHz.
#[cfg(all(feature = "link", not(feature = "uart-link")))]
const SYSCLK_HZ: u32 = 96_000_000;

type Out = AnyPin<Output>;

#[cfg(not(feature = "rig-stack"))]
pub fn main() -> ! {
    let (Some(dp), Some(cp)) = (pac::Peripherals::take(), cortex_m::Peripherals::take()) else { halt() };
    #[cfg(not(all(feature = "link", not(feature = "uart-link"))))]
    let mut rcc = dp.RCC.freeze(Config::hse(25.MHz()).sysclk(SYSCLK_HZ.Hz()));
    #[cfg(all(feature = "link", not(feature = "uart-link")))]
    let mut rcc = dp.RCC.freeze(Config::hse(25.MHz()).sysclk(SYSCLK_HZ.Hz()).require_pll48clk());
    let gpioa = dp.GPIOA.split(&mut rcc);
    let gpiob = dp.GPIOB.split(&mut rcc);
    let preset_button = gpioa.pa1.into_pull_up_input();
    let step = gpiob.pb0.into_push_pull_output().erase();
    let dir = gpiob.pb1.into_push_pull_output().erase();
    let pins: RigPins<PA0<Input>, Out, 2> = RigPins {
        start: gpioa.pa0.into_pull_up_input(),
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
    let Some(rig) = realtime::new_rig(pins, step, dir, SYSCLK_HZ) else { halt() };
    #[cfg(all(feature = "link", not(feature = "uart-link")))]
    let Some(port) = usb::UsbPort::new(
        (dp.OTG_FS_GLOBAL, dp.OTG_FS_DEVICE, dp.OTG_FS_PWRCLK),
        (gpioa.pa11, gpioa.pa12),
        &rcc.clocks,
    ) else {
        halt()
    };
    #[cfg(feature = "uart-link")]
    let Some(port) = uart::UartPort::new(dp.USART2, (gpioa.pa2, gpioa.pa3), &mut rcc) else { halt() };
    let mut buttons = realtime::Buttons::new();
    realtime::run(
        rig,
        move |rig, state| buttons.between_runs(rig, state, preset_button.is_low()),
        cp.SYST,
        SYSCLK_HZ,
        #[cfg(feature = "link")]
        port,
    )
}

/// The stack rig (`rig-stack`): the pins of the second table above; with `link`, the host link
/// as the meter-stick rig's.
#[cfg(feature = "rig-stack")]
pub fn main() -> ! {
    let (Some(dp), Some(cp)) = (pac::Peripherals::take(), cortex_m::Peripherals::take()) else { halt() };
    #[cfg(not(all(feature = "link", not(feature = "uart-link"))))]
    let mut rcc = dp.RCC.freeze(Config::hse(25.MHz()).sysclk(SYSCLK_HZ.Hz()));
    #[cfg(all(feature = "link", not(feature = "uart-link")))]
    let mut rcc = dp.RCC.freeze(Config::hse(25.MHz()).sysclk(SYSCLK_HZ.Hz()).require_pll48clk());
    let gpioa = dp.GPIOA.split(&mut rcc);
    let gpiob = dp.GPIOB.split(&mut rcc);
    let preset_button = gpioa.pa1.into_pull_up_input();
    let pins: RigPins<PA0<Input>, Out, 3> = RigPins {
        start: gpioa.pa0.into_pull_up_input(),
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
            ModeLights {
                sticking: gpiob.pb6.into_push_pull_output().erase(),
                sliding: gpiob.pb7.into_push_pull_output().erase(),
                separated: gpiob.pb8.into_push_pull_output().erase(),
            },
        ],
        fault: gpioa.pa10.into_push_pull_output().erase(),
    };
    let mut buttons = realtime_stack::Buttons::new();
    let Some(mut rig) = realtime_stack::new_rig(pins, realtime_stack::boot_params(), SYSCLK_HZ) else {
        halt()
    };
    buttons.show(&mut rig);
    #[cfg(all(feature = "link", not(feature = "uart-link")))]
    let Some(port) = usb::UsbPort::new(
        (dp.OTG_FS_GLOBAL, dp.OTG_FS_DEVICE, dp.OTG_FS_PWRCLK),
        (gpioa.pa11, gpioa.pa12),
        &rcc.clocks,
    ) else {
        halt()
    };
    #[cfg(feature = "uart-link")]
    let Some(port) = uart::UartPort::new(dp.USART2, (gpioa.pa2, gpioa.pa3), &mut rcc) else { halt() };
    realtime::run(
        rig,
        move |rig, state| buttons.between_runs(rig, state, preset_button.is_low()),
        cp.SYST,
        SYSCLK_HZ,
        #[cfg(feature = "link")]
        port,
    )
}

/// The host link on USART2 (`uart-link`): PA2 TX, PA3 RX, 921,600 baud 8N1, polled.
#[cfg(feature = "uart-link")]
mod uart {
    use embedded_hal_nb::serial::{Read as _, Write as _};
    use stm32f4xx_hal::pac::USART2;
    use stm32f4xx_hal::prelude::*;
    use stm32f4xx_hal::rcc::Rcc;
    use stm32f4xx_hal::serial::{Serial, config::Config};

    use meterstick_rig::session::Port;

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
    }

    /// Nothing to service while waiting (the USB port's counterpart).
    impl crate::realtime::LinkPort for UartPort {}

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

    use meterstick_rig::session::Port;

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
    }

    impl crate::realtime::LinkPort for UsbPort {
        /// Services the USB device (enumeration, transfers); call often.
        fn poll(&mut self) {
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
