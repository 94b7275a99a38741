//! Reading an input file with a size cap: every file `host-sim` reads goes through [`read`] or
//! [`read_text`], so no input (a device such as `/dev/zero`, a file that grows while it is read,
//! a mistaken multi-gigabyte file) can exhaust the machine's memory or keep `host-sim` reading
//! for ever. The cap is enforced on the bytes actually read (`take(cap + 1)`), not on
//! `metadata().len()`, which is 0 for a device or a pipe. A file `host-sim serve` sends is not
//! read whole: [`open`] takes regular files only, with their length from the metadata, and the
//! server sends exactly that many bytes, a chunk at a time.

use std::io::Read as _;
use std::path::Path;

use anyhow::Context as _;

/// The largest LCP file `host-sim lcp` reads: 1 MiB (a 16 x 16 LCP in either format is a few
/// kilobytes).
pub const LCP_FILE_CAP: u64 = 1 << 20;

/// The largest firmware ELF `host-sim qemu` reads: 64 MiB (the firmware's are about 1-3 MB with
/// debug information).
pub const ELF_FILE_CAP: u64 = 64 << 20;

/// The largest `summary.json` `host-sim serve --replay` reads: 64 MiB.
pub const SUMMARY_FILE_CAP: u64 = 64 << 20;

/// The largest file `host-sim serve` sends: 1 GiB (a `core.csv` of a 10^6-step run is about
/// 200 MB). It is sent in chunks ([`open`]), never held whole.
pub const SERVED_FILE_CAP: u64 = 1 << 30;

/// `n` bytes in words (`1 MiB`, `64 MiB`, `512 bytes`).
#[must_use]
pub fn bytes_text(n: u64) -> String {
    if n >= 1 << 30 && n.is_multiple_of(1 << 30) {
        format!("{} GiB", n >> 30)
    } else if n >= 1 << 20 && n.is_multiple_of(1 << 20) {
        format!("{} MiB", n >> 20)
    } else if n >= 1 << 10 && n.is_multiple_of(1 << 10) {
        format!("{} KiB", n >> 10)
    } else {
        format!("{n} bytes")
    }
}

/// Reads at most `cap` bytes of `path`.
///
/// # Errors
/// The file cannot be opened or read (naming it), or it holds more than `cap` bytes (naming the
/// file and the cap; reading stops at `cap + 1` bytes).
pub fn read(path: &Path, cap: u64) -> anyhow::Result<Vec<u8>> {
    let file = std::fs::File::open(path).with_context(|| format!("reading {}", path.display()))?;
    let mut bytes = Vec::new();
    file.take(cap.saturating_add(1))
        .read_to_end(&mut bytes)
        .with_context(|| format!("reading {}", path.display()))?;
    anyhow::ensure!(
        bytes.len() as u64 <= cap,
        "reading {}: larger than the {} this input may have (reading stopped there)",
        path.display(),
        bytes_text(cap)
    );
    Ok(bytes)
}

/// Opens `path`, a regular file of at most `cap` bytes, to be read a chunk at a time: the file
/// and its length (read no further than that, so a file that grows while it is read ends there).
///
/// # Errors
/// The file cannot be opened (naming it), is not a regular file, or holds more than `cap` bytes
/// (naming the file and the cap).
pub fn open(path: &Path, cap: u64) -> anyhow::Result<(std::fs::File, u64)> {
    let file = std::fs::File::open(path).with_context(|| format!("reading {}", path.display()))?;
    let meta = file.metadata().with_context(|| format!("reading {}", path.display()))?;
    anyhow::ensure!(meta.is_file(), "reading {}: not a regular file", path.display());
    anyhow::ensure!(
        meta.len() <= cap,
        "reading {}: larger than the {} this input may have ({} bytes)",
        path.display(),
        bytes_text(cap),
        meta.len()
    );
    Ok((file, meta.len()))
}

/// Reads at most `cap` bytes of `path` as UTF-8 text.
///
/// # Errors
/// As [`read`], or the file is not UTF-8 text (naming it and the first bad byte's offset).
pub fn read_text(path: &Path, cap: u64) -> anyhow::Result<String> {
    let bytes = read(path, cap)?;
    String::from_utf8(bytes).map_err(|e| {
        anyhow::anyhow!(
            "reading {}: not UTF-8 text (byte {} is not valid UTF-8)",
            path.display(),
            e.utf8_error().valid_up_to()
        )
    })
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    /// `/dev/zero` as an input: refused after `cap + 1` bytes, naming the file and the cap.
    /// Before this helper, `host-sim lcp /dev/zero` read without end (`read_to_string` with no
    /// cap) and was killed by a 5 s timeout.
    #[test]
    #[cfg(unix)]
    fn a_device_without_end_is_refused_at_the_cap() {
        let e = read(Path::new("/dev/zero"), 4096).unwrap_err().to_string();
        assert_eq!(e, "reading /dev/zero: larger than the 4 KiB this input may have (reading stopped there)");
    }

    #[test]
    fn a_file_of_exactly_the_cap_is_read_and_one_byte_more_is_not() {
        let path = std::env::temp_dir().join(format!("ms17-input-{}", std::process::id()));
        std::fs::write(&path, [b'x'; 100]).unwrap();
        assert_eq!(read(&path, 100).unwrap().len(), 100);
        let e = read(&path, 99).unwrap_err().to_string();
        assert!(e.contains("larger than the 99 bytes"), "{e}");
        std::fs::write(&path, [0xff, 0xfe]).unwrap();
        let e = read_text(&path, 100).unwrap_err().to_string();
        assert!(e.ends_with("not UTF-8 text (byte 0 is not valid UTF-8)"), "{e}");
        std::fs::remove_file(&path).unwrap();
        let e = read(&path, 100).unwrap_err();
        assert_eq!(e.to_string(), format!("reading {}", path.display()));
    }

    #[test]
    fn open_gives_the_length_and_refuses_above_the_cap() {
        let path = std::env::temp_dir().join(format!("ms17-open-{}", std::process::id()));
        std::fs::write(&path, [b'x'; 100]).unwrap();
        assert_eq!(open(&path, 100).unwrap().1, 100);
        let e = open(&path, 99).unwrap_err().to_string();
        assert!(e.ends_with("larger than the 99 bytes this input may have (100 bytes)"), "{e}");
        std::fs::remove_file(&path).unwrap();
        assert_eq!(open(&path, 100).unwrap_err().to_string(), format!("reading {}", path.display()));
    }

    #[test]
    #[cfg(unix)]
    fn open_refuses_a_device() {
        let e = open(Path::new("/dev/zero"), 4096).unwrap_err().to_string();
        assert_eq!(e, "reading /dev/zero: not a regular file");
    }

    #[test]
    fn sizes_read_as_words() {
        assert_eq!(bytes_text(LCP_FILE_CAP), "1 MiB");
        assert_eq!(bytes_text(ELF_FILE_CAP), "64 MiB");
        assert_eq!(bytes_text(SERVED_FILE_CAP), "1 GiB");
        assert_eq!(bytes_text(4096), "4 KiB");
        assert_eq!(bytes_text(1000), "1000 bytes");
    }
}
