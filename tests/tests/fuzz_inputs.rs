//! Fuzz targets for every parser of user input in `host-sim`: the LCP JSON reader, the Siconos
//! `.dat` reader (each through `lcp_io::parse_file` as `host-sim lcp` calls it, then solved), and
//! the command line (`cli::parse_from` on argument vectors built from the real flag names with
//! random and edge values, then the scene flags resolved and validated as `run`, `scene` and `map`
//! do before anything runs). The link protocol's targets are in `link/tests/proptest.rs` and
//! `link/tests/fuzz_io.rs`.
//!
//! Every input must end without a panic, within [`TIME_BOUND`], and allocate at most
//! [`alloc_bound`] bytes while it is parsed (a counting allocator measures this thread's peak);
//! what a parser accepts must be consistent (an `n x n` LCP with `1 <= n <= 16`; a generated
//! valid file parses back to the matrix it was written from; resolved scenes validate, stay
//! within the step cap and have short, distinct folder names). Each target prints how many inputs
//! it tried and how they ended.
//!
//! Inputs per target: `MS_FUZZ_CASES` (default 2,000 each, in the test command); a long run:
//! `MS_FUZZ_CASES=200000 cargo test --release -p meterstick-tests --test fuzz_inputs -- --nocapture`.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, unsafe_code)]

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::collections::BTreeMap;
use std::path::Path;
use std::time::{Duration, Instant};

use meterstick_host_sim::cli::{self, Cmd};
use meterstick_host_sim::commands::{map, run as run_command};
use meterstick_host_sim::lcp_io::{self, LcpData, MAX_N, Precision};
use meterstick_host_sim::monitor;
use meterstick_host_sim::scenes::{MAX_STEPS, ParamsExt as _, SceneArgs};
use meterstick_tests::corpus_dir;
use proptest::prelude::*;
use proptest::test_runner::{Config, TestCaseError, TestRunner};

/// The longest one input may take (parse, solve or resolve; a debug build on a loaded machine).
const TIME_BOUND: Duration = Duration::from_secs(2);

/// The most a parse of `len` bytes may allocate: a few times the text (numbers become `f64`s in
/// vectors that double) plus a fixed allowance, far below `input::LCP_FILE_CAP` for these inputs.
const fn alloc_bound(len: usize) -> usize {
    16 * len + (64 << 10)
}

// ---- a counting allocator: this thread's live bytes and their peak ----

struct Counting;

thread_local! {
    static LIVE: Cell<isize> = const { Cell::new(0) };
    static PEAK: Cell<isize> = const { Cell::new(0) };
}

fn track(delta: isize) {
    let _ = LIVE.try_with(|live| {
        let now = live.get() + delta;
        live.set(now);
        let _ = PEAK.try_with(|peak| peak.set(peak.get().max(now)));
    });
}

// SAFETY: every call is forwarded to `System` unchanged; only the sizes are counted.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            track(layout.size().cast_signed());
        }
        p
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc_zeroed(layout) };
        if !p.is_null() {
            track(layout.size().cast_signed());
        }
        p
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        track(-layout.size().cast_signed());
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if !p.is_null() {
            track(new_size.cast_signed() - layout.size().cast_signed());
        }
        p
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Runs `f` and returns its result, the most bytes this thread held beyond what it held before,
/// and the time it took.
fn measured<R>(f: impl FnOnce() -> R) -> (R, usize, Duration) {
    let base = LIVE.with(Cell::get);
    PEAK.with(|p| p.set(base));
    let started = Instant::now();
    let r = f();
    let took = started.elapsed();
    let peak = PEAK.with(Cell::get) - base;
    (r, usize::try_from(peak).unwrap_or(0), took)
}

// ---- the runner: counts, tallies, bounds ----

fn cases() -> u32 {
    std::env::var("MS_FUZZ_CASES").ok().and_then(|s| s.trim().parse().ok()).unwrap_or(2000)
}

/// Runs `cases()` inputs of `strategy` through `check` (which returns what happened to the
/// input), prints the count and the tally, and returns the tally.
fn fuzz<S: Strategy>(
    name: &str,
    strategy: S,
    check: impl Fn(&S::Value) -> Result<&'static str, TestCaseError>,
) -> BTreeMap<&'static str, u32> {
    let cases = cases();
    let mut runner = TestRunner::new(Config { cases, failure_persistence: None, ..Config::default() });
    let tally = std::cell::RefCell::new(BTreeMap::<&'static str, u32>::new());
    let tried = Cell::new(0_u64);
    let slowest = Cell::new(Duration::ZERO);
    let started = Instant::now();
    let result = runner.run(&strategy, |v| {
        tried.set(tried.get() + 1);
        let t = Instant::now();
        let what = check(&v)?;
        slowest.set(slowest.get().max(t.elapsed()));
        *tally.borrow_mut().entry(what).or_default() += 1;
        Ok(())
    });
    let tally = tally.into_inner();
    println!(
        "{name}: {} inputs tried in {:.1} s (slowest {:.1} ms): {tally:?}",
        tried.get(),
        started.elapsed().as_secs_f64(),
        1e3 * slowest.get().as_secs_f64()
    );
    if let Err(e) = result {
        panic!("{name}: {e}");
    }
    assert!(tried.get() >= u64::from(cases), "{name}: {} of {cases} inputs ran", tried.get());
    tally
}

// ---- the LCP readers ----

/// An LCP, read back: consistent sizes.
fn consistent(data: &LcpData) -> Result<(), TestCaseError> {
    let n = data.n();
    prop_assert!((1..=MAX_N).contains(&n), "accepted n = {}", n);
    prop_assert_eq!(data.m.len(), n);
    prop_assert!(data.m.iter().all(|row| row.len() == n), "ragged M accepted");
    Ok(())
}

/// Parses `text` as the file `name`, checks the bounds and the result, solves what was accepted.
fn lcp_input(name: &str, text: &str) -> Result<&'static str, TestCaseError> {
    let (parsed, bytes, took) = measured(|| lcp_io::parse_file(Path::new(name), text));
    prop_assert!(took <= TIME_BOUND, "{} bytes took {:?}", text.len(), took);
    prop_assert!(bytes <= alloc_bound(text.len()), "{} bytes of input allocated {} bytes", text.len(), bytes);
    match parsed {
        Ok(data) => {
            consistent(&data)?;
            let (solved, _, took) =
                measured(|| (lcp_io::solve(&data, Precision::F64), lcp_io::solve(&data, Precision::F32)));
            prop_assert!(took <= TIME_BOUND, "solving took {:?}", took);
            let (a, b) = solved;
            prop_assert!(a.is_ok() && b.is_ok(), "an accepted LCP must be solvable or say why");
            Ok("accepted and solved")
        }
        Err(e) => {
            let msg = format!("{e:#}");
            prop_assert!(msg.starts_with(&format!("{name}: expected an LCP")), "{}", msg);
            Ok("refused")
        }
    }
}

/// A number as a file may hold it: ordinary, edge, or not a number at all.
fn number_text() -> impl Strategy<Value = String> {
    prop_oneof![
        6 => (-1e3..1e3f64).prop_map(|x| format!("{x}")),
        2 => (-5i64..6).prop_map(|x| x.to_string()),
        1 => prop::sample::select(vec![
            "0", "-0", "1e308", "-1e308", "1e999", "5e-324", "nan", "NaN", "inf", "-inf", "infinity",
            "1e", "--1", "0x10", "1_000", "", "1.5.2", "\u{2212}1", "9".repeat(400).leak(),
        ])
        .prop_map(str::to_owned),
    ]
}

/// An integer as a header may hold it: small, at the limits, huge, or not an integer.
fn int_text() -> impl Strategy<Value = String> {
    prop_oneof![
        6 => (0usize..20).prop_map(|x| x.to_string()),
        1 => prop::sample::select(vec![
            "16", "17", "1000000000", "4294967296", "18446744073709551615", "18446744073709551616",
            "-1", "1.0", "x", "", "99999999999999999999999999",
        ])
        .prop_map(str::to_owned),
    ]
}

/// A random LCP in the JSON format, possibly malformed: `n` rows of about `n` entries.
fn json_text() -> impl Strategy<Value = String> {
    let nums = prop_oneof![
        2 => prop::collection::vec((-1e3..1e3f64).prop_map(|x| format!("{x}")), 0..420),
        1 => prop::collection::vec(number_text(), 0..420),
    ];
    (0usize..20, nums, 0u8..8).prop_map(|(n, nums, shape)| {
        let mut it = nums.into_iter().cycle();
        let mut row = |len: usize| {
            (0..len).map(|_| it.next().unwrap_or_else(|| "1".into())).collect::<Vec<_>>().join(",")
        };
        let m: Vec<String> =
            (0..n).map(|i| format!("[{}]", row(if shape == 1 && i == 0 { n + 1 } else { n }))).collect();
        let q = row(if shape == 2 { n.saturating_sub(1) } else { n });
        match shape {
            3 => format!(r#"{{"M": [{}]}}"#, m.join(",")),
            4 => format!(r#"{{"M": [{}], "q": [{q}], "extra": {{"x": [1, 2]}}}}"#, m.join(",")),
            5 => format!(r#"{{"M": "{}", "q": [{q}]}}"#, m.join(",")),
            6 => format!(r#"{{"M": [{}], "q": [{q}]"#, m.join(",")),
            _ => format!(r#"{{"M": [{}], "q": [{q}]}}"#, m.join(",")),
        }
    })
}

/// A valid LCP (`1 <= n <= 16`) and its Siconos text, dense or in sparse blocks (random block
/// sizes, random zero blocks left out): `(M row-major, q, text)`.
fn valid_siconos() -> impl Strategy<Value = (Vec<Vec<f64>>, Vec<f64>, String)> {
    (1usize..=16)
        .prop_flat_map(|n| {
            (
                Just(n),
                prop::collection::vec(-100i32..100, n * n),
                prop::collection::vec(-100i32..100, n),
                any::<bool>(),
                prop::collection::vec(any::<bool>(), 2 * n),
                prop::collection::vec(any::<bool>(), n * n),
            )
        })
        .prop_map(|(n, m, q, dense, cuts, keep)| {
            let m: Vec<Vec<f64>> =
                (0..n).map(|r| (0..n).map(|c| f64::from(m[r * n + c]) / 4.0).collect()).collect();
            let q: Vec<f64> = q.iter().map(|&x| f64::from(x) / 4.0).collect();
            let qs: Vec<String> = q.iter().map(ToString::to_string).collect();
            if dense {
                let cols: Vec<String> = (0..n)
                    .map(|c| (0..n).map(|r| m[r][c].to_string()).collect::<Vec<_>>().join(" "))
                    .collect();
                let text = format!("{n} 0 {n} {n} {n} {n}\n{}\n{}\n", cols.join("\n"), qs.join(" "));
                return (m, q, text);
            }
            // Block boundaries: a cut after index i (0 < i < n) where cuts[i] says so.
            let bounds = |off: usize| -> Vec<usize> {
                (1..n).filter(|&i| cuts[off + i]).chain(std::iter::once(n)).collect()
            };
            let (rows, cols) = (bounds(0), bounds(n));
            let start = |cum: &[usize], b: usize| if b == 0 { 0 } else { cum[b - 1] };
            let mut index1 = vec![0];
            let (mut index2, mut blocks) = (Vec::new(), Vec::new());
            let mut shown = m.clone();
            for br in 0..rows.len() {
                for bc in 0..cols.len() {
                    let (r0, r1, c0, c1) = (start(&rows, br), rows[br], start(&cols, bc), cols[bc]);
                    if keep[br * cols.len() + bc] || (br == 0 && bc == 0) {
                        let vals: Vec<String> = (c0..c1)
                            .flat_map(|c| (r0..r1).map(move |r| (r, c)))
                            .map(|(r, c)| m[r][c].to_string())
                            .collect();
                        blocks.push(format!("{} {}", index2.len(), vals.join(" ")));
                        index2.push(bc);
                    } else {
                        for row in &mut shown[r0..r1] {
                            for x in &mut row[c0..c1] {
                                *x = 0.0;
                            }
                        }
                    }
                }
                index1.push(index2.len());
            }
            let join = |v: &[usize]| v.iter().map(usize::to_string).collect::<Vec<_>>().join(" ");
            let text = format!(
                "{n} 1 {n} {n}\n{}\n{} {}\n{}\n{}\n{} {}\n{}\n{}\n{}\n{}\n",
                index2.len(),
                rows.len(),
                cols.len(),
                join(&rows),
                join(&cols),
                index1.len(),
                index2.len(),
                join(&index1),
                join(&index2),
                blocks.join("\n"),
                qs.join(" ")
            );
            (shown, q, text)
        })
}

/// A token-level mutation of a text: replace, delete or duplicate a token, or cut the text.
fn mutate(text: &str, ops: &[(usize, u8, String)]) -> String {
    let mut tokens: Vec<String> = text.split_whitespace().map(str::to_owned).collect();
    for (at, op, with) in ops {
        if tokens.is_empty() {
            break;
        }
        let i = at % tokens.len();
        match op % 4 {
            0 => tokens[i].clone_from(with),
            1 => {
                tokens.remove(i);
            }
            2 => tokens.insert(i, tokens[i].clone()),
            _ => tokens.truncate(i),
        }
    }
    tokens.join(" ")
}

fn corpus_texts() -> Vec<String> {
    let mut files: Vec<_> = std::fs::read_dir(corpus_dir())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "dat"))
        .collect();
    files.sort();
    files.iter().map(|p| std::fs::read_to_string(p).unwrap()).collect()
}

fn edit() -> impl Strategy<Value = (usize, u8, String)> {
    (any::<usize>(), any::<u8>(), prop_oneof![int_text(), number_text()])
}

/// The JSON reader: random, malformed and mutated JSON, and random bytes, as `.json` files.
#[test]
fn fuzz_lcp_json() {
    let input = prop_oneof![
        4 => json_text(),
        2 => (json_text(), prop::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 1..6)).prop_map(
            |(t, edits)| {
                let mut b = t.into_bytes();
                for (at, byte) in edits {
                    if !b.is_empty() {
                        let i = at.index(b.len());
                        b[i] = byte;
                    }
                }
                String::from_utf8_lossy(&b).into_owned()
            }
        ),
        1 => prop::collection::vec(any::<u8>(), 0..300).prop_map(|b| String::from_utf8_lossy(&b).into_owned()),
        1 => Just(String::new()),
    ];
    let tally = fuzz("LCP JSON", input, |text| lcp_input("fuzz.json", text));
    assert!(tally.get("accepted and solved").copied().unwrap_or(0) >= cases() / 20, "{tally:?}");
    assert!(tally.get("refused").copied().unwrap_or(0) >= cases() / 20, "{tally:?}");
}

/// The Siconos reader: valid generated files must parse back to their matrix; headers of edge
/// integers; token mutations of generated and corpus files; random tokens; random bytes; as
/// `.dat` files and as files whose name says nothing (the format then chosen by content).
#[test]
fn fuzz_lcp_siconos() {
    let corpus = corpus_texts();
    let valid = valid_siconos().prop_map(|(m, q, text)| (Some((m, q)), text));
    let mutated_valid = (valid_siconos(), prop::collection::vec(edit(), 1..4))
        .prop_map(|((_, _, text), ops)| (None, mutate(&text, &ops)));
    let mutated_corpus = (prop::sample::select(corpus), prop::collection::vec(edit(), 1..4))
        .prop_map(|(text, ops)| (None, mutate(&text, &ops)));
    let header = (
        prop::collection::vec(int_text(), 4..20),
        prop::collection::vec(prop_oneof![int_text(), number_text()], 0..300),
    )
        .prop_map(|(head, body)| (None, format!("{} {}", head.join(" "), body.join(" "))));
    let bytes = prop::collection::vec(any::<u8>(), 0..300)
        .prop_map(|b| (None, String::from_utf8_lossy(&b).into_owned()));
    let input = (
        prop_oneof![3 => valid, 3 => mutated_valid, 2 => mutated_corpus, 2 => header, 1 => bytes],
        any::<bool>(),
    );
    let tally = fuzz("LCP Siconos .dat", input, |((expected, text), dat_name)| {
        let name = if *dat_name { "fuzz.dat" } else { "fuzz-no-extension" };
        let what = lcp_input(name, text)?;
        if let Some((m, q)) = expected {
            let data = lcp_io::parse_file(Path::new(name), text);
            prop_assert!(data.is_ok(), "a valid file was refused: {:?}\n{}", data.err(), text);
            let data = data.unwrap();
            prop_assert_eq!(&data.m, m, "M read back differs:\n{}", text);
            prop_assert_eq!(&data.q, q);
            return Ok("valid: read back exactly");
        }
        Ok(what)
    });
    assert!(tally.get("valid: read back exactly").copied().unwrap_or(0) >= cases() / 10, "{tally:?}");
    assert!(tally.get("refused").copied().unwrap_or(0) >= cases() / 10, "{tally:?}");
}

// ---- the command line ----

/// A subcommand's long flags, each with the values clap knows for it (none for a number).
type Flags = Vec<(String, Vec<String>)>;

/// Every subcommand with its long flags and, where clap knows them, their possible values.
fn flag_table() -> Vec<(String, Flags)> {
    cli::command()
        .get_subcommands()
        .map(|sub| {
            let flags = sub
                .get_arguments()
                .filter_map(|a| {
                    let values = a.get_possible_values().iter().map(|v| v.get_name().to_owned()).collect();
                    a.get_long().map(|l| (format!("--{l}"), values))
                })
                .collect();
            (sub.get_name().to_owned(), flags)
        })
        .collect()
}

/// A value as a user might type one (or mistype it).
fn value_text() -> impl Strategy<Value = String> {
    prop_oneof![
        4 => number_text(),
        2 => (number_text(), number_text()).prop_map(|(a, b)| format!("{a},{b}")),
        1 => prop::collection::vec(number_text(), 3..6).prop_map(|v| v.join(",")),
        1 => prop::sample::select(vec![
            "meter-stick", "incline", "ladder", "f32", "f64", "6", "8", "speed", "mu-ratio", "0.05,1",
            "1,1", ",", "1,", "-", "--", "-1e-3", "tcp:127.0.0.1:1", "mu_kinetic=0.3", "x=", "=1",
            "finger1_velocity=nan", "slow", "\u{e9}", " 1 ", "1e39", "1e-50", "0x1p3",
        ])
        .prop_map(str::to_owned),
        1 => "[a-z0-9_=.,:-]{0,30}",
    ]
}

/// One argument vector: `host-sim SUB` then flags of that subcommand (sometimes of another) with
/// values, flags without values, `--flag=value`, stray words and `--`.
fn argv(table: Vec<(String, Flags)>) -> impl Strategy<Value = Vec<String>> {
    let subs = table.len();
    (
        0..subs + 1,
        prop::collection::vec(
            (any::<prop::sample::Index>(), 0u8..24, value_text(), any::<prop::sample::Index>()),
            0..6,
        ),
    )
        .prop_map(move |(s, items)| {
            let mut args = vec!["host-sim".to_owned()];
            let Some((sub, flags)) = table.get(s) else {
                args.push("no-such-command".into());
                return args;
            };
            args.push(sub.clone());
            for (pick, kind, value, other) in items {
                let (flag, values) = if flags.is_empty() || kind >= 22 {
                    let (_, f) = &table[other.index(subs)];
                    if f.is_empty() {
                        continue;
                    }
                    f[other.index(f.len())].clone()
                } else {
                    flags[pick.index(flags.len())].clone()
                };
                let value = if values.is_empty() || kind % 2 == 0 {
                    value
                } else {
                    values[pick.index(values.len())].clone()
                };
                match kind {
                    18 => args.push(format!("{flag}={value}")),
                    19 => args.push(flag),
                    20 => args.push(value),
                    21 => args.push("--".into()),
                    _ => args.extend([flag, value]),
                }
            }
            args
        })
}

/// What `run`, `scene` and `map` do with the scene flags before anything runs; checks what they
/// accept.
fn resolve(scene: &SceneArgs, default_list: Option<(&str, &[f64])>) -> Result<&'static str, TestCaseError> {
    match scene.specs(default_list) {
        Ok(specs) => {
            prop_assert!(!specs.is_empty());
            let mut names: Vec<&str> = specs.iter().map(|(n, _)| n.as_str()).collect();
            for (name, spec) in &specs {
                prop_assert!(spec.validate(scene.precision).is_ok(), "{} accepted but invalid", name);
                let steps = (spec.max_time() / spec.step()).ceil();
                prop_assert!(steps <= MAX_STEPS, "{} steps accepted", steps);
                prop_assert!(
                    !name.is_empty() && name.len() <= 64 && !name.contains(['/', '\\']),
                    "folder name {:?}",
                    name
                );
            }
            names.sort_unstable();
            names.dedup();
            prop_assert_eq!(names.len(), specs.len(), "two runs share a folder");
            Ok("parsed, scene accepted")
        }
        Err(e) => {
            let msg = e.to_string();
            prop_assert!(!msg.is_empty() && !msg.contains("panicked"));
            Ok("parsed, scene refused")
        }
    }
}

/// The command line: argument vectors from the real flag names with random and edge values.
#[test]
fn fuzz_command_line() {
    let tally = fuzz("command line", argv(flag_table()), |args| {
        let (parsed, _, took) = measured(|| cli::parse_from(args.clone()));
        prop_assert!(took <= TIME_BOUND, "{:?} took {:?}", args, took);
        let cli = match parsed {
            Ok(cli) => cli,
            Err(e) => {
                let text = e.to_string();
                prop_assert!(!text.is_empty());
                prop_assert!(matches!(e.exit_code(), 0 | 2), "exit code {} for {:?}", e.exit_code(), args);
                return Ok(if e.exit_code() == 0 { "help or version" } else { "refused by the parser" });
            }
        };
        let (what, _, took) = measured(|| -> Result<&'static str, TestCaseError> {
            match &cli.command {
                Cmd::Run(a) => resolve(&a.scene, Some(("speed", &run_command::PAPER_SPEEDS))),
                Cmd::Scene(a) => resolve(&a.scene, None),
                Cmd::Map(a) => {
                    let grid = map::grid(a);
                    let scene = resolve(&a.scene, None)?;
                    Ok(if grid.is_ok() { scene } else { "parsed, map grid refused" })
                }
                Cmd::Monitor(a) => {
                    let ok =
                        a.set.iter().all(|s| meterstick_host_sim::commands::monitor::parse_set(s).is_ok());
                    Ok(if ok { "parsed, other" } else { "parsed, --set refused" })
                }
                _ => Ok("parsed, other"),
            }
        });
        prop_assert!(took <= TIME_BOUND, "{:?}: resolving took {:?}", args, took);
        what
    });
    for want in ["refused by the parser", "parsed, scene accepted", "parsed, scene refused"] {
        assert!(tally.get(want).copied().unwrap_or(0) >= cases() / 50, "{want}: {tally:?}");
    }
}

// ---- the link, host side: a rig's reports into `host-sim monitor` ----

/// A report a rig (or a broken one) may send: every field random, enums from their full lists.
fn rig_report() -> impl Strategy<Value = meterstick_link::Report> {
    use meterstick_link::{ContactTelemetry, ErrorCode, Mode, OutcomeCode, Report, RigState};
    let f = || prop_oneof![4 => -2.0f32..2.0, 1 => any::<u32>().prop_map(f32::from_bits)];
    let mode = || {
        prop::sample::select(vec![
            Mode::Separated,
            Mode::Sticking,
            Mode::SlidingPositive,
            Mode::SlidingNegative,
        ])
    };
    let state = || {
        prop::sample::select(vec![RigState::Waiting, RigState::Running, RigState::Finished, RigState::Fault])
    };
    let outcome = prop::sample::select(vec![
        OutcomeCode::Balanced,
        OutcomeCode::Fell,
        OutcomeCode::Held,
        OutcomeCode::Slid,
        OutcomeCode::Tipped,
        OutcomeCode::Unfinished,
        OutcomeCode::SolverFailed,
        OutcomeCode::NonFinite,
        OutcomeCode::ReducedModelLeftRange,
    ]);
    let contact = (mode(), f(), f()).prop_map(|(mode, normal_impulse, friction_impulse)| ContactTelemetry {
        mode,
        normal_impulse,
        friction_impulse,
    });
    prop_oneof![
        6 => (0u32..20_000, f(), prop::array::uniform6(f()), prop::array::uniform2(f()), prop::array::uniform2(contact))
            .prop_map(|(step, time, state, fingers, contacts)| Report::Telemetry { step, time, state, fingers, contacts }),
        2 => (any::<u32>(), f(), any::<u8>(), mode(), prop::array::uniform2(f()))
            .prop_map(|(step, time, contact, mode, along)| Report::Switch { step, time, contact, mode, along }),
        1 => (outcome, f(), any::<u32>(), any::<u32>())
            .prop_map(|(outcome, time, steps, checksum)| Report::Outcome { outcome, time, steps, checksum }),
        1 => any::<[u32; 4]>().prop_map(|[worst_cycles, period_cycles, overruns, worst_step]| Report::Margin {
            worst_cycles,
            period_cycles,
            overruns,
            worst_step
        }),
        2 => state().prop_map(Report::State),
        1 => any::<u32>().prop_map(|count| Report::Error(ErrorCode::TxDropped { count })),
        1 => any::<u32>().prop_map(|nonce| Report::Pong { nonce }),
    ]
}

/// The rig's parameters as `read_params` would return them: the defaults, or with a random
/// step and time limit (a rig set to `h = 1e-7 s` must not make the host record 10^8 steps).
fn rig_params() -> impl Strategy<Value = meterstick_core::scene::MeterStickParams<f32>> {
    prop_oneof![
        3 => Just(meterstick_core::scene::MeterStickParams::default()),
        1 => (prop::sample::select(vec![1e-3f32, 1e-5, 1e-7, 0.0, -1.0, f32::NAN]), prop::sample::select(vec![1.0f32, 30.0, 1e6, f32::INFINITY]))
            .prop_map(|(step, max_time)| meterstick_core::scene::MeterStickParams { step, max_time, ..Default::default() }),
    ]
}

/// The host side of the link: a fake rig on a TCP socket sends random reports (around a plausible
/// run half the time: running, telemetry, switches, an outcome, the margin, finished), damaged
/// frames and garbage, then closes; `monitor::record_run` must end (recorded, or an error such as
/// the link closing) and `monitor::compare` must compare or refuse, without a panic, within the
/// bound. It found, on its first run, `dropped += count` overflowing on two `TxDropped` reports
/// (a panic in a debug build, a wrong count in release; now saturating), and that a rig set to a
/// tiny step made `compare` record up to 10^8 host steps (now refused above
/// `trajectory::MAX_RECORDED_STEPS`).
#[test]
fn fuzz_rig_reports_into_monitor() {
    use meterstick_link::{MAX_FRAME, Report, RigState, encode};
    let frame = |r: &Report| {
        let mut buf = [0u8; MAX_FRAME];
        encode(r, &mut buf).unwrap().to_vec()
    };
    let input = (
        any::<bool>(),
        prop::collection::vec((rig_report(), 0u8..10, prop::collection::vec(any::<u8>(), 0..20)), 0..30),
        rig_params(),
    );
    let tally = fuzz("link: a rig's reports into host-sim monitor", input, |(plausible, parts, params)| {
        let mut reports: Vec<(Report, u8, Vec<u8>)> = parts.clone();
        if *plausible {
            reports.insert(0, (Report::State(RigState::Running), 0, Vec::new()));
            reports.push((
                Report::Outcome {
                    outcome: meterstick_link::OutcomeCode::Balanced,
                    time: 8.4,
                    steps: 8400,
                    checksum: 1,
                },
                0,
                Vec::new(),
            ));
            reports.push((Report::State(RigState::Finished), 0, Vec::new()));
        }
        let mut wire = Vec::new();
        for (r, damage, garbage) in &reports {
            let mut f = frame(r);
            match damage {
                0 => {
                    let i = garbage.first().map_or(0, |&b| usize::from(b) % f.len());
                    f[i] ^= 0x5a;
                }
                1 => wire.extend(garbage),
                _ => {}
            }
            wire.extend(f);
        }
        let listener = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
        let addr = listener.local_addr().unwrap();
        let rig = std::thread::spawn(move || {
            use std::io::Write as _;
            let (mut s, _) = listener.accept().unwrap();
            let _ = s.write_all(&wire);
        });
        let stream = std::net::TcpStream::connect(addr).unwrap();
        let started = Instant::now();
        let mut link = meterstick_link::host::Link::tcp(stream, "fuzz rig").unwrap();
        let rec =
            monitor::record_run(&mut link, *params, false, Duration::from_secs(10), &mut |_: &Report| {});
        rig.join().unwrap();
        let what = match rec {
            Ok(rec) => match monitor::compare(&rec) {
                Ok(_) => "recorded and compared",
                Err(_) => "recorded, comparison refused",
            },
            Err(e) => {
                let msg = format!("{e:#}");
                prop_assert!(msg.contains("fuzz rig") || msg.contains("no outcome"), "{}", msg);
                "link ended before an outcome"
            }
        };
        prop_assert!(started.elapsed() <= 3 * TIME_BOUND, "took {:?}", started.elapsed());
        Ok(what)
    });
    assert!(tally.get("recorded and compared").copied().unwrap_or(0) >= cases() / 10, "{tally:?}");
    assert!(tally.get("link ended before an outcome").copied().unwrap_or(0) >= cases() / 10, "{tally:?}");
}
