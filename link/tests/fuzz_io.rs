//! Fuzz target: the reading side of the link over misbehaving byte streams. `read_into` and
//! `poll_into` (what the rig's main loop and a host call) are fed arbitrary streams (valid frames,
//! damaged frames and garbage) by readers that return random chunk sizes, fail at random
//! (`Err`: nothing fed), are not ready at random (`poll_into` must not read then), and claim to
//! have read more than the buffer holds. The messages delivered must be exactly those of the
//! same bytes fed at once to a fresh decoder (`FrameDecoder::feed`, itself checked against a
//! model in `proptest.rs`), every call reads at most `READ_CHUNK` bytes, and the counters add up;
//! the work is bounded (a call per chunk, no spinning). The decoder's own fuzz targets (arbitrary
//! bytes, damaged streams, garbage around frames) are in `proptest.rs`.
//!
//! Inputs: `MS_FUZZ_CASES` (default 2,000); prints how many were tried.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    clippy::indexing_slicing,
    clippy::arithmetic_side_effects,
    clippy::as_conversions,
    clippy::cast_possible_truncation,
    clippy::type_complexity,
    clippy::single_match_else
)]

mod common;

use common::{all_commands, all_reports};
use meterstick_link::{
    Command, FrameDecoder, FrameError, MAX_FRAME, READ_CHUNK, Report, encode, poll_into, read_into,
};
use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};

/// What a reader does on one call.
#[derive(Debug, Clone, Copy)]
enum Step {
    /// Return up to this many bytes (at least 1 while bytes remain).
    Give(usize),
    /// Fail.
    Fail,
    /// `read_ready` says no.
    NotReady,
    /// Claim to have read more than the buffer holds (a broken driver).
    Overclaim,
}

/// A reader following a script (repeated), over a byte stream; counts what it handed out.
struct Scripted<'a> {
    bytes: &'a [u8],
    at: usize,
    script: &'a [Step],
    next: usize,
    ready: bool,
    /// Bytes actually placed in a caller's buffer (and so fed).
    handed: Vec<u8>,
    reads: usize,
}

impl Scripted<'_> {
    fn step(&mut self) -> Step {
        let s = self.script[self.next % self.script.len()];
        self.next += 1;
        s
    }
}

impl embedded_io::ErrorType for Scripted<'_> {
    type Error = embedded_io::ErrorKind;
}

impl embedded_io::Read for Scripted<'_> {
    fn read(&mut self, buf: &mut [u8]) -> Result<usize, Self::Error> {
        self.reads += 1;
        let left = self.bytes.len() - self.at;
        let (n, claim) = match self.step() {
            Step::Fail => return Err(embedded_io::ErrorKind::Other),
            Step::NotReady | Step::Give(_) if left == 0 => (0, 0),
            Step::Give(k) => {
                let n = k.clamp(1, buf.len()).min(left);
                (n, n)
            }
            Step::NotReady => (1, 1),
            // A broken driver: it filled the whole buffer and claims more.
            Step::Overclaim if left >= buf.len() => (buf.len(), buf.len() + 1 + self.next),
            Step::Overclaim => (left, left),
        };
        buf[..n].copy_from_slice(&self.bytes[self.at..self.at + n]);
        self.handed.extend_from_slice(&buf[..n]);
        self.at += n;
        Ok(claim)
    }
}

impl embedded_io::ReadReady for Scripted<'_> {
    fn read_ready(&mut self) -> Result<bool, Self::Error> {
        self.ready = !matches!(self.script[self.next % self.script.len()], Step::NotReady);
        if !self.ready {
            self.next += 1;
        }
        Ok(self.ready)
    }
}

fn step() -> impl Strategy<Value = Step> {
    prop_oneof![
        8 => (1usize..80).prop_map(Step::Give),
        1 => Just(Step::Fail),
        1 => Just(Step::NotReady),
        1 => Just(Step::Overclaim),
    ]
}

fn stream() -> impl Strategy<Value = Vec<u8>> {
    let commands = all_commands();
    let reports = all_reports();
    let part = prop_oneof![
        3 => prop::sample::select(commands).prop_map(|c| frame(&c)),
        3 => prop::sample::select(reports).prop_map(|r| frame(&r)),
        2 => prop::collection::vec(any::<u8>(), 0..100),
        1 => prop::collection::vec(prop_oneof![3 => 1u8..=255, 1 => Just(0u8)], 0..200),
        1 => (prop::sample::select(all_reports()), any::<prop::sample::Index>(), any::<u8>()).prop_map(
            |(r, at, b)| {
                let mut f = frame(&r);
                let i = at.index(f.len());
                f[i] = b;
                f
            }
        ),
    ];
    prop::collection::vec(part, 0..40).prop_map(|parts| parts.concat())
}

fn frame<M: serde::Serialize>(m: &M) -> Vec<u8> {
    let mut buf = [0u8; MAX_FRAME];
    encode(m, &mut buf).unwrap().to_vec()
}

/// Feeds `stream` through `read_into` (or `poll_into`) with the scripted reader until it is
/// exhausted; returns the results and the bytes that were fed.
fn through<M: serde::de::DeserializeOwned>(
    bytes: &[u8],
    script: &[Step],
    poll: bool,
) -> Result<(Vec<Result<M, FrameError>>, Vec<u8>, FrameDecoder<M>), TestCaseError> {
    let mut r = Scripted { bytes, at: 0, script, next: 0, ready: true, handed: Vec::new(), reads: 0 };
    let mut dec = FrameDecoder::<M>::new();
    let mut got = Vec::new();
    // Each call moves at least one step of the script; a script of only failures and
    // not-ready steps would never end, so the calls are bounded.
    let bound = 4 * (bytes.len() + 1) * script.len().max(1) + 16;
    let mut calls = 0;
    while r.at < bytes.len() {
        calls += 1;
        prop_assert!(calls <= bound, "no progress after {} calls", calls);
        let before = r.handed.len();
        let reads_before = r.reads;
        let res = if poll {
            poll_into(&mut r, &mut dec, |m| got.push(m))
        } else {
            read_into(&mut r, &mut dec, |m| got.push(m))
        };
        let fed = r.handed.len() - before;
        match res {
            Ok(n) => {
                prop_assert!(n <= READ_CHUNK, "{} bytes in one call", n);
                prop_assert_eq!(n, fed, "returned {} but {} were handed over", n, fed);
            }
            Err(_) => prop_assert_eq!(fed, 0, "an error fed bytes"),
        }
        if poll && !r.ready {
            prop_assert_eq!(r.reads, reads_before, "poll_into read while not ready");
        }
        prop_assert!(r.reads <= reads_before + 1, "more than one read per call");
        if script.iter().all(|s| matches!(s, Step::Fail | Step::NotReady)) {
            break;
        }
    }
    Ok((got, r.handed, dec))
}

fn same<M: PartialEq + std::fmt::Debug + serde::Serialize>(
    a: &[Result<M, FrameError>],
    b: &[Result<M, FrameError>],
) -> Result<(), TestCaseError> {
    prop_assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(b) {
        match (x, y) {
            (Ok(x), Ok(y)) => prop_assert!(common::same_bits(x, y), "{:?} vs {:?}", x, y),
            (Err(x), Err(y)) => prop_assert_eq!(x, y),
            _ => prop_assert!(false, "{:?} vs {:?}", x, y),
        }
    }
    Ok(())
}

#[test]
fn fuzz_reading_over_misbehaving_streams() {
    let cases = std::env::var("MS_FUZZ_CASES").ok().and_then(|s| s.trim().parse().ok()).unwrap_or(2000);
    let mut runner = TestRunner::new(Config { cases, failure_persistence: None, ..Config::default() });
    let tried = std::cell::Cell::new(0_u64);
    let delivered = std::cell::Cell::new(0_u64);
    let result = runner.run(
        &(stream(), prop::collection::vec(step(), 1..12), any::<bool>()),
        |(bytes, script, poll)| {
            tried.set(tried.get() + 1);
            // Reports as the host reads them, commands as the rig does.
            let (got, fed, dec) = through::<Report>(&bytes, &script, poll)?;
            let mut whole = FrameDecoder::<Report>::new();
            let mut want = Vec::new();
            whole.feed(&fed, |m| want.push(m));
            same(&got, &want)?;
            prop_assert_eq!(dec.stats(), whole.stats());
            prop_assert_eq!(dec.stats().bytes as usize, fed.len());
            delivered.set(delivered.get() + got.iter().filter(|r| r.is_ok()).count() as u64);
            let (got, fed, _) = through::<Command>(&bytes, &script, poll)?;
            let mut whole = FrameDecoder::<Command>::new();
            let mut want = Vec::new();
            whole.feed(&fed, |m| want.push(m));
            same(&got, &want)?;
            Ok(())
        },
    );
    println!(
        "link reading (read_into/poll_into): {} inputs tried, {} reports delivered",
        tried.get(),
        delivered.get()
    );
    result.unwrap();
    assert!(tried.get() >= u64::from(cases));
    assert!(delivered.get() >= u64::from(cases), "too few frames got through: {}", delivered.get());
}
