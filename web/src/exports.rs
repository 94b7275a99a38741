//! The page's API: plain `extern "C"` functions over one [`Session`] per wasm instance, with
//! numbers for arguments and results and two buffers in linear memory that the page reads (the
//! text buffer: JSON descriptions, refusals, outcomes; the trace buffer: one row of f64 per step,
//! as many as the scene's row has, [`crate::sim::Rows`]). `docs/page.md` lists them; `web/page/core.js` is their one caller.
//!
//! Return conventions: counts as `u32` (or `f64` where they may exceed 2^32), codes as `i32`
//! (`-1`: none or a bad argument), a text's length in bytes as `u32` (read from [`ms_text_ptr`]).
//!
//! **Why this module allows `unsafe_code`** (denied in the workspace): an export keeps its name
//! only with `#[unsafe(no_mangle)]`, and on wasm32 the session lives in a `static`, whose interior
//! mutability needs `unsafe impl Sync` (sound there: `wasm32-unknown-unknown` without the atomics
//! feature runs one thread). Nothing else here is unsafe; on the host the session is thread-local.
#![allow(unsafe_code)]

use core::fmt::Write as _;

use crate::config::{Precision, layout_of_page_size};
use crate::session::{CreateError, Session, TEXT_BYTES, TRACE_ROWS, describe, outcome_text};
use crate::sim::{MAX_ROW, outcome_code};
use crate::text::Text;

/// The session and what the last call said.
#[derive(Debug)]
struct State {
    session: Session,
    /// Bytes in the text buffer.
    text_len: usize,
    /// The flag to blame for the last refusal (index in `flags::FLAGS`), or -1.
    error_flag: i32,
}

impl State {
    const fn new() -> Self {
        Self { session: Session::new(), text_len: 0, error_flag: -1 }
    }
}

#[cfg(target_arch = "wasm32")]
mod store {
    use core::cell::RefCell;

    use super::{MAX_ROW, State, TEXT_BYTES, TRACE_ROWS};

    /// A cell in a `static`.
    pub struct Global<T>(RefCell<T>);

    // SAFETY: wasm32-unknown-unknown (built without the `atomics` target feature) has exactly one
    // thread, so a `Global` is never accessed from two threads.
    unsafe impl<T> Sync for Global<T> {}

    static STATE: Global<State> = Global(RefCell::new(State::new()));
    // Zero-initialised, so they take no room in the .wasm file.
    static TEXT: Global<[u8; TEXT_BYTES]> = Global(RefCell::new([0; TEXT_BYTES]));
    static TRACE: Global<[f64; TRACE_ROWS * MAX_ROW]> = Global(RefCell::new([0.0; TRACE_ROWS * MAX_ROW]));

    pub fn with<R>(f: impl FnOnce(&mut State, &mut [u8], &mut [f64]) -> R) -> R {
        f(&mut STATE.0.borrow_mut(), &mut TEXT.0.borrow_mut()[..], &mut TRACE.0.borrow_mut()[..])
    }

    pub fn text_ptr() -> *const u8 {
        TEXT.0.as_ptr().cast()
    }

    pub fn trace_ptr() -> *const f64 {
        TRACE.0.as_ptr().cast()
    }
}

#[cfg(not(target_arch = "wasm32"))]
mod store {
    use std::cell::RefCell;

    use super::{MAX_ROW, State, TEXT_BYTES, TRACE_ROWS};

    struct Store {
        state: State,
        text: Box<[u8]>,
        trace: Box<[f64]>,
    }

    std::thread_local! {
        static STORE: RefCell<Store> = RefCell::new(Store {
            state: State::new(),
            text: vec![0; TEXT_BYTES].into_boxed_slice(),
            trace: vec![0.0; TRACE_ROWS * MAX_ROW].into_boxed_slice(),
        });
    }

    pub fn with<R>(f: impl FnOnce(&mut State, &mut [u8], &mut [f64]) -> R) -> R {
        STORE.with(|s| {
            let s = &mut *s.borrow_mut();
            f(&mut s.state, &mut s.text, &mut s.trace)
        })
    }

    pub fn text_ptr() -> *const u8 {
        STORE.with(|s| s.borrow().text.as_ptr())
    }

    pub fn trace_ptr() -> *const f64 {
        STORE.with(|s| s.borrow().trace.as_ptr())
    }
}

/// Replaces the text buffer's content with what `write` writes; returns its length.
fn set_text(
    state: &mut State,
    buf: &mut [u8],
    write: impl FnOnce(&mut Text<'_>) -> core::fmt::Result,
) -> u32 {
    let mut text = Text::new(buf);
    let _ = write(&mut text);
    state.text_len = text.len();
    text.len() as u32
}

/// The text buffer (its length: the last text call's result, or [`ms_text_len`]).
#[unsafe(no_mangle)]
#[must_use]
pub extern "C" fn ms_text_ptr() -> *const u8 {
    store::text_ptr()
}

/// Bytes in the text buffer.
#[unsafe(no_mangle)]
#[must_use]
pub extern "C" fn ms_text_len() -> u32 {
    store::with(|s, _, _| s.text_len as u32)
}

/// Writes the description (JSON: scenes with their fields and defaults, contacts, row length,
/// measured quantities and outcomes; flags with unit, help and field per scene; modes, outcomes,
/// limits) into the text buffer; returns its length.
#[unsafe(no_mangle)]
#[must_use]
pub extern "C" fn ms_describe() -> u32 {
    store::with(|s, text, _| set_text(s, text, describe))
}

/// Starts a configuration of scene `scene` (its index in the description's `scenes`: the
/// catalogue's order) with the core's defaults and no run; 0, or -1 for an unknown scene.
#[unsafe(no_mangle)]
#[must_use]
pub extern "C" fn ms_configure(scene: u32) -> i32 {
    let Some(kind) = crate::flags::SceneKind::from_index(scene) else {
        return -1;
    };
    store::with(|s, _, _| s.session.configure(kind));
    0
}

/// Gives flag `flag` (its index in the description's `flags`) `value`, in the flag's unit
/// (degrees for angles); 0, or -1 for an unknown flag. A flag that does not apply to the scene is
/// refused by [`ms_create`], as on the command line.
#[unsafe(no_mangle)]
#[must_use]
pub extern "C" fn ms_give(flag: u32, value: f64) -> i32 {
    if store::with(|s, _, _| s.session.give(flag as usize, value)) { 0 } else { -1 }
}

/// Resolves the configuration (as `host-sim scene` would) and makes the run at `t = 0` in
/// precision `bits` (32 or 64) with an `n x n` LCP (6 or 8). 0: the run is ready; 1: refused, the
/// text buffer holds why in the user's words and [`ms_error_flag`] the flag to blame; -1: bad
/// `bits` or `n`.
#[unsafe(no_mangle)]
#[must_use]
pub extern "C" fn ms_create(bits: u32, n: u32) -> i32 {
    let (Some(precision), Some(size)) = (Precision::from_bits(bits), layout_of_page_size(n)) else {
        return -1;
    };
    store::with(|s, text, _| match s.session.create(precision, size) {
        Ok(()) => {
            s.error_flag = -1;
            s.text_len = 0;
            0
        }
        Err(e) => {
            s.error_flag = match e {
                CreateError::Config(c) => c.flag().and_then(|i| i32::try_from(i).ok()).unwrap_or(-1),
                CreateError::Core(_) | CreateError::OtherModule(_) => -1,
            };
            set_text(s, text, |t| write!(t, "{e}"));
            1
        }
    })
}

/// Writes what the run is told before it starts ([`crate::session::Session::cautions`]: friction
/// beyond the precision, a mass ratio outside f32's measured reach) into the text buffer, one a
/// line, worded as `host-sim` words them but for the flags' `--`; returns its length (0: none).
#[unsafe(no_mangle)]
#[must_use]
pub extern "C" fn ms_cautions() -> u32 {
    store::with(|s, text, _| {
        let cautions = s.session.cautions();
        set_text(s, text, |t| {
            for (i, c) in cautions.enumerate() {
                write!(t, "{}{}", if i > 0 { "\n" } else { "" }, c.worded(""))?;
            }
            Ok(())
        })
    })
}

/// The flag (index) the last refusal blames, or -1.
#[unsafe(no_mangle)]
#[must_use]
pub extern "C" fn ms_error_flag() -> i32 {
    store::with(|s, _, _| s.error_flag)
}

/// The run's parameter `i` (core units: SI, radians) in the order of the scene's `fields`; NaN
/// without a run or past the end.
#[unsafe(no_mangle)]
#[must_use]
pub extern "C" fn ms_param(i: u32) -> f64 {
    store::with(|s, _, _| s.session.spec().and_then(|p| p.field(i as usize)).unwrap_or(f64::NAN))
}

/// Writes the state at `t = 0` as the first row of the trace buffer; 1, or 0 without a run.
#[unsafe(no_mangle)]
#[must_use]
pub extern "C" fn ms_start_row() -> u32 {
    store::with(|s, _, trace| {
        s.session.sim().map_or(0, |sim| {
            let row = sim.start_row();
            trace[..row.len()].copy_from_slice(row);
            1
        })
    })
}

/// Steps the run up to `n` times (at most the trace buffer's rows), writing one row per step into
/// the trace buffer; returns the steps taken (0 once the run has ended, or without a run).
#[unsafe(no_mangle)]
#[must_use]
pub extern "C" fn ms_step(n: u32) -> u32 {
    store::with(|s, _, trace| {
        let rows = (n as usize).min(TRACE_ROWS);
        s.session.sim_mut().map_or(0, |sim| {
            let len = sim.row_len();
            sim.step_rows(&mut trace[..rows * len]) as u32
        })
    })
}

/// After the outcome, steps the run on past it (the bodies go on: the stack tumbles off the
/// table) up to `n` times (at most the trace buffer's rows), one row per step in the trace
/// buffer as [`ms_step`] writes them; the run is reported as judged (outcome, checksum, time,
/// counters, measured quantities). Returns the steps taken: 0 before the outcome, when a step fails or after
/// `sim::MAX_PAST_STEPS` in all.
#[unsafe(no_mangle)]
#[must_use]
pub extern "C" fn ms_step_past(n: u32) -> u32 {
    store::with(|s, _, trace| {
        let rows = (n as usize).min(TRACE_ROWS);
        s.session.sim_mut().map_or(0, |sim| {
            let len = sim.row_len();
            sim.step_past_rows(&mut trace[..rows * len]) as u32
        })
    })
}

/// Steps the run up to `max` times without rows (the outcome map, the benchmark); returns the
/// steps taken.
#[unsafe(no_mangle)]
#[must_use]
pub extern "C" fn ms_run(max: f64) -> f64 {
    let max = if max.is_nan() || max < 0.0 { 0 } else { max as u64 };
    store::with(|s, _, _| s.session.sim_mut().map_or(0, |sim| sim.run(max)) as f64)
}

/// The trace buffer: rows of the scene's `row` f64 (`core.csv`'s columns for its contacts).
#[unsafe(no_mangle)]
#[must_use]
pub extern "C" fn ms_trace_ptr() -> *const f64 {
    store::trace_ptr()
}

/// The outcome's code (the index in the description's `outcomes`), or -1 while the run goes on
/// (or without a run).
#[unsafe(no_mangle)]
#[must_use]
pub extern "C" fn ms_outcome() -> i32 {
    store::with(|s, _, _| {
        s.session.sim().and_then(crate::sim::Sim::outcome).map_or(-1, |o| i32::from(outcome_code(o)))
    })
}

/// Writes the outcome as the core displays it (a failure with its cause) into the text buffer;
/// returns its length (0 while the run goes on).
#[unsafe(no_mangle)]
#[must_use]
pub extern "C" fn ms_outcome_text() -> u32 {
    store::with(|s, text, _| match s.session.sim().and_then(crate::sim::Sim::outcome) {
        Some(o) => set_text(s, text, |t| outcome_text(t, o)),
        None => set_text(s, text, |_| Ok(())),
    })
}

/// The trajectory checksum so far (FNV-1a over the state's bits after every step; as
/// `host-sim scene` prints it for the same run). 0 without a run.
#[unsafe(no_mangle)]
#[must_use]
pub extern "C" fn ms_checksum() -> u32 {
    store::with(|s, _, _| s.session.sim().map_or(0, crate::sim::Sim::checksum))
}

/// Simulated time (s); NaN without a run.
#[unsafe(no_mangle)]
#[must_use]
pub extern "C" fn ms_time() -> f64 {
    store::with(|s, _, _| s.session.sim().map_or(f64::NAN, crate::sim::Sim::time))
}

/// A counter of the run: 0 steps, 1 pivots, 2 most pivots in a step, 3 warm starts, 4 steps that
/// needed the 8x8 form, 5 regularised solves; NaN otherwise.
#[unsafe(no_mangle)]
#[must_use]
pub extern "C" fn ms_stat(i: u32) -> f64 {
    store::with(|s, _, _| {
        let Some(st) = s.session.sim().map(crate::sim::Sim::stats) else { return f64::NAN };
        match i {
            0 => st.steps as f64,
            1 => st.pivots as f64,
            2 => f64::from(st.max_pivots),
            3 => st.warm_starts as f64,
            4 => st.reduced_check_fired as f64,
            5 => st.regularized_solves as f64,
            _ => f64::NAN,
        }
    })
}

/// The run's measured quantity `i`, named by the scene's `measures` in the description
/// (`summary.json`'s keys, in their units); NaN where there is none (yet) or past the end.
#[unsafe(no_mangle)]
#[must_use]
pub extern "C" fn ms_measured(i: u32) -> f64 {
    store::with(|s, _, _| {
        s.session.sim().map_or(f64::NAN, |sim| sim.measured().get(i as usize).copied().unwrap_or(f64::NAN))
    })
}

/// Body `i` (0 the lowest of a scene of several bodies): its width (`axis` 0) or height (`axis`
/// 1) in m (a disc's diameter for both); NaN past its bodies, for another axis or without a run.
#[unsafe(no_mangle)]
#[must_use]
pub extern "C" fn ms_body_size(i: u32, axis: u32) -> f64 {
    store::with(|s, _, _| {
        let size = s.session.sim().and_then(|sim| sim.body_size(i as usize));
        size.and_then(|wh| wh.get(axis as usize).copied()).unwrap_or(f64::NAN)
    })
}

/// Body `i` (0 the lowest of a scene of several bodies): 1 when it is round (a disc, drawn with a
/// spoke so that its turning shows), 0 for a box, past its bodies or without a run.
#[unsafe(no_mangle)]
#[must_use]
pub extern "C" fn ms_body_round(i: u32) -> u32 {
    store::with(|s, _, _| u32::from(s.session.sim().is_some_and(|sim| sim.body_round(i as usize))))
}

/// The table the scene's bodies rest on (a scene of several bodies): its left (`end` 0) or right
/// (`end` 1) end in m (the top face is `y = 0`); NaN for an end it does not have (a floor has
/// none), or without such a run.
#[unsafe(no_mangle)]
#[must_use]
pub extern "C" fn ms_table_end(end: u32) -> f64 {
    store::with(|s, _, _| {
        let ends = s.session.sim().map_or([None, None], crate::sim::Sim::table);
        ends.get(end as usize).copied().flatten().unwrap_or(f64::NAN)
    })
}

/// The bodies of a scene in three dimensions: their solid's code (`j` 0: 0 a box, 1 a ball, 2 a
/// flat cylinder, 3 a block) and sizes (`j` 1 to 3: m; `spatial::Solid`); NaN for another `j` or
/// without such a run.
#[cfg(any(feature = "sp", feature = "st"))]
#[unsafe(no_mangle)]
#[must_use]
pub extern "C" fn ms_solid(j: u32) -> f64 {
    store::with(|s, _, _| {
        let solid = s.session.sim().and_then(crate::sim::Sim::solid);
        solid.and_then(|v| v.get(j as usize).copied()).unwrap_or(f64::NAN)
    })
}

/// Support `i` of a scene in three dimensions: number `j` of `[code, point, direction]` (code 1 a
/// plane and its normal, 2 a finger's tip and the direction it lies along, 3 the table's edge and
/// its top's normal; m, world, `z` up;
/// `spatial::SupportOf`); NaN past its supports, for another `j` or without such a run.
#[cfg(any(feature = "sp", feature = "st"))]
#[unsafe(no_mangle)]
#[must_use]
pub extern "C" fn ms_support(i: u32, j: u32) -> f64 {
    store::with(|s, _, _| {
        let support = s.session.sim().and_then(|sim| sim.support(i as usize));
        support.and_then(|v| v.get(j as usize).copied()).unwrap_or(f64::NAN)
    })
}

/// The text buffer's content (host only: tests).
#[cfg(not(target_arch = "wasm32"))]
#[must_use]
pub fn text() -> String {
    store::with(|s, text, _| String::from_utf8_lossy(&text[..s.text_len]).into_owned())
}

/// Row `i` of the trace buffer, rows of `len` numbers (host only: tests).
#[cfg(not(target_arch = "wasm32"))]
#[must_use]
pub fn trace_row(i: usize, len: usize) -> Vec<f64> {
    store::with(|_, _, trace| trace[i * len..(i + 1) * len].to_vec())
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::float_cmp)] // exact: values copied or rounded once, not computed
    use super::*;
    use crate::flags::{FLAGS, flag_index};
    use crate::sim::OUTCOMES;

    fn flag(long: &str) -> u32 {
        flag_index(long).unwrap() as u32
    }

    #[test]
    fn the_description_is_json_the_page_can_read() {
        let n = ms_describe();
        let json = text();
        assert_eq!(json.len(), n as usize);
        assert!(json.len() < TEXT_BYTES / 2, "room to grow: {} bytes", json.len());
        assert!(json.starts_with("{\"version\":") && json.ends_with('}'), "{json}");
        assert!(json.contains(r#"{"long":"mu-k","unit":"","help":"Kinetic friction coefficient (0 <= mu-k <= mu-s)","fields":{"meter-stick":"mu_kinetic","meter-stick-3d":"mu_kinetic","incline":"mu_kinetic","three-fingers":"mu_kinetic","cylinder":"mu_kinetic","painleve":"mu_kinetic","block-on-block":"mu_kinetic","tablecloth":"mu_kinetic","stack":"mu_kinetic","stack-3d":"mu_kinetic","disc-on-board":"mu_kinetic","puck":"mu_kinetic","billiard":"mu_kinetic"}}"#), "{json}");
        // The scenes in three dimensions (feature `sp`): rows of three bodies and sixteen contacts.
        assert!(json.contains(r#""contacts":["its face"],"spatial":true,"row":232,"#), "{json}");
        assert!(json.contains(r#""contacts":["finger 1","finger 2"],"row":19,"measures":["meeting.time_s","meeting.com_offset_m"]"#), "{json}");
        assert!(
            json.contains(r#""name":"cylinder","#) && json.contains(r#""contacts":["rim"],"row":13,"#),
            "{json}"
        );
        assert!(json.contains(r#""contacts":["finger 1","finger 2","finger 3"],"row":25,"#), "{json}");
        assert!(json.contains(r#""holds":[0,1,2,3],"#), "the host build holds every scene: {json}");
        // The scenes of several bodies come last, rows of time and each body's x, y, theta.
        assert!(json.contains(r#"{"name":"stack","#), "{json}");
        assert!(json.contains(r#"{"name":"disc-on-board","#), "{json}");
        assert!(json.contains(r#""contacts":[],"bodies":true,"row":10,"#), "{json}");
        assert!(json.contains(r#""ends":["Rolled","Slid"],"main_flags":["angle","mu-s","mu-k","radius","inertia-ratio","h"]}"#), "{json}");
        assert!(json.contains(r#""measures":["jam.time_s","jam.normal_impulse_n_s","jam.friction_impulse_n_s"],"ends":["Jammed","Slid","Fell","Unfinished"]"#), "{json}");
        assert!(json.contains(r#""defaults":[1,0.005,0.2,9.81,-0.4,0.4,0,0,0.1,0,0.01,0.6,0.4,0.001,0.00001,0.35,0.02,0.5,30]"#), "{json}");
    }

    #[test]
    fn a_run_through_the_exports() {
        assert_eq!(ms_configure(0), 0);
        assert_eq!(ms_give(flag("x1"), -0.35), 0);
        assert_eq!(ms_give(flag("speed"), 1.0), 0);
        assert_eq!(ms_create(32, 6), 0);
        assert_eq!(ms_outcome(), -1);
        assert_eq!(ms_param(4), -0.35, "finger1_x");
        assert_eq!(ms_start_row(), 1);
        assert_eq!(trace_row(0, 19)[7], f64::from(-0.35_f32), "finger 1 in f32");
        let mut steps = 0;
        loop {
            let n = ms_step(100);
            if n == 0 {
                break;
            }
            assert!(n <= 100);
            steps += n;
            assert_eq!(trace_row(n as usize - 1, 19)[0], ms_time(), "the last row is the current time");
        }
        assert_eq!(f64::from(steps), ms_stat(0));
        assert_eq!(ms_outcome(), 1, "Fell");
        assert_eq!(ms_outcome_text(), 4);
        assert_eq!(text(), "Fell");
        let checksum = ms_checksum();
        // Past the outcome the rod goes on falling; the run stays as judged.
        let (t, y) = (ms_time(), trace_row(0, 19)[2]);
        assert_eq!(ms_step_past(300), 300);
        let after = trace_row(299, 19);
        assert!(after[0] > t && after[2] < y, "{after:?}");
        assert_eq!((ms_outcome(), ms_checksum(), ms_time(), ms_stat(0)), (1, checksum, t, f64::from(steps)));
        // The same run without rows: the same checksum.
        assert_eq!(ms_create(32, 6), 0);
        assert_eq!(ms_run(1e9), f64::from(steps));
        assert_eq!(ms_checksum(), checksum);
        // The fingers met (0.74 m at 1 m/s) before the rod fell; the meter stick measures two things.
        assert!((ms_measured(0) - 0.74).abs() <= 1.5e-3, "{}", ms_measured(0));
        assert!(ms_measured(1).is_finite() && ms_measured(2).is_nan() && ms_measured(9).is_nan());
    }

    #[test]
    fn a_one_contact_run_through_the_exports() {
        // The cylinder (scene 4) on a steep slope: rows of 13, it slides.
        assert_eq!(ms_configure(4), 0);
        assert_eq!(ms_give(flag("angle"), 70.0), 0);
        assert_eq!(ms_create(64, 8), 0);
        assert_eq!(ms_start_row(), 1);
        assert_eq!(trace_row(0, 13)[9], 1.0, "the rim sticks at rest");
        assert_eq!(ms_step(5), 5);
        let row = trace_row(4, 13);
        assert_eq!((row[0], row[9]), (ms_time(), 2.0), "sliding+");
        assert_eq!(trace_row(5, 13)[0], 0.0, "five rows written");
        while ms_step(2048) > 0 {}
        assert_eq!(OUTCOMES[ms_outcome() as usize], "Slid");
        // g (sin a - mu_k cos a) at 70 degrees.
        let a = 70_f64.to_radians();
        assert!((ms_measured(0) - 9.81 * (a.sin() - 0.4 * a.cos())).abs() < 1e-6, "{}", ms_measured(0));
        // Friction's torque spins it up at mu_k g cos a / (k r), k = 0.5, r = 0.1.
        let spin = 0.4 * 9.81 * a.cos() / (0.5 * 0.1);
        assert!((ms_measured(1) - spin).abs() < 1e-6, "{}", ms_measured(1));
        assert!(ms_measured(2).is_nan());
    }

    #[test]
    fn refusals_reach_the_text_buffer_with_the_flag_to_blame() {
        assert_eq!(ms_configure(1), 0);
        assert_eq!(ms_give(flag("angle"), 95.0), 0);
        assert_eq!(ms_create(64, 8), 1);
        assert_eq!(text(), "angle 95 deg: out of range (0 <= angle < 90 deg)");
        assert_eq!(i64::from(ms_error_flag()), i64::from(flag("angle")));
        assert_eq!(ms_step(10), 0, "no run");
        assert!(ms_param(0).is_nan());
        assert_eq!(ms_create(16, 6), -1);
        assert_eq!(ms_create(32, 7), -1);
        assert_eq!(ms_configure(crate::flags::SceneKind::ALL.len() as u32), -1);
        assert_eq!(ms_give(FLAGS.len() as u32, 1.0), -1);
    }

    /// A run f32 does not follow is told so, as `host-sim` tells it (the catalogue's words); f64,
    /// and the defaults, are told nothing.
    #[cfg(feature = "mb")]
    #[test]
    fn cautions_reach_the_text_buffer() {
        use crate::flags::SceneKind;
        let bob = SceneKind::ALL.iter().position(|&k| k == SceneKind::BlockOnBlock).unwrap() as u32;
        assert_eq!(ms_configure(bob), 0);
        assert_eq!(ms_create(32, 8), 0);
        assert_eq!(ms_cautions(), 0, "the defaults: {}", text());
        assert_eq!((ms_give(flag("mass"), 1e6), ms_give(flag("mass2"), 1.0)), (0, 0));
        assert_eq!(ms_create(32, 8), 0);
        let n = ms_cautions();
        assert_eq!(n as usize, text().len());
        assert!(
            text().starts_with("mass 1000000 kg on mass2 1 kg: mass ratio 1.00e6: outside 1.00e-4 .. 1.00e5"),
            "{}",
            text()
        );
        assert!(text().ends_with("use precision f64 or masses closer together"), "{}", text());
        assert_eq!(ms_create(64, 8), 0);
        assert_eq!(ms_cautions(), 0, "f64: {}", text());
        // Friction beyond f32 and the mass ratio: two lines.
        assert_eq!((ms_give(flag("mu-s"), 1e5), ms_give(flag("mu-k"), 1e5)), (0, 0));
        assert_eq!(ms_create(32, 8), 0);
        let _ = ms_cautions();
        let lines: Vec<String> = text().lines().map(String::from).collect();
        assert_eq!(lines.len(), 2, "{lines:?}");
        assert!(
            lines[0].starts_with("mu-s 100000 and mu-k 100000: friction beyond what f32 resolves"),
            "{lines:?}"
        );
    }
}
