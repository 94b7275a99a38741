//! The outcome of a scene over two of its parameters (a [`Grid`] over two [`Axis`]), one run per
//! cell in parallel, with the boundaries between outcomes located by bisection; and the files
//! of a map (`map.csv`, `boundaries.csv`, `summary.json`, `map.svg`; with a measure, its value in
//! each cell in `map.csv` and `measure.svg`). `host-sim map`
//! ([`crate::commands::map`]) and `host-sim report` ([`crate::commands::report`]) draw theirs
//! with it.
//!
//! The bands where the meter-stick trick works and fails are not monotone in speed (the moving
//! finger stops abruptly when the fingers meet; a rod riding on it slides on by
//! `v^2 / (2 mu_k g)`, past the other finger or not, depending on the phase of the stick-slip
//! cycle at the stop). Any scene flag can be an axis, `mu-ratio` scales `mu_k` to
//! `ratio * mu_s`, and `mu` sets both to one coefficient (a scene with `--mu-s` and `--mu-k`).
//!
//! Each row's boundaries (adjacent cells with different outcomes along the x axis) are bisected
//! to the grid's tolerance (in the x axis's unit), every run in the implementation given.
use std::path::Path;
use std::time::Instant;

use anyhow::Context as _;
use rayon::prelude::*;
use serde::Serialize;

use crate::output::{create_dir, write_json, write_lines};
use crate::plot;
use crate::progress::bar as progress;
use crate::scenes::{
    FLAGS, Flag, Implementation, ImplementationOf, MAX_STEPS, ParamsExt as _, SceneKind, SceneParams,
    flag_error,
};
use crate::trajectory::{OutcomeKind, Record, run_k};
use meterstick_catalogue::{Catalogued as _, Refusal};

/// The most cells a map may have (each is a run of up to `MAX_STEPS`).
/// (At about 550 runs per second on 2 cores, 200,000 cells take about 6 minutes.)
pub const MAX_CELLS: usize = 200_000;

/// An axis: a scene flag or the friction ratio.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Axis {
    /// A scene flag, in its unit.
    Flag(&'static Flag),
    /// `mu_k / mu_s` with `mu_s` as given.
    MuRatio,
    /// One coefficient of friction, `mu_s = mu_k` (`mu` of a scene whose flags are `--mu-s` and
    /// `--mu-k`: Coulomb's law with one coefficient, as the puck's and the ball's laws take it).
    Coulomb,
    /// A launch's `v0 / (R omega0)`, the launch speed as given (a scene of a spinning stone:
    /// `--spin` set to `speed / (radius * ratio)`).
    LaunchRatio,
}

impl Axis {
    /// The axis `--x-axis`/`--y-axis` name: `mu-ratio` or a scene flag's long name.
    ///
    /// # Errors
    /// An unknown name, listing the names `kind` takes.
    pub fn parse(name: &str, kind: SceneKind) -> anyhow::Result<Self> {
        if name == "mu-ratio" {
            return Ok(Self::MuRatio);
        }
        let name = name.trim_start_matches("--");
        let own_mu = FLAGS.iter().any(|f| f.long == "mu" && f.field(kind).is_some());
        if name == "mu" && !own_mu && kind.field_names().contains(&"mu_static") {
            return Ok(Self::Coulomb);
        }
        if name == "launch-ratio"
            && ["speed", "spin", "radius"].iter().all(|f| kind.field_names().contains(f))
        {
            return Ok(Self::LaunchRatio);
        }
        FLAGS.iter().find(|f| f.long == name).map(Self::Flag).with_context(|| {
            let names: Vec<&str> = FLAGS.iter().filter(|f| f.field(kind).is_some()).map(|f| f.long).collect();
            let coulomb = if kind.field_names().contains(&"mu_static") { "mu (mu-s = mu-k), " } else { "" };
            format!(
                "no axis {name:?}: use mu-ratio, {coulomb}or a flag of --scene {kind} ({})",
                names.join(", ")
            )
        })
    }

    /// The axis's name and unit, for labels.
    #[must_use]
    pub fn label(&self) -> String {
        match self {
            Self::MuRatio => "mu_k / mu_s".into(),
            Self::Coulomb => "mu (mu_s = mu_k)".into(),
            Self::LaunchRatio => "v0 / (R omega0)".into(),
            Self::Flag(f) if f.unit.is_empty() => f.long.to_string(),
            Self::Flag(f) => format!("{} ({})", f.long, f.unit),
        }
    }

    /// `spec` with this axis at `value`.
    fn apply(self, spec: &mut SceneParams, value: f64) -> anyhow::Result<()> {
        let kind = spec.kind();
        match self {
            Self::MuRatio => {
                let mu_s =
                    spec.get("mu_static").with_context(|| format!("mu-ratio: --scene {kind} has no mu_s"))?;
                spec.set("mu_kinetic", value * mu_s);
            }
            Self::Coulomb => {
                spec.set("mu_static", value);
                spec.set("mu_kinetic", value);
            }
            Self::LaunchRatio => {
                let (speed, radius) = (spec.get("speed"), spec.get("radius"));
                let (Some(speed), Some(radius)) = (speed, radius) else {
                    anyhow::bail!("launch-ratio: --scene {kind} has no --speed and --radius");
                };
                spec.set("spin", speed / (radius * value));
            }
            Self::Flag(f) => {
                let field = f
                    .field(kind)
                    .with_context(|| format!("--{} does not apply to --scene {kind}", f.long))?;
                spec.set(field, f.to_core(value));
            }
        }
        Ok(())
    }
}

/// Cell centres of `cells` cells over `[a, b]`.
fn centres((a, b): (f64, f64), cells: usize) -> Vec<f64> {
    (0..cells).map(|k| a + (b - a) * (k as f64 + 0.5) / cells as f64).collect()
}

/// A boundary between two outcomes along the x axis, in one row.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Boundary {
    /// The row's y value.
    pub y: f64,
    /// The x where the outcome changes (the bisection interval's midpoint).
    pub x: f64,
    /// The bisection interval's width.
    pub width: f64,
    /// The outcome below `x`.
    pub below: OutcomeKind,
    /// The outcome above `x`.
    pub above: OutcomeKind,
}

/// `summary.json`.
#[derive(Debug, Clone, Serialize)]
pub struct MapSummary {
    /// The scene.
    pub scene: SceneKind,
    /// Who computed it.
    pub implementation: ImplementationOf,
    /// Axes.
    pub x_axis: String,
    /// Axes.
    pub y_axis: String,
    /// Cells (columns x rows).
    pub cells: [usize; 2],
    /// Runs in all (cells and bisection).
    pub runs: usize,
    /// Wall-clock time (s).
    pub wall_s: f64,
    /// Cells of each outcome.
    pub counts: Vec<(OutcomeKind, usize)>,
    /// Every boundary found.
    pub boundaries: Vec<Boundary>,
    /// Where `docs/scenes.md`'s law changes its outcome along x in each row (a scene of several
    /// bodies; none for the others), bisected on the law to the last representable x.
    pub law_boundaries: Vec<Boundary>,
    /// Cells whose eight neighbours' centres the law classifies as their own centre (so more than
    /// one cell from any law boundary) and whose run's outcome differs from the law's (none for a
    /// scene without a law).
    pub law_disagreements: Option<LawAgreement>,
}

/// The runs against the law away from its boundaries ([`MapSummary::law_disagreements`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct LawAgreement {
    /// Cells more than one cell from every law boundary.
    pub cells_compared: usize,
    /// Of them, those whose outcome is not the law's.
    pub disagree: usize,
}

/// A computed map.
#[derive(Debug, Clone)]
pub struct Map {
    /// Column centres.
    pub xs: Vec<f64>,
    /// Row centres.
    pub ys: Vec<f64>,
    /// `outcomes[row][column]`.
    pub outcomes: Vec<Vec<OutcomeKind>>,
    /// The law's outcome at each cell's centre, `[row][column]`, for a scene with a law
    /// ([`crate::bodies::law`]; `None` in a cell at the law's threshold).
    pub law: Option<Vec<Vec<Option<OutcomeKind>>>>,
    /// The measure [`Grid::measure`] asked for: its name and its value at each cell's centre,
    /// `[row][column]` (NaN where the run measured none).
    pub measured: Option<(&'static str, Vec<Vec<f64>>)>,
    /// The summary.
    pub summary: MapSummary,
}

/// The outcome at `(x, y)`, and the scene's measure of index `measure` there (NaN where it
/// measured none; the core's runs only).
fn outcome_at(
    base: &SceneParams,
    axes: (Axis, Axis),
    (x, y): (f64, f64),
    implementation: Implementation,
    measure: Option<usize>,
) -> anyhow::Result<(OutcomeKind, f64)> {
    let spec = apply_axes(base, axes, (x, y))?;
    spec.validate(implementation.precision())
        .map_err(|e| anyhow::anyhow!("at ({x:?}, {y:?}): {}", flag_error(&spec, e)))?;
    Ok(match implementation {
        Implementation::Core(precision, layout) => {
            let run = crate::view_run::run_view(&spec, precision, layout)?;
            let value = measure.and_then(|i| run.measured.get(i).copied().flatten()).unwrap_or(f64::NAN);
            (run.outcome.class, value)
        }
        Implementation::Reference => (reference_outcome(&spec)?, f64::NAN),
    })
}

/// The independent f64 reference's outcome of `spec`: its run of one body where it has the scene
/// as one ([`crate::scenes::ParamsExt::to_reference`]), else its run of several bodies.
fn reference_outcome(spec: &SceneParams) -> anyhow::Result<OutcomeKind> {
    if spec.to_reference().is_none() {
        return Ok(crate::bodies::run_reference(spec, false)?.outcome.class);
    }
    Ok(crate::with_contacts!(
        spec.kind(),
        K => run_k::<K>(spec, Implementation::Reference, Record::Nothing)?.outcome.class
    ))
}

/// The law's outcome at `(x, y)` (`docs/scenes.md`; [`crate::bodies::law`]): `None` for a scene
/// without a law or at its threshold.
fn law_at(base: &SceneParams, axes: (Axis, Axis), (x, y): (f64, f64)) -> anyhow::Result<Option<OutcomeKind>> {
    let spec = apply_axes(base, axes, (x, y))?;
    Ok(crate::bodies::law(&spec).and_then(|l| l.outcome))
}

/// The law's boundaries along x in the row at `y` over `(from, to)`: scanned at the cells' edges
/// and centres `xs`, each change bisected on the law until no representable x lies between.
fn law_boundaries(
    base: &SceneParams,
    axes: (Axis, Axis),
    (from, to): (f64, f64),
    xs: &[f64],
    y: f64,
) -> anyhow::Result<Vec<Boundary>> {
    let class = |x: f64| -> anyhow::Result<Option<OutcomeKind>> { law_at(base, axes, (x, y)) };
    let mut points = vec![from];
    points.extend_from_slice(xs);
    points.push(to);
    let mut found = Vec::new();
    // Consecutive points the law decides (a point at its threshold is skipped, so a boundary
    // on a scan point is still found).
    let mut last: Option<(f64, OutcomeKind)> = None;
    for x in points {
        let Some(class_here) = class(x)? else { continue };
        let Some((from, below)) = last.replace((x, class_here)) else { continue };
        if below == class_here {
            continue;
        }
        let (mut lo, mut hi, mut above) = (from, x, class_here);
        loop {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            match class(mid)? {
                Some(here) if here == below => lo = mid,
                // The law's threshold itself (undecided) bounds the interval, not a class.
                None => hi = mid,
                Some(here) => {
                    hi = mid;
                    above = here;
                }
            }
        }
        found.push(Boundary { y, x: 0.5 * (lo + hi), width: hi - lo, below, above });
    }
    Ok(found)
}

/// Cells compared with the law away from its boundaries ([`MapSummary::law_disagreements`]).
fn agreement(outcomes: &[Vec<OutcomeKind>], law: &[Vec<Option<OutcomeKind>>]) -> LawAgreement {
    let mut tally = LawAgreement { cells_compared: 0, disagree: 0 };
    for (j, row) in law.iter().enumerate() {
        for (i, &here) in row.iter().enumerate() {
            let Some(expected) = here else { continue };
            let rows = j.saturating_sub(1)..=(j + 1).min(law.len() - 1);
            let alike = rows
                .into_iter()
                .all(|r| (i.saturating_sub(1)..=(i + 1).min(row.len() - 1)).all(|c| law[r][c] == here));
            if alike {
                tally.cells_compared += 1;
                tally.disagree += usize::from(outcomes[j][i] != expected);
            }
        }
    }
    tally
}

/// `base` with the axes at `(x, y)`: a scene flag first, then `mu-ratio` or `launch-ratio` (which
/// scale the cell's `mu_s`, or set its spin from its speed and radius, whichever axis sets those).
fn apply_axes(base: &SceneParams, axes: (Axis, Axis), (x, y): (f64, f64)) -> anyhow::Result<SceneParams> {
    let mut spec = *base;
    let derived = |a: Axis| matches!(a, Axis::MuRatio | Axis::LaunchRatio);
    let (first, second) =
        if derived(axes.0) { ((axes.1, y), (axes.0, x)) } else { ((axes.0, x), (axes.1, y)) };
    first.0.apply(&mut spec, first.1)?;
    second.0.apply(&mut spec, second.1)?;
    Ok(spec)
}

/// A grid over two axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    /// The x and y axes.
    pub axes: (Axis, Axis),
    /// The x range (`from`, `to`), in the x axis's unit.
    pub x: (f64, f64),
    /// The y range.
    pub y: (f64, f64),
    /// Columns and rows.
    pub cells: [usize; 2],
    /// Bisect each boundary along x to this width (0: no bisection).
    pub tolerance: f64,
    /// A quantity the scene measures, drawn beside the outcome: its index in the scene's
    /// measures (`SceneKind::info().measures`; the core's runs only).
    pub measure: Option<usize>,
}

impl Grid {
    /// The meter stick's outcome over finger speed (`from..to` m/s) and `mu_k / mu_s` (0.2 .. 1).
    ///
    /// # Errors
    /// None in practice: the `speed` flag is in [`FLAGS`].
    pub fn speed_by_mu_ratio(
        (from, to): (f64, f64),
        cells: [usize; 2],
        tolerance: f64,
    ) -> anyhow::Result<Self> {
        let speed = Axis::parse("speed", SceneKind::MeterStick)?;
        Ok(Self {
            axes: (speed, Axis::MuRatio),
            x: (from, to),
            y: (0.2, 1.0),
            cells,
            tolerance,
            measure: None,
        })
    }

    /// Checks the centres of the grid's four corner cells on `base`: every run is at a cell's
    /// centre or between two neighbours' (the bisection), the ranges are linear and the parameter
    /// checks are bounds, so those four stand for the whole grid (and a whole-number axis, such as
    /// `points` over `3.5,8.5` in 5 cells, is checked at 4 and 8, where it runs).
    ///
    /// # Errors
    /// The first corner whose parameters do not validate, in the flags' words.
    pub fn validate(&self, base: &SceneParams, implementation: Implementation) -> anyhow::Result<()> {
        let ends = |range: (f64, f64), cells: usize| {
            let c = centres(range, cells.max(1));
            [c.first().copied().unwrap_or(range.0), c.last().copied().unwrap_or(range.1)]
        };
        for x in ends(self.x, self.cells[0]) {
            for y in ends(self.y, self.cells[1]) {
                let spec = apply_axes(base, self.axes, (x, y))?;
                // `{:?}`: 1e300 stays 1e300 (Display writes all 301 digits).
                let at_corner = |why: String| {
                    anyhow::anyhow!(
                        "--x-range {:?},{:?} x --y-range {:?},{:?}: at the corner cell ({x:?}, {y:?}): {why}",
                        self.x.0,
                        self.x.1,
                        self.y.0,
                        self.y.1,
                    )
                };
                spec.validate(implementation.precision()).map_err(|e| at_corner(flag_error(&spec, e)))?;
                // A cell's steps grow toward a corner (smaller h, longer duration, slower fingers).
                let steps = spec.steps();
                if steps.is_nan() || steps > MAX_STEPS {
                    let refusal =
                        Refusal::TooManySteps { params: spec, steps, limit: MAX_STEPS, followed: false };
                    return Err(at_corner(refusal.worded("--").to_string()));
                }
            }
        }
        Ok(())
    }
}

/// Computes the outcome of `base` over `grid`, in `implementation`, with progress bars.
///
/// # Errors
/// Parameters that do not validate at a corner (before anything runs), or a cell that cannot run.
pub fn compute(base: &SceneParams, grid: &Grid, implementation: Implementation) -> anyhow::Result<Map> {
    grid.validate(base, implementation)?;
    let axes = grid.axes;
    let (xs, ys) = (centres(grid.x, grid.cells[0]), centres(grid.y, grid.cells[1]));
    let cells = xs.len() * ys.len();
    let started = Instant::now();
    let bar = progress(cells as u64, "map cells");
    let flat: Vec<anyhow::Result<(OutcomeKind, f64)>> = (0..cells)
        .into_par_iter()
        .map(|k| {
            let r =
                outcome_at(base, axes, (xs[k % xs.len()], ys[k / xs.len()]), implementation, grid.measure);
            bar.inc(1);
            r
        })
        .collect();
    bar.finish_and_clear();
    let (flat, values): (Vec<OutcomeKind>, Vec<f64>) =
        flat.into_iter().collect::<anyhow::Result<Vec<_>>>()?.into_iter().unzip();
    let outcomes: Vec<Vec<OutcomeKind>> = flat.chunks(xs.len()).map(<[OutcomeKind]>::to_vec).collect();
    let measured = grid.measure.map(|i| {
        let name = base.kind().info().measures.get(i).copied().unwrap_or("");
        (name, values.chunks(xs.len()).map(<[f64]>::to_vec).collect())
    });
    // Boundaries along x, bisected.
    let pairs: Vec<(usize, usize)> = (0..ys.len())
        .flat_map(|j| (1..xs.len()).map(move |i| (j, i)))
        .filter(|&(j, i)| outcomes[j][i] != outcomes[j][i - 1])
        .collect();
    let bar = progress(pairs.len() as u64, "bisecting boundaries");
    let bisected: Vec<anyhow::Result<(Boundary, usize)>> = pairs
        .par_iter()
        .map(|&(j, i)| {
            let (mut lo, mut hi) = (xs[i - 1], xs[i]);
            let (below, mut above) = (outcomes[j][i - 1], outcomes[j][i]);
            let mut runs = 0;
            // Keeps `outcome(lo) = below != outcome(hi) = above`: a midpoint of a third class
            // becomes the new `hi` and its class the new `above`, so the interval always holds a
            // change between the two classes it is labelled with (the first from `lo`, when a
            // cell holds several).
            while grid.tolerance > 0.0 && hi - lo > grid.tolerance && runs < 64 {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break; // no representable point between them
                }
                // A midpoint the core refuses (a whole-number axis such as `points`) ends the
                // bisection: the boundary lies between the two valid points.
                if apply_axes(base, axes, (mid, ys[j]))?.validate(implementation.precision()).is_err() {
                    break;
                }
                runs += 1;
                let (here, _) = outcome_at(base, axes, (mid, ys[j]), implementation, None)?;
                if here == below {
                    lo = mid;
                } else {
                    hi = mid;
                    above = here;
                }
            }
            bar.inc(1);
            Ok((Boundary { y: ys[j], x: 0.5 * (lo + hi), width: (hi - lo).abs(), below, above }, runs))
        })
        .collect();
    bar.finish_and_clear();
    let bisected = bisected.into_iter().collect::<anyhow::Result<Vec<_>>>()?;
    let runs = cells + bisected.iter().map(|b| b.1).sum::<usize>();
    let mut counts: Vec<(OutcomeKind, usize)> = Vec::new();
    for o in &flat {
        match counts.iter_mut().find(|(c, _)| c == o) {
            Some((_, n)) => *n += 1,
            None => counts.push((*o, 1)),
        }
    }
    let law = if crate::bodies::law(base).is_some() {
        let rows = ys
            .iter()
            .map(|&y| xs.iter().map(|&x| law_at(base, axes, (x, y))).collect())
            .collect::<anyhow::Result<Vec<Vec<_>>>>()?;
        Some(rows)
    } else {
        None
    };
    let law_boundaries = match law {
        Some(_) => ys
            .iter()
            .map(|&y| law_boundaries(base, axes, grid.x, &xs, y))
            .collect::<anyhow::Result<Vec<_>>>()?
            .concat(),
        None => Vec::new(),
    };
    let summary = MapSummary {
        law_boundaries,
        law_disagreements: law.as_deref().map(|l| agreement(&outcomes, l)),
        scene: base.kind(),
        implementation: implementation.of_scene(base.kind()),
        x_axis: axes.0.label(),
        y_axis: axes.1.label(),
        cells: [xs.len(), ys.len()],
        runs,
        wall_s: started.elapsed().as_secs_f64(),
        counts,
        boundaries: bisected.into_iter().map(|b| b.0).collect(),
    };
    Ok(Map { xs, ys, outcomes, law, measured, summary })
}

/// Writes `map.csv`, `boundaries.csv`, `summary.json` and `map.svg` into `out`.
///
/// # Errors
/// I/O or plotting, naming the file.
pub fn write(map: &Map, out: &Path) -> anyhow::Result<()> {
    create_dir(out)?;
    let s = &map.summary;
    let value =
        |j: usize, i: usize| map.measured.as_ref().map(|(_, v)| format!(",{}", v[j][i])).unwrap_or_default();
    let cells = map.ys.iter().enumerate().flat_map(|(j, y)| {
        map.xs.iter().enumerate().map(move |(i, x)| format!("{x},{y},{}{}", map.outcomes[j][i], value(j, i)))
    });
    let header = match &map.measured {
        Some((name, _)) => format!("x,y,outcome,{name}"),
        None => "x,y,outcome".into(),
    };
    write_lines(&out.join("map.csv"), &header, cells)?;
    if let Some((name, values)) = &map.measured {
        let title =
            format!("{} {name}, {} ({} x {} cells)", s.scene, s.implementation, s.cells[0], s.cells[1]);
        plot::value_map(
            &out.join("measure.svg"),
            &title,
            (&s.x_axis, &map.xs),
            (&s.y_axis, &map.ys),
            values,
        )?;
    }
    let bounds = s.boundaries.iter().map(|b| format!("{},{},{},{},{}", b.y, b.x, b.width, b.below, b.above));
    write_lines(&out.join("boundaries.csv"), "y,x,width,below,above", bounds)?;
    let laws =
        s.law_boundaries.iter().map(|b| format!("{},{},{},{},{}", b.y, b.x, b.width, b.below, b.above));
    if map.law.is_some() {
        write_lines(&out.join("law_boundaries.csv"), "y,x,width,below,above", laws)?;
    }
    write_json(&out.join("summary.json"), s)?;
    // One line per kind of law boundary (`Held | Rode`), through its points in row order.
    let mut lines: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    for b in &s.law_boundaries {
        let label = format!("law: {} | {}", b.below, b.above);
        match lines.iter_mut().find(|(l, _)| *l == label) {
            Some((_, points)) => points.push((b.x, b.y)),
            None => lines.push((label, vec![(b.x, b.y)])),
        }
    }
    let title = format!("{} outcome, {} ({} x {} cells)", s.scene, s.implementation, s.cells[0], s.cells[1]);
    plot::outcome_raster(
        &out.join("map.svg"),
        &title,
        (&s.x_axis, &map.xs),
        (&s.y_axis, &map.ys),
        &map.outcomes,
        &s.boundaries.iter().map(|b| (b.x, b.y)).collect::<Vec<_>>(),
        &lines,
    )
}
