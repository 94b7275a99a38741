//! `meterstick-uf2 rp2040|rp2350 IN.elf OUT.uf2`: the `.uf2` file a Pico's boot ROM takes by drag
//! and drop (hold BOOTSEL, plug in, copy the file to the drive that appears), converted with
//! `elf2flash-core` (the converter library of crates.io's `elf2flash`; `elf2uf2-rs` 2.2 knows only
//! the RP2040's family ID).
//!
//! Before writing it checks, in the UF2 blocks themselves, what each boot ROM needs to start the
//! image, so that a file a board would ignore is refused here:
//! * every block carries the chip's family ID (RP2040 `0xe48bff56`; RP2350 Arm Secure
//!   `0xe48bff59`) and the blocks number `0..n` without gaps;
//! * RP2350: an IMAGE_DEF block in the first 4 KiB of flash: the start marker `0xffffded3`, an
//!   IMAGE_TYPE item (`0x42`) that says "executable, Arm", and the end marker `0xab123579` within
//!   the block's bounded size (RP2350 datasheet, "Image definitions"; rp235x-hal's `block`
//!   module writes it);
//! * RP2040: the second-stage boot loader at the start of flash, 252 bytes and their CRC-32
//!   (MPEG-2: polynomial `0x04c11db7`, no reflection, initial value all ones), which the boot
//!   ROM verifies before it runs it.
//!
//! The UF2 format: 512-byte blocks, each a 32-byte header (magics `0x0a324655`, `0x9e5d5157`,
//! flags, target address, payload size, block number, number of blocks, family ID), 476 bytes
//! of data (the payload first) and the end magic `0x0ab16f30`.
use std::collections::BTreeMap;
use std::process::ExitCode;

use elf2flash_core::boards::{BoardInfo, RP2040, RP2350};
use elf2flash_core::{NoProgress, elf2uf2};

/// Where the RP2040 and RP2350 map their flash.
const FLASH: u32 = 0x1000_0000;
const RP2040_FAMILY: u32 = 0xe48b_ff56;
const RP2350_ARM_S_FAMILY: u32 = 0xe48b_ff59;

/// The chips this tool writes for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Chip {
    Rp2040,
    Rp2350,
}

/// Why a converted image was refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Refusal {
    /// A block that is not 512 bytes with the UF2 magics.
    NotUf2,
    /// A block with another family ID (or none).
    Family(u32),
    /// Block numbers not `0..n` in order, or `n` not the block count.
    Numbering,
    /// RP2350: no IMAGE_DEF block (start marker, executable Arm image type, end marker) in the
    /// first 4 KiB of flash.
    NoImageDef,
    /// RP2040: no second-stage boot loader whose CRC the boot ROM accepts.
    BadBoot2,
}

impl core::fmt::Display for Refusal {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::NotUf2 => write!(f, "not UF2 blocks"),
            Self::Family(id) => write!(f, "a block with family ID {id:#010x}, not the chip's"),
            Self::Numbering => write!(f, "blocks not numbered 0..n"),
            Self::NoImageDef => write!(
                f,
                "no IMAGE_DEF block (executable, Arm) in the first 4 KiB of flash: the RP2350's boot ROM \
                 would not start it"
            ),
            Self::BadBoot2 => write!(
                f,
                "no second-stage boot loader with a valid CRC at the start of flash: the RP2040's boot \
                 ROM would not start it"
            ),
        }
    }
}

fn word(b: &[u8], at: usize) -> Option<u32> {
    Some(u32::from_le_bytes(b.get(at..at + 4)?.try_into().ok()?))
}

/// The flash image the blocks describe (address -> byte), after checking the family and the
/// numbering.
fn image_of(uf2: &[u8], family: u32) -> Result<BTreeMap<u32, u8>, Refusal> {
    if uf2.is_empty() || !uf2.len().is_multiple_of(512) {
        return Err(Refusal::NotUf2);
    }
    let count = uf2.len() / 512;
    let mut image = BTreeMap::new();
    for (i, block) in uf2.chunks_exact(512).enumerate() {
        let field = |k: usize| word(block, 4 * k).ok_or(Refusal::NotUf2);
        if field(0)? != 0x0a32_4655 || field(1)? != 0x9e5d_5157 || word(block, 508) != Some(0x0ab1_6f30) {
            return Err(Refusal::NotUf2);
        }
        let (flags, addr, size, number, total, fam) =
            (field(2)?, field(3)?, field(4)?, field(5)?, field(6)?, field(7)?);
        if flags & 0x2000 == 0 || fam != family {
            return Err(Refusal::Family(if flags & 0x2000 == 0 { 0 } else { fam }));
        }
        if number as usize != i || total as usize != count || size > 476 {
            return Err(Refusal::Numbering);
        }
        for (k, &b) in block[32..32 + size as usize].iter().enumerate() {
            image.insert(addr + k as u32, b);
        }
    }
    Ok(image)
}

/// The bytes at `addr..addr + n` of `image` (absent bytes: erased flash, 0xff).
fn bytes(image: &BTreeMap<u32, u8>, addr: u32, n: u32) -> Vec<u8> {
    (addr..addr + n).map(|a| image.get(&a).copied().unwrap_or(0xff)).collect()
}

/// RP2350: an IMAGE_DEF block in the first 4 KiB: start marker, then an IMAGE_TYPE item (type
/// byte `0x42`) saying "executable" (bits 0-3 = 1) for Arm (bits 8-10 = 0), and the end marker
/// within 64 words.
fn has_image_def(image: &BTreeMap<u32, u8>) -> bool {
    let first = bytes(image, FLASH, 4096);
    (0..4096 - 8).step_by(4).any(|at| {
        word(&first, at) == Some(0xffff_ded3)
            && word(&first, at + 4).is_some_and(|item| {
                let flags = item >> 16;
                item & 0xff == 0x42 && flags & 0xf == 1 && flags & 0x700 == 0
            })
            && (at + 8..(at + 256).min(4096 - 4)).step_by(4).any(|end| word(&first, end) == Some(0xab12_3579))
    })
}

/// CRC-32/MPEG-2 (polynomial 0x04c11db7, initial value all ones, no reflection, no final xor).
fn crc32_mpeg2(data: &[u8]) -> u32 {
    let mut crc = 0xffff_ffffu32;
    for &b in data {
        crc ^= u32::from(b) << 24;
        for _ in 0..8 {
            crc = if crc & 0x8000_0000 != 0 { (crc << 1) ^ 0x04c1_1db7 } else { crc << 1 };
        }
    }
    crc
}

/// RP2040: the 256 bytes at the start of flash are a boot loader and its CRC.
fn has_boot2(image: &BTreeMap<u32, u8>) -> bool {
    let boot2 = bytes(image, FLASH, 256);
    boot2[..252].iter().any(|&b| b != 0xff) && word(&boot2, 252) == Some(crc32_mpeg2(&boot2[..252]))
}

/// Converts `elf` for `chip` and checks the result.
fn convert(chip: Chip, elf: &[u8]) -> Result<Vec<u8>, String> {
    let board: &dyn BoardInfo = match chip {
        Chip::Rp2040 => &RP2040,
        Chip::Rp2350 => &RP2350,
    };
    let mut uf2 = Vec::new();
    elf2uf2(elf, &mut uf2, board, NoProgress).map_err(|e| format!("converting: {e}"))?;
    let family = match chip {
        Chip::Rp2040 => RP2040_FAMILY,
        Chip::Rp2350 => RP2350_ARM_S_FAMILY,
    };
    let image = image_of(&uf2, family).map_err(|e| e.to_string())?;
    let ok = match chip {
        Chip::Rp2040 => has_boot2(&image).then_some(()).ok_or(Refusal::BadBoot2),
        Chip::Rp2350 => has_image_def(&image).then_some(()).ok_or(Refusal::NoImageDef),
    };
    ok.map_err(|e| e.to_string())?;
    Ok(uf2)
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [chip, input, output] = args.as_slice() else {
        eprintln!("usage: meterstick-uf2 rp2040|rp2350 IN.elf OUT.uf2");
        return ExitCode::from(2);
    };
    let chip = match chip.as_str() {
        "rp2040" => Chip::Rp2040,
        "rp2350" => Chip::Rp2350,
        other => {
            eprintln!("meterstick-uf2: chip {other:?}: rp2040 or rp2350");
            return ExitCode::from(2);
        }
    };
    let result = std::fs::read(input)
        .map_err(|e| format!("reading {input}: {e}"))
        .and_then(|elf| convert(chip, &elf))
        .and_then(|uf2| {
            std::fs::write(output, &uf2).map(|()| uf2.len()).map_err(|e| format!("{output}: {e}"))
        });
    match result {
        Ok(n) => {
            println!("{output}: {n} bytes, {} blocks", n / 512);
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("meterstick-uf2: {input}: {e}");
            ExitCode::FAILURE
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One UF2 block of `payload` at `addr`.
    fn block(addr: u32, payload: &[u8], number: u32, total: u32, family: u32) -> Vec<u8> {
        let mut b = Vec::new();
        for w in [0x0a32_4655, 0x9e5d_5157, 0x2000, addr, payload.len() as u32, number, total, family] {
            b.extend_from_slice(&u32::to_le_bytes(w));
        }
        b.extend_from_slice(payload);
        b.resize(508, 0);
        b.extend_from_slice(&0x0ab1_6f30u32.to_le_bytes());
        b
    }

    #[test]
    fn crc_of_the_check_string() {
        // CRC-32/MPEG-2 of "123456789" (the catalogue's check value).
        assert_eq!(crc32_mpeg2(b"123456789"), 0x0376_e6e7);
    }

    #[test]
    fn image_def_found_and_missing() {
        // rp235x-hal's `ImageDef::secure_exe()`: start marker, IMAGE_TYPE item (EXE, Secure,
        // Arm, RP2350), last item, link, end marker.
        let def: Vec<u8> = [0xffff_ded3u32, 0x1021_0142, 0x0000_01ff, 0, 0xab12_3579]
            .iter()
            .flat_map(|w| w.to_le_bytes())
            .collect();
        let mut payload = vec![0u8; 0x110];
        payload.extend_from_slice(&def);
        let uf2 = block(FLASH, &payload, 0, 1, RP2350_ARM_S_FAMILY);
        assert!(has_image_def(&image_of(&uf2, RP2350_ARM_S_FAMILY).unwrap()));
        let plain = block(FLASH, &[0u8; 256], 0, 1, RP2350_ARM_S_FAMILY);
        assert!(!has_image_def(&image_of(&plain, RP2350_ARM_S_FAMILY).unwrap()));
        assert_eq!(image_of(&uf2, RP2040_FAMILY), Err(Refusal::Family(RP2350_ARM_S_FAMILY)));
    }

    #[test]
    fn boot2_crc_checked() {
        let mut boot2 = vec![0x5au8; 252];
        boot2.extend_from_slice(&crc32_mpeg2(&boot2).to_le_bytes());
        let good = block(FLASH, &boot2, 0, 1, RP2040_FAMILY);
        assert!(has_boot2(&image_of(&good, RP2040_FAMILY).unwrap()));
        boot2[10] ^= 1;
        let bad = block(FLASH, &boot2, 0, 1, RP2040_FAMILY);
        assert!(!has_boot2(&image_of(&bad, RP2040_FAMILY).unwrap()));
    }

    #[test]
    fn numbering_checked() {
        let mut two = block(FLASH, &[0; 256], 0, 2, RP2040_FAMILY);
        two.extend(block(FLASH + 256, &[0; 256], 0, 2, RP2040_FAMILY));
        assert_eq!(image_of(&two, RP2040_FAMILY), Err(Refusal::Numbering));
    }
}
