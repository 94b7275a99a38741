//! Reading one LCP from a file: JSON `{"M": [[row], ...], "q": [...]}` (row-major) or the
//! Siconos `.dat` format (dense or sparse-block; see the corpus README), and solving it
//! with the core solver of the matching const size.

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

/// Parses a file's text: JSON when it starts with `{`, the Siconos `.dat` format otherwise.
///
/// # Errors
/// A malformed file, with what was wrong.
pub fn parse(text: &str) -> anyhow::Result<LcpData> {
    if text.trim_start().starts_with('{') { parse_json(text) } else { parse_siconos(text) }
}

/// Parses `{"M": [[row], ...], "q": [...]}`.
///
/// # Errors
/// Not JSON, missing fields, ragged or non-square `M`, or `q` of another length.
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
    ensure!(raw.m.len() == n, "M has {} rows but q has {} entries", raw.m.len(), n);
    for (i, row) in raw.m.iter().enumerate() {
        ensure!(row.len() == n, "row {i} of M has {} entries, expected {n}", row.len());
    }
    Ok(LcpData { m: raw.m, q: raw.q })
}

struct Tokens<'a> {
    it: std::str::SplitWhitespace<'a>,
    what: &'static str,
}

impl Tokens<'_> {
    fn int(&mut self, name: &str) -> anyhow::Result<usize> {
        let t = self.it.next().with_context(|| format!("{}: file ends before {name}", self.what))?;
        t.parse()
            .with_context(|| format!("{}: {name} should be a non-negative integer, found {t:?}", self.what))
    }
    fn float(&mut self, name: &str) -> anyhow::Result<f64> {
        let t = self.it.next().with_context(|| format!("{}: file ends before {name}", self.what))?;
        t.parse().with_context(|| format!("{}: {name} should be a number, found {t:?}", self.what))
    }
}

/// Parses the Siconos `.dat` format (`linearComplementarity_newFromFile`): `n`, storage
/// type, sizes, then `M` column-major (dense, type 0) or as a sparse block matrix (type 1),
/// then `q`. Anything after `q` is ignored, as Siconos does.
///
/// # Errors
/// A truncated file, an unsupported storage type, or inconsistent sizes.
pub fn parse_siconos(text: &str) -> anyhow::Result<LcpData> {
    let mut t = Tokens { it: text.split_whitespace(), what: "Siconos .dat" };
    let n = t.int("n")?;
    ensure!(n > 0, "n is 0");
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
            let nbblocks = t.int("nbblocks")?;
            let (brows, bcols) = (t.int("blocknumber0")?, t.int("blocknumber1")?);
            let row_cum = (0..brows).map(|_| t.int("blocksize0")).collect::<anyhow::Result<Vec<_>>>()?;
            let col_cum = (0..bcols).map(|_| t.int("blocksize1")).collect::<anyhow::Result<Vec<_>>>()?;
            ensure!(
                row_cum.last() == Some(&n) && col_cum.last() == Some(&n),
                "block sizes do not add up to n = {n}"
            );
            let (filled1, filled2) = (t.int("filled1")?, t.int("filled2")?);
            ensure!(filled1 == brows + 1 && filled2 == nbblocks, "inconsistent block counts");
            let index1 = (0..filled1).map(|_| t.int("index1_data")).collect::<anyhow::Result<Vec<_>>>()?;
            let index2 = (0..filled2).map(|_| t.int("index2_data")).collect::<anyhow::Result<Vec<_>>>()?;
            let start = |cum: &[usize], b: usize| if b == 0 { 0 } else { cum[b - 1] };
            for brow in 0..brows {
                ensure!(index1[brow] <= index1[brow + 1] && index1[brow + 1] <= nbblocks, "bad row pointers");
                for b in index1[brow]..index1[brow + 1] {
                    let number = t.int("block number")?;
                    ensure!(number == b, "expected block {b}, found {number}");
                    let bcol = index2[b];
                    ensure!(bcol < bcols, "block column {bcol} out of range");
                    let (r0, r1) = (start(&row_cum, brow), row_cum[brow]);
                    let (c0, c1) = (start(&col_cum, bcol), col_cum[bcol]);
                    ensure!(r0 < r1 && c0 < c1, "empty or decreasing block sizes");
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

/// Scalar precision of a solve.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, clap::ValueEnum, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Precision {
    /// `f32`, as on the microcontroller.
    #[default]
    F32,
    /// `f64`.
    F64,
}

impl Precision {
    /// `f32` or `f64`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::F32 => "f32",
            Self::F64 => "f64",
        }
    }
}

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
