//! `host-sim map`: the outcome of a scene over two of its parameters, on a grid a person chooses,
//! with the boundaries between outcomes located by bisection ([`crate::map`]); writes `map.csv`,
//! `boundaries.csv`, `summary.json` and `map.svg`.
//!
//! The default is the meter stick's outcome over finger speed (0.05 .. 1 m/s, 200 columns) and
//! `mu_k / mu_s` (0.2 .. 1, 50 rows, `mu_s` fixed). Any scene flag can be an axis (`--x-axis x1`,
//! `--y-axis angle`), `mu-ratio` scales `mu_k` to `ratio * mu_s`, and `mu` sets `mu_s = mu_k` (the
//! puck's outcome over `--x-axis mu --y-axis angle`). Each row's boundaries are
//! bisected to `--tolerance` (default 1e-3, in the x axis's unit), every run in the precision and
//! LCP size given (default the firmware's, core f32 6x6). Runs go in parallel on all cores.
//!
//! `--measure` writes a quantity the scene measures beside each cell's outcome and draws it
//! (the curling stone's terminal ratio over `--x-axis points --y-axis launch-ratio`).
//!
//! A scene of several bodies maps the same way (`--scene block-on-block --x-axis force --y-axis
//! mu-s`), its law's boundaries (`docs/scenes.md`) drawn beside the runs' and the cells away from
//! them compared with it.

use std::fmt::Write as _;
use std::path::PathBuf;

use anyhow::{Context as _, bail};

use crate::map::{self, Axis, Grid, MAX_CELLS, Map};
use crate::scenes::{Implementation, SceneArgs};
use meterstick_catalogue::Catalogued as _;

/// `host-sim map` options.
#[derive(Debug, Clone, clap::Args)]
pub struct MapArgs {
    /// The scene and its fixed parameters (the axes' flags are set per cell).
    #[command(flatten)]
    pub scene: SceneArgs,
    /// The x axis: a scene flag (e.g. speed, x1, angle), mu-ratio, or mu (mu-s = mu-k).
    #[arg(long, default_value = "speed")]
    pub x_axis: String,
    /// The x range, `from,to`, in the flag's unit.
    #[arg(long, default_value = "0.05,1", allow_hyphen_values = true)]
    pub x_range: String,
    /// Columns.
    #[arg(long, default_value_t = 200)]
    pub x_cells: usize,
    /// The y axis: a scene flag, mu-ratio (mu_k / mu_s, mu_s fixed), or mu (mu-s = mu-k).
    #[arg(long, default_value = "mu-ratio")]
    pub y_axis: String,
    /// The y range, `from,to`.
    #[arg(long, default_value = "0.2,1", allow_hyphen_values = true)]
    pub y_range: String,
    /// Rows.
    #[arg(long, default_value_t = 50)]
    pub y_cells: usize,
    /// Bisect each boundary along x to this width (in the x axis's unit; 0: no bisection).
    #[arg(long, default_value_t = 1e-3)]
    pub tolerance: f64,
    /// A quantity the scene measures (a key of its `summary.json`'s `measured`, e.g.
    /// `terminal_ratio`), written beside each cell's outcome (`map.csv`) and drawn in `measure.svg`;
    /// the core's runs only.
    #[arg(long)]
    pub measure: Option<String>,
    /// Output directory (created; files in it are overwritten).
    #[arg(long, default_value = "out/map")]
    pub out: PathBuf,
}

fn parse_range(flag: &str, s: &str) -> anyhow::Result<(f64, f64)> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    let [a, b] = parts.as_slice() else { bail!("{flag} {s:?}: give two numbers, from,to") };
    let parse = |t: &str| t.parse::<f64>().with_context(|| format!("{flag} {s:?}: {t:?} is not a number"));
    let (a, b) = (parse(a)?, parse(b)?);
    if !(a.is_finite() && b.is_finite() && a < b) {
        bail!("{flag} {s:?}: two finite numbers, from < to");
    }
    Ok((a, b))
}

/// `--measure`'s index in the scene's measures, refused (naming those it has) before anything runs.
fn measure_of(args: &MapArgs) -> anyhow::Result<Option<usize>> {
    let Some(name) = &args.measure else { return Ok(None) };
    let kind = args.scene.kind();
    let measures = kind.info().measures;
    let Some(index) = measures.iter().position(|m| m == name) else {
        let names = if measures.is_empty() { "none".to_string() } else { measures.join(", ") };
        bail!("--measure {name}: --scene {kind} measures {names}");
    };
    if args.scene.implementation() == Implementation::Reference {
        bail!("--measure {name}: a map of a measure runs in the core (--precision), not the reference");
    }
    Ok(Some(index))
}

/// The grid `args` describe.
///
/// # Errors
/// Bad axes, ranges, cell counts or tolerance, naming the flag.
pub fn grid(args: &MapArgs) -> anyhow::Result<Grid> {
    let grid = Grid {
        axes: (Axis::parse(&args.x_axis, args.scene.kind())?, Axis::parse(&args.y_axis, args.scene.kind())?),
        x: parse_range("--x-range", &args.x_range)?,
        y: parse_range("--y-range", &args.y_range)?,
        cells: [args.x_cells, args.y_cells],
        tolerance: args.tolerance,
        measure: measure_of(args)?,
    };
    let names = (args.x_axis.trim_start_matches("--"), args.y_axis.trim_start_matches("--"));
    if grid.axes.0 == grid.axes.1 {
        bail!("--x-axis and --y-axis are both {}: choose two different axes", names.0);
    }
    let is_mu_k = |a: Axis| matches!(a, Axis::Flag(f) if f.long == "mu-k");
    let is_mu = |a: Axis| matches!(a, Axis::Flag(f) if f.long == "mu-k" || f.long == "mu-s");
    if (grid.axes.0 == Axis::MuRatio || grid.axes.1 == Axis::MuRatio)
        && (is_mu_k(grid.axes.0) || is_mu_k(grid.axes.1))
    {
        bail!(
            "--x-axis {} with --y-axis {}: mu-ratio sets mu-k, so the two cannot both be axes",
            names.0,
            names.1
        );
    }
    if (grid.axes.0 == Axis::Coulomb || grid.axes.1 == Axis::Coulomb)
        && (is_mu(grid.axes.0)
            || is_mu(grid.axes.1)
            || grid.axes.0 == Axis::MuRatio
            || grid.axes.1 == Axis::MuRatio)
    {
        bail!(
            "--x-axis {} with --y-axis {}: mu sets mu-s and mu-k, so the two cannot both be axes",
            names.0,
            names.1
        );
    }
    let cells = args.x_cells.saturating_mul(args.y_cells);
    if args.x_cells == 0 || args.y_cells == 0 || cells > MAX_CELLS {
        bail!("--x-cells {} x --y-cells {}: between 1 and {MAX_CELLS} cells", args.x_cells, args.y_cells);
    }
    if !(args.tolerance >= 0.0 && args.tolerance.is_finite()) {
        bail!("--tolerance {:?}: a finite number >= 0", args.tolerance);
    }
    Ok(grid)
}

/// Computes the map `args` describe.
///
/// # Errors
/// Bad axes, ranges, cell counts or parameters (before anything runs), or a cell that cannot run.
pub fn compute(args: &MapArgs) -> anyhow::Result<Map> {
    let grid = grid(args)?;
    let specs = args.scene.specs(None)?;
    let [(_, base)] = specs.as_slice() else {
        bail!("host-sim map varies two axes: give the other flags one value each")
    };
    map::compute(base, &grid, args.scene.implementation())
}

/// `host-sim map`: computes, writes, and returns the terminal summary.
///
/// # Errors
/// As [`compute`] and [`map::write`].
pub fn run(args: &MapArgs) -> anyhow::Result<String> {
    let map = compute(args)?;
    map::write(&map, &args.out)?;
    let s = &map.summary;
    let mut text = format!(
        "map: {} x {} cells of {} over {} x {}, {} runs in {:.1} s ({})\n",
        s.cells[0], s.cells[1], s.scene, s.x_axis, s.y_axis, s.runs, s.wall_s, s.implementation
    );
    for (class, n) in &s.counts {
        let _ = writeln!(text, "  {class}: {n} cells");
    }
    if let Some(a) = s.law_disagreements {
        let _ = writeln!(
            text,
            "the law (docs/scenes.md): {} boundaries (law_boundaries.csv, dashed in map.svg); of the {} cells more than one cell from them, {} disagree with it",
            s.law_boundaries.len(),
            a.cells_compared,
            a.disagree
        );
    }
    let _ = writeln!(
        text,
        "{} boundaries located to {:?} (boundaries.csv); files in {}",
        s.boundaries.len(),
        args.tolerance,
        args.out.display()
    );
    Ok(text)
}
