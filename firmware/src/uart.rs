//! UART drivers for QEMU's machines, as [`Port`]s for the host link: the CMSDK APB UART0 of
//! mps2-an386 (Cortex-M4F) at `0x4000_4000` and the nRF51 UART of the micro:bit (Cortex-M0) at
//! `0x4000_2000`. QEMU connects either to its first `-serial` back-end (e.g. a TCP socket).
//! Both are polled, never blocking: `read` takes what has arrived, `write` what the transmitter
//! takes now. Register access is volatile MMIO at fixed addresses (the only `unsafe` here).
#![allow(unsafe_code)]

use meterstick_rig::session::Port;

/// A 32-bit register at `addr`.
fn read_reg(addr: usize) -> u32 {
    // SAFETY: `addr` is one of the documented, aligned UART registers of the machine this
    // driver is built for; reading it has no effect beyond the UART's own.
    unsafe { core::ptr::read_volatile(addr as *const u32) }
}

fn write_reg(addr: usize, value: u32) {
    // SAFETY: as `read_reg`; the UART is owned by this driver alone.
    unsafe { core::ptr::write_volatile(addr as *mut u32, value) }
}

/// CMSDK APB UART (ARM DDI 0479): DATA, STATE (bit 0 TX full, bit 1 RX full, bit 3 RX
/// overrun), CTRL (bit 0 TX enable, bit 1 RX enable), BAUDDIV.
#[cfg(feature = "qemu-mps2-an386")]
pub struct Uart {
    overruns: u32,
}

#[cfg(feature = "qemu-mps2-an386")]
impl Uart {
    const BASE: usize = 0x4000_4000;
    const DATA: usize = Self::BASE;
    const STATE: usize = Self::BASE + 0x04;
    const CTRL: usize = Self::BASE + 0x08;
    const BAUDDIV: usize = Self::BASE + 0x10;

    /// UART0, transmitter and receiver on (the baud divider is QEMU's minimum, 16; QEMU
    /// ignores the rate).
    pub fn new() -> Self {
        write_reg(Self::BAUDDIV, 16);
        write_reg(Self::CTRL, 0b11);
        Self { overruns: 0 }
    }

    /// Receive overruns seen (bytes lost by the hardware).
    #[allow(dead_code)]
    pub const fn overruns(&self) -> u32 {
        self.overruns
    }
}

#[cfg(feature = "qemu-mps2-an386")]
impl Port for Uart {
    fn read(&mut self, buf: &mut [u8]) -> usize {
        let mut n = 0;
        for slot in buf {
            let state = read_reg(Self::STATE);
            if state & 0b1000 != 0 {
                self.overruns = self.overruns.wrapping_add(1);
                write_reg(Self::STATE, 0b1000); // write 1 to clear
            }
            if state & 0b10 == 0 {
                break;
            }
            *slot = read_reg(Self::DATA) as u8;
            n += 1;
        }
        n
    }

    fn write(&mut self, bytes: &[u8]) -> usize {
        let mut n = 0;
        for &b in bytes {
            if read_reg(Self::STATE) & 0b1 != 0 {
                break;
            }
            write_reg(Self::DATA, u32::from(b));
            n += 1;
        }
        n
    }
}

/// nRF51 UART (nRF51 Series Reference Manual, chapter 29): tasks STARTRX/STARTTX, events
/// RXDRDY/TXDRDY, ENABLE (4), RXD, TXD. A byte written to TXD before the previous one's
/// TXDRDY would be lost (QEMU drops it), so `write` waits for that event between bytes.
#[cfg(feature = "qemu-microbit")]
pub struct Uart {
    tx_pending: bool,
}

#[cfg(feature = "qemu-microbit")]
impl Uart {
    const BASE: usize = 0x4000_2000;
    const STARTRX: usize = Self::BASE;
    const STARTTX: usize = Self::BASE + 0x008;
    const RXDRDY: usize = Self::BASE + 0x108;
    const TXDRDY: usize = Self::BASE + 0x11C;
    const ENABLE: usize = Self::BASE + 0x500;
    const RXD: usize = Self::BASE + 0x518;
    const TXD: usize = Self::BASE + 0x51C;
    const BAUDRATE: usize = Self::BASE + 0x524;

    /// The UART enabled at 115,200 baud, receiver and transmitter started.
    pub fn new() -> Self {
        write_reg(Self::ENABLE, 4);
        write_reg(Self::BAUDRATE, 0x01D7_E000);
        write_reg(Self::STARTTX, 1);
        write_reg(Self::STARTRX, 1);
        Self { tx_pending: false }
    }
}

#[cfg(feature = "qemu-microbit")]
impl Port for Uart {
    fn read(&mut self, buf: &mut [u8]) -> usize {
        let mut n = 0;
        for slot in buf {
            if read_reg(Self::RXDRDY) == 0 {
                break;
            }
            // Clear the event first: reading RXD raises it again when more bytes wait.
            write_reg(Self::RXDRDY, 0);
            *slot = read_reg(Self::RXD) as u8;
            n += 1;
        }
        n
    }

    fn write(&mut self, bytes: &[u8]) -> usize {
        let mut n = 0;
        for &b in bytes {
            if self.tx_pending {
                if read_reg(Self::TXDRDY) == 0 {
                    break;
                }
                write_reg(Self::TXDRDY, 0);
            }
            write_reg(Self::TXD, u32::from(b));
            self.tx_pending = true;
            n += 1;
        }
        n
    }
}
