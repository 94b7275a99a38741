//! Drives every public entry point of `meterstick-link` with inputs the optimiser cannot see
//! (`core::hint::black_box`), so that every reachable panic path stays in the binary; the
//! panic handler calls a symbol that does not exist. Linking succeeds only if no panic path
//! is reachable.
#![no_std]
#![no_main]

use core::hint::black_box;

use cortex_m_rt::entry;
use embedded_io::{ErrorType, Read, ReadReady, Write};
use meterstick_link::{
    Command, CommandDecoder, FrameDecoder, MAX_FRAME, Report, ReportDecoder, crc32c, encode, poll_into,
    read_into, write_all, write_message,
};

unsafe extern "C" {
    /// Deliberately undefined.
    fn meterstick_link_has_a_panic_path() -> !;
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo<'_>) -> ! {
    // SAFETY: never runs; the symbol does not exist, so this only links if it is unreachable.
    unsafe { meterstick_link_has_a_panic_path() }
}

/// A serial port whose every answer is opaque.
struct Port;

impl ErrorType for Port {
    type Error = embedded_io::ErrorKind;
}

impl Read for Port {
    fn read(&mut self, buf: &mut [u8]) -> Result<usize, Self::Error> {
        for b in buf.iter_mut() {
            *b = black_box(0);
        }
        if black_box(false) { Err(embedded_io::ErrorKind::Other) } else { Ok(black_box(buf.len())) }
    }
}

impl ReadReady for Port {
    fn read_ready(&mut self) -> Result<bool, Self::Error> {
        Ok(black_box(true))
    }
}

impl Write for Port {
    fn write(&mut self, buf: &[u8]) -> Result<usize, Self::Error> {
        black_box(buf);
        if black_box(false) { Err(embedded_io::ErrorKind::Other) } else { Ok(black_box(buf.len())) }
    }
    fn flush(&mut self) -> Result<(), Self::Error> {
        Ok(())
    }
}

#[entry]
fn main() -> ! {
    let mut commands = CommandDecoder::new();
    let mut reports = ReportDecoder::new();
    let mut small = FrameDecoder::<Report, 16>::new();
    let mut out = [0u8; MAX_FRAME];
    let mut port = Port;
    loop {
        // Decoders, byte by byte and by slices.
        let byte = black_box(0u8);
        let _ = black_box(commands.push(byte));
        let _ = black_box(reports.push(byte));
        let chunk = black_box([0u8; 8]);
        small.feed(&chunk, |r| {
            let _ = black_box(r);
        });
        black_box(commands.stats().since(&reports.stats()).dropped());
        if black_box(false) {
            commands.reset();
            reports.clear_stats();
        }

        // Encoder, any message into a buffer of any length.
        let report: Report = black_box(Report::Pong { nonce: 0 });
        let command: Command = black_box(Command::Start);
        let len = black_box(MAX_FRAME);
        if let Some(buf) = out.get_mut(..len) {
            let _ = black_box(encode(&report, buf).map(<[u8]>::len));
            let _ = black_box(encode(&command, buf).map(<[u8]>::len));
        }
        black_box(crc32c(black_box(&out)));
        black_box(command.tag());

        // Byte-stream helpers.
        black_box(write_message(&mut port, &report).is_ok());
        black_box(write_all(&mut port, black_box(&out)).is_ok());
        let _ = black_box(read_into(&mut port, &mut reports, |r| {
            let _ = black_box(r);
        }));
        let _ = black_box(poll_into(&mut port, &mut commands, |r| {
            let _ = black_box(r);
        }));
    }
}
