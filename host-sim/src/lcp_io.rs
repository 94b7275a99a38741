//! Reading one LCP from a file: JSON `{"M": [[row], ...], "q": [...]}` (row-major) or the
//! Siconos `.dat` format (dense or sparse-block; see the corpus README), and solving it
//! with the core solver of the matching const size.
//!
//! **Limits before work.** A file is read through [`crate::input`] with a cap
//! ([`crate::input::LCP_FILE_CAP`]), and every size a file declares (`n`, block counts, block
//! sizes) is checked against [`MAX_N`] and against the others before anything is allocated for
//! it, so a few bytes declaring `n = 10^9` are an error, not an allocation.

use std::path::Path;

use anyhow::{Context as _, bail, ensure};
use meterstick_core::Real;
use meterstick_core::lcp::{Lcp, Lemke};
use meterstick_core::nalgebra::{SMatrix, SVector};
use serde::Serialize;

/// The largest size the `lcp` command solves (the core solver is instantiated for 1..=16).
pub const MAX_N: usize = 16;

/// A dense LCP read from a file, in f64, row-major.
#[derive(Debug, Clone, PartialEq)]
pub struct LcpData {
    /// `M`, row-major: `m[row][col]`.
    pub m: Vec<Vec<f64>>,
    /// `q`.
    pub q: Vec<f64>,
}

impl LcpData {
    /// The size `n`.
    #[must_use]
    pub fn n(&self) -> usize {
        self.q.len()
    }
}

/// The two file formats.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// `{"M": [[row], ...], "q": [...]}`.
    Json,
    /// Siconos `.dat`.
    Siconos,
}

impl Format {
    /// The format a file's name says: `.json` or `.dat` (any case); `None` otherwise.
    #[must_use]
    pub fn of_path(path: &Path) -> Option<Self> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "json" => Some(Self::Json),
            "dat" => Some(Self::Siconos),
            _ => None,
        }
    }

    /// The format a file's content suggests: JSON when it starts with `{`, Siconos otherwise.
    #[must_use]
    pub fn of_text(text: &str) -> Self {
        if text.trim_start().starts_with('{') { Self::Json } else { Self::Siconos }
    }

    /// The format in words, with its shape.
    #[must_use]
    pub const fn describe(self) -> &'static str {
        match self {
            Self::Json => r#"an LCP in JSON ({"M": [[row], ...], "q": [...]})"#,
            Self::Siconos => "an LCP in the Siconos .dat format (n, storage type, sizes, M, q)",
        }
    }
}

/// Reads and parses the LCP file `path`: at most [`crate::input::LCP_FILE_CAP`] bytes, in the
/// format its extension names (`.json`, `.dat`), else the one its content suggests.
///
/// # Errors
/// An unreadable or oversized file, or a malformed LCP: the message names the file, the format
/// expected and why it was chosen, and what was wrong.
pub fn read_file(path: &Path) -> anyhow::Result<LcpData> {
    let text = crate::input::read_text(path, crate::input::LCP_FILE_CAP)?;
    parse_file(path, &text)
}

/// Parses `text`, the content of the file `path`, in the format its extension names, else the
/// one its content suggests (see [`read_file`]).
///
/// # Errors
/// A malformed LCP, naming the file and the format expected.
pub fn parse_file(path: &Path, text: &str) -> anyhow::Result<LcpData> {
    let by_name = Format::of_path(path);
    let format = by_name.unwrap_or_else(|| Format::of_text(text));
    parse_as(format, text).with_context(|| {
        let why = match by_name {
            Some(Format::Json) => "as its name ends in .json",
            Some(Format::Siconos) => "as its name ends in .dat",
            None => "by its content: the name ends in neither .json nor .dat",
        };
        let hint = match by_name {
            Some(f) if f != Format::of_text(text) && !text.trim().is_empty() => {
                if f == Format::Siconos {
                    "; the content looks like JSON"
                } else {
                    "; the content is not JSON"
                }
            }
            _ => "",
        };
        format!("{}: expected {} ({why}{hint})", path.display(), format.describe())
    })
}

/// Parses `text` in `format`.
///
/// # Errors
/// An empty text, or a malformed LCP.
pub fn parse_as(format: Format, text: &str) -> anyhow::Result<LcpData> {
    ensure!(!text.trim().is_empty(), "the file is empty");
    match format {
        Format::Json => parse_json(text),
        Format::Siconos => parse_siconos(text),
    }
}

/// Parses a file's text: JSON when it starts with `{`, the Siconos `.dat` format otherwise.
///
/// # Errors
/// A malformed file, with what was wrong.
pub fn parse(text: &str) -> anyhow::Result<LcpData> {
    parse_as(Format::of_text(text), text)
}

/// Checks a declared size before anything is allocated for it.
fn check_n(n: usize) -> anyhow::Result<()> {
    ensure!(
        (1..=MAX_N).contains(&n),
        "LCP size {n} is not supported: the core solver is built for 1..={MAX_N}"
    );
    Ok(())
}

/// Parses `{"M": [[row], ...], "q": [...]}`.
///
/// # Errors
/// Not JSON, missing fields, ragged or non-square `M`, `q` of another length, or a size
/// outside `1..=MAX_N`.
pub fn parse_json(text: &str) -> anyhow::Result<LcpData> {
    #[derive(serde::Deserialize)]
    struct Raw {
        #[serde(rename = "M")]
        m: Vec<Vec<f64>>,
        q: Vec<f64>,
    }
    let raw: Raw = serde_json::from_str(text).context("parsing the LCP JSON")?;
    let n = raw.q.len();
    ensure!(n > 0, "q is empty");
    check_n(n)?;
    ensure!(raw.m.len() == n, "M has {} rows but q has {} entries", raw.m.len(), n);
    for (i, row) in raw.m.iter().enumerate() {
        ensure!(row.len() == n, "row {i} of M has {} entries, expected {n}", row.len());
    }
    Ok(LcpData { m: raw.m, q: raw.q })
}

struct Tokens<'a> {
    it: std::str::SplitWhitespace<'a>,
}

impl Tokens<'_> {
    fn int(&mut self, name: &str) -> anyhow::Result<usize> {
        let t = self.it.next().with_context(|| format!("the file ends before {name}"))?;
        t.parse().with_context(|| format!("{name} should be a non-negative integer, found {t:?}"))
    }
    /// An integer that counts or indexes something of at most `max` elements.
    fn count(&mut self, name: &str, max: usize) -> anyhow::Result<usize> {
        let v = self.int(name)?;
        ensure!(v <= max, "{name} is {v}, more than {max}");
        Ok(v)
    }
    fn float(&mut self, name: &str) -> anyhow::Result<f64> {
        let t = self.it.next().with_context(|| format!("the file ends before {name}"))?;
        t.parse().with_context(|| format!("{name} should be a number, found {t:?}"))
    }
    /// `len` integers, each at most `max` (`len` checked by the caller).
    fn counts(&mut self, name: &str, len: usize, max: usize) -> anyhow::Result<Vec<usize>> {
        (0..len).map(|_| self.count(name, max)).collect()
    }
}

/// Cumulative block sizes: strictly increasing (no empty block), the last equal to `n`.
fn check_cumulative(name: &str, cum: &[usize], n: usize) -> anyhow::Result<()> {
    let mut prev = 0;
    for &c in cum {
        ensure!(c > prev, "{name} {cum:?}: cumulative sizes must increase (no empty block)");
        prev = c;
    }
    ensure!(prev == n, "{name} {cum:?}: the block sizes add up to {prev}, not n = {n}");
    Ok(())
}

/// Parses the Siconos `.dat` format (`linearComplementarity_newFromFile`): `n`, storage
/// type, sizes, then `M` column-major (dense, type 0) or as a sparse block matrix (type 1),
/// then `q`. Anything after `q` is ignored, as Siconos does. Every declared size is checked
/// (against [`MAX_N`] and the others) before anything is allocated for it.
///
/// # Errors
/// A truncated file, an unsupported storage type, or inconsistent sizes.
pub fn parse_siconos(text: &str) -> anyhow::Result<LcpData> {
    let mut t = Tokens { it: text.split_whitespace() };
    let n = t.int("n")?;
    check_n(n)?;
    let storage = t.int("storage type")?;
    let (rows, cols) = (t.int("size0")?, t.int("size1")?);
    ensure!(rows == n && cols == n, "M is {rows}x{cols} but n = {n}");
    let mut m = vec![vec![0.0; n]; n];
    match storage {
        0 => {
            let (r2, c2) = (t.int("size0")?, t.int("size1")?);
            ensure!(r2 == n && c2 == n, "dense block is {r2}x{c2} but n = {n}");
            for k in 0..n * n {
                m[k % n][k / n] = t.float("an entry of M")?;
            }
        }
        1 => {
            let nbblocks = t.count("nbblocks", n * n)?;
            let brows = t.count("blocknumber0", n)?;
            let bcols = t.count("blocknumber1", n)?;
            let row_cum = t.counts("blocksize0", brows, n)?;
            let col_cum = t.counts("blocksize1", bcols, n)?;
            check_cumulative("blocksize0", &row_cum, n)?;
            check_cumulative("blocksize1", &col_cum, n)?;
            ensure!(nbblocks <= brows * bcols, "nbblocks {nbblocks} exceeds {brows} x {bcols} blocks");
            let (filled1, filled2) = (t.count("filled1", brows + 1)?, t.count("filled2", nbblocks)?);
            ensure!(filled1 == brows + 1 && filled2 == nbblocks, "inconsistent block counts");
            let index1 = t.counts("index1_data", filled1, nbblocks)?;
            let index2 = t.counts("index2_data", filled2, bcols.saturating_sub(1))?;
            let start = |cum: &[usize], b: usize| if b == 0 { 0 } else { cum[b - 1] };
            for brow in 0..brows {
                ensure!(index1[brow] <= index1[brow + 1], "bad row pointers {index1:?}");
                for b in index1[brow]..index1[brow + 1] {
                    let number = t.int("block number")?;
                    ensure!(number == b, "expected block {b}, found {number}");
                    let bcol = index2[b];
                    let (r0, r1) = (start(&row_cum, brow), row_cum[brow]);
                    let (c0, c1) = (start(&col_cum, bcol), col_cum[bcol]);
                    for c in c0..c1 {
                        for r in r0..r1 {
                            m[r][c] = t.float("a block entry")?;
                        }
                    }
                }
            }
        }
        other => bail!("storage type {other} is not supported (0 dense, 1 sparse block)"),
    }
    let q = (0..n).map(|_| t.float("an entry of q")).collect::<anyhow::Result<Vec<_>>>()?;
    Ok(LcpData { m, q })
}

/// Scalar precision of a solve: the core's.
pub use meterstick_core::scene::Precision;

/// The JSON line the `lcp` command prints.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LcpReport {
    /// Problem size.
    pub n: usize,
    /// `solution`, `ray`, `max_pivots`, `non_finite` or `unverified`.
    pub status: &'static str,
    /// The solution, `None` when there is none.
    pub z: Option<Vec<f64>>,
    /// `w = M z + q`, `None` when there is no solution.
    pub w: Option<Vec<f64>>,
    /// Pivots performed.
    pub pivots: u32,
    /// The scalar type used.
    pub precision: Precision,
}

fn solve_sized<T: Real, const N: usize>(data: &LcpData, precision: Precision) -> LcpReport {
    let m = SMatrix::<T, N, N>::from_fn(|i, j| T::of(data.m[i][j]));
    let q = SVector::<T, N>::from_fn(|i, _| T::of(data.q[i]));
    match Lemke::<T, N>::new().solve(&Lcp::new(m, q)) {
        Ok(sol) => LcpReport {
            n: N,
            status: "solution",
            z: Some(sol.z.iter().map(|x| x.as_f64()).collect()),
            w: Some(sol.w.iter().map(|x| x.as_f64()).collect()),
            pivots: sol.pivots,
            precision,
        },
        Err(e) => LcpReport { n: N, status: e.kind(), z: None, w: None, pivots: e.pivots(), precision },
    }
}

/// Solves `data` with the core solver of size `n` in the requested precision.
///
/// # Errors
/// `n` is 0 or above [`MAX_N`].
pub fn solve(data: &LcpData, precision: Precision) -> anyhow::Result<LcpReport> {
    macro_rules! dispatch {
        ($($n:literal)*) => {
            match (data.n(), precision) {
                $(($n, Precision::F32) => Ok(solve_sized::<f32, $n>(data, precision)),
                  ($n, Precision::F64) => Ok(solve_sized::<f64, $n>(data, precision)),)*
                (n, _) => bail!("LCP size {n} is not supported: the core solver is built for 1..={MAX_N}"),
            }
        };
    }
    dispatch!(1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn err(text: &str) -> String {
        format!("{:#}", parse_siconos(text).unwrap_err())
    }

    /// Every declared size is checked before anything is allocated: `n = 10^9` (which would
    /// allocate `10^18` entries), `n = usize::MAX`, a cumulative block size beyond `n`.
    #[test]
    fn declared_sizes_are_checked_before_allocating() {
        assert_eq!(
            err("1000000000 0 1000000000 1000000000"),
            "LCP size 1000000000 is not supported: the core solver is built for 1..=16"
        );
        assert!(
            err("18446744073709551615 1 18446744073709551615 18446744073709551615")
                .contains("size 18446744073709551615")
        );
        let blocks = "3 1 3 3\n1\n2 1\n5 3\n3\n3 1\n0 1 1\n0\n0\n1 2 3 4 5 6 7 8 9\n1 2 3\n";
        assert_eq!(err(blocks), "blocksize0 is 5, more than 3");
        assert_eq!(
            err("3 1 3 3 1 2 1 2 1 3"),
            "blocksize0 [2, 1]: cumulative sizes must increase (no empty block)"
        );
        assert_eq!(err("2 1 2 2 3 1 1 2 2 2 3"), "nbblocks 3 exceeds 1 x 1 blocks");
        assert_eq!(err("2 1 2 2 1 1 1 2 2 2 1 0 1 5"), "index2_data is 5, more than 0");
        assert_eq!(err("0 0 0 0"), "LCP size 0 is not supported: the core solver is built for 1..=16");
    }

    /// The format is the one the name says, then the content; the message says which and why
    /// (an empty `.json` file is an empty JSON file, not a truncated Siconos one).
    #[test]
    fn the_format_follows_the_name_then_the_content() {
        let e = |name: &str, text: &str| format!("{:#}", parse_file(Path::new(name), text).unwrap_err());
        assert_eq!(
            e("a.json", ""),
            r#"a.json: expected an LCP in JSON ({"M": [[row], ...], "q": [...]}) (as its name ends in .json): the file is empty"#
        );
        assert!(e("a.JSON", " \n").ends_with("(as its name ends in .json): the file is empty"));
        assert!(
            e("a.dat", r#"{"M": [[1]], "q": [1]}"#)
                .contains("(as its name ends in .dat; the content looks like JSON): n should be")
        );
        assert!(
            e("a.json", "1 0 1 1 1 1 2 -1")
                .contains("(as its name ends in .json; the content is not JSON): parsing the LCP JSON")
        );
        assert!(e("a.txt", "").contains("Siconos .dat format (n, storage type, sizes, M, q) (by its content: the name ends in neither .json nor .dat)"));
        let ok = parse_file(Path::new("a.txt"), r#"{"M": [[2]], "q": [-1]}"#).unwrap();
        assert_eq!((ok.m, ok.q), (vec![vec![2.0]], vec![-1.0]));
    }

    /// A sparse-block file with a block left out (zero) reads as its dense twin.
    #[test]
    fn sparse_blocks_read_as_dense() {
        // n = 3, blocks rows [0..2, 2..3] x cols [0..1, 1..3]; stored: (0,0), (0,1), (1,1).
        let sparse = "3 1 3 3 3 2 2 2 3 1 3 3 3 0 2 3 0 1 1 0 1 2 1 3 4 5 6 2 7 8 -1 -2 -3";
        let d = parse_siconos(sparse).unwrap();
        assert_eq!(d.m, vec![vec![1.0, 3.0, 5.0], vec![2.0, 4.0, 6.0], vec![0.0, 7.0, 8.0]]);
        assert_eq!(d.q, vec![-1.0, -2.0, -3.0]);
        let dense = "3 0 3 3 3 3 1 2 0 3 4 7 5 6 8 -1 -2 -3";
        assert_eq!(parse_siconos(dense).unwrap(), d);
    }
}
