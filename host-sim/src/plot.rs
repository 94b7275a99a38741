//! SVG plots (plotters, SVG backend only: no font or image libraries needed).

use std::path::Path;

use anyhow::{Context as _, anyhow};
pub use plotters::prelude::SeriesLabelPosition;
use plotters::prelude::*;

use crate::scenes::SceneKind;
use crate::trajectory::{Row, Trajectory};

/// At most this many points per plotted series (trajectories are thinned evenly).
const MAX_POINTS: usize = 3000;

fn thin<T: Copy>(v: &[T]) -> impl Iterator<Item = T> + '_ {
    let stride = v.len().div_ceil(MAX_POINTS).max(1);
    v.iter().step_by(stride).copied().chain(v.last().copied().filter(|_| v.len() % stride != 1))
}

fn err<E: std::fmt::Display>(e: E) -> anyhow::Error {
    anyhow!("plotting: {e}")
}

const PALETTE: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(23, 190, 207),
];

fn tick_label(v: f64, log: bool) -> String {
    if log { format!("{v:.0e}") } else { format!("{}", (v * 1e6).round() / 1e6) }
}

/// One line of a chart.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend text.
    pub label: String,
    /// `(x, y)` points; non-finite ones (and non-positive ones on log axes) are skipped.
    pub points: Vec<(f64, f64)>,
    /// Dashed (a second implementation) or solid.
    pub dashed: bool,
}

/// A line chart of several series, optionally log-log, written as SVG.
///
/// # Errors
/// Nothing to plot, or I/O.
pub fn lines(
    path: &Path,
    title: &str,
    axes: (&str, &str),
    series: &[Series],
    log_log: bool,
    legend: &SeriesLabelPosition,
) -> anyhow::Result<()> {
    let root = SVGBackend::new(path, (900, 560)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    draw_lines(&root, title, axes, series, log_log, legend)
        .with_context(|| format!("plotting {}", path.display()))?;
    root.present().map_err(err)
}

/// Draws a line chart on `area`. Solid series are thick; dashed ones (a second implementation)
/// thin, dashed, with a marker every few points, and a dashed legend swatch, so that two
/// implementations on top of each other can be told apart.
fn draw_lines<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    title: &str,
    (x_desc, y_desc): (&str, &str),
    series: &[Series],
    log_log: bool,
    legend: &SeriesLabelPosition,
) -> anyhow::Result<()>
where
    DB::ErrorType: 'static,
{
    let finite =
        |p: &&(f64, f64)| p.0.is_finite() && p.1.is_finite() && (!log_log || (p.0 > 0.0 && p.1 > 0.0));
    let pts: Vec<(f64, f64)> = series.iter().flat_map(|s| s.points.iter().filter(finite).copied()).collect();
    anyhow::ensure!(!pts.is_empty(), "no finite points");
    let (mut x0, mut x1, mut y0, mut y1) = pts
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY), |(a, b, c, d), p| {
            (a.min(p.0), b.max(p.0), c.min(p.1), d.max(p.1))
        });
    if log_log {
        (x0, x1, y0, y1) = (x0 / 1.5, x1 * 1.5, y0 / 2.0, y1 * 2.0);
    } else {
        let (dx, dy) = ((x1 - x0).max(1e-12) * 0.03, (y1 - y0).max(1e-12) * 0.05);
        (x0, x1, y0, y1) = (x0 - dx, x1 + dx, y0 - dy, y1 + dy);
    }
    let mut builder = ChartBuilder::on(area);
    builder.caption(title, ("sans-serif", 18)).margin(12).x_label_area_size(45).y_label_area_size(75);
    macro_rules! draw {
        ($chart:expr) => {{
            let mut chart = $chart;
            chart
                .configure_mesh()
                .x_desc(x_desc)
                .y_desc(y_desc)
                .x_label_formatter(&|v| tick_label(*v, log_log))
                .y_label_formatter(&|v| tick_label(*v, log_log))
                .draw()
                .map_err(err)?;
            // Solid and dashed series are coloured in the same order, so that a quantity has
            // one colour in both implementations.
            let (mut solid, mut dash) = (0, 0);
            for Series { label, points, dashed } in series {
                let k = if *dashed { &mut dash } else { &mut solid };
                let color = PALETTE[*k % PALETTE.len()];
                *k += 1;
                let style = if *dashed { color.stroke_width(1) } else { color.stroke_width(3) };
                let data: Vec<(f64, f64)> = thin(points).filter(|p| finite(&p)).collect();
                if log_log || *dashed {
                    let every = if log_log { 1 } else { (data.len() / 25).max(1) };
                    let marks: Vec<(f64, f64)> = data.iter().copied().step_by(every).collect();
                    let size = if *dashed { 3 } else { 4 };
                    chart
                        .draw_series(PointSeries::of_element(marks, size, style, &|c, s, st| {
                            EmptyElement::at(c) + Circle::new((0, 0), s, st)
                        }))
                        .map_err(err)?;
                }
                let anno = if *dashed {
                    chart.draw_series(DashedLineSeries::new(data, 7, 5, style)).map_err(err)?
                } else {
                    chart.draw_series(LineSeries::new(data, style)).map_err(err)?
                };
                let dashed = *dashed;
                // A dashed swatch with a marker for a dashed series, a thick line otherwise.
                let (gap, marker, width) = if dashed { (4, 3, 2) } else { (0, 0, 3) };
                anno.label(label.as_str()).legend(move |(x, y)| {
                    EmptyElement::at((x, y))
                        + PathElement::new(vec![(0, 0), (10 - gap / 2, 0)], color.stroke_width(width))
                        + PathElement::new(vec![(10 + gap / 2, 0), (20, 0)], color.stroke_width(width))
                        + Circle::new((24, 0), marker, color.stroke_width(1))
                });
            }
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .position(legend.clone())
                .draw()
                .map_err(err)?;
        }};
    }
    if log_log {
        draw!(builder.build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale()).map_err(err)?);
    } else {
        draw!(builder.build_cartesian_2d(x0..x1, y0..y1).map_err(err)?);
    }
    Ok(())
}

/// One panel of [`panels`]: its y axis, its series, where its legend goes.
pub type Panel<'a> = (&'a str, Vec<Series>, SeriesLabelPosition);

/// Line charts stacked vertically, one per [`Panel`], over a common x axis, the title over the
/// first.
///
/// # Errors
/// A panel with nothing to plot, or I/O.
pub fn panels(path: &Path, title: &str, x_desc: &str, panels: &[Panel<'_>]) -> anyhow::Result<()> {
    let height = 380 * u32::try_from(panels.len()).unwrap_or(1).max(1);
    let root = SVGBackend::new(path, (900, height)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    for (k, (area, (y_desc, series, legend))) in
        root.split_evenly((panels.len(), 1)).iter().zip(panels).enumerate()
    {
        let title = if k == 0 { title } else { "" };
        draw_lines(area, title, (x_desc, y_desc), series, false, legend)
            .with_context(|| format!("plotting {}", path.display()))?;
    }
    root.present().map_err(err)
}

/// Series of one quantity of every run: solid for the first run, dashed for the others.
fn per_run<const K: usize>(
    runs: &[&Trajectory<K>],
    name: &str,
    value: impl Fn(&Row<K>) -> f64,
) -> Vec<Series> {
    runs.iter()
        .enumerate()
        .map(|(k, run)| Series {
            label: format!("{name} ({})", run.implementation.of_scene(run.scene)),
            points: run.rows.iter().map(|r| (r.t, value(r))).collect(),
            dashed: k > 0,
        })
        .collect()
}

/// The paper's figs. 2, 3 and 5: each support's and the centre of mass's `x` over time (for a
/// scene on fixed lines: the centre of mass's `x` and `y`), core solid, reference dashed.
///
/// # Errors
/// I/O.
pub fn positions<const K: usize>(path: &Path, title: &str, runs: &[&Trajectory<K>]) -> anyhow::Result<()> {
    let mut series = Vec::new();
    if runs.first().is_some_and(|r| matches!(r.scene, SceneKind::MeterStick | SceneKind::ThreeFingers)) {
        for i in 0..K {
            series.extend(per_run(runs, &format!("finger {}", i + 1), |r| r.supports[i][0]));
        }
        series.extend(per_run(runs, "centre of mass", |r| r.q[0]));
        return lines(path, title, ("t (s)", "x (m)"), &series, false, &SeriesLabelPosition::LowerRight);
    }
    series.extend(per_run(runs, "centre of mass x", |r| r.q[0]));
    series.extend(per_run(runs, "centre of mass y", |r| r.q[1]));
    lines(path, title, ("t (s)", "position (m)"), &series, false, &SeriesLabelPosition::LowerLeft)
}

/// The body's angle and its centre of mass's height over time, in two panels (so that a fall,
/// a tip or a slide shows even where the `x` plot looks calm).
///
/// # Errors
/// I/O.
pub fn motion<const K: usize>(path: &Path, title: &str, runs: &[&Trajectory<K>]) -> anyhow::Result<()> {
    let angle = per_run(runs, "angle", |r| r.q[2].to_degrees());
    let height = per_run(runs, "centre of mass height", |r| r.q[1]);
    panels(
        path,
        title,
        "t (s)",
        &[
            ("angle (deg)", angle, SeriesLabelPosition::UpperLeft),
            ("height y (m)", height, SeriesLabelPosition::LowerLeft),
        ],
    )
}

/// Finger positions relative to the centre of mass, along the rod, over time (meter stick).
///
/// # Errors
/// I/O.
pub fn relative<const K: usize>(path: &Path, title: &str, runs: &[&Trajectory<K>]) -> anyhow::Result<()> {
    let mut series = Vec::new();
    for i in 0..K {
        series.extend(per_run(runs, &format!("finger {} - COM", i + 1), |r| r.contacts[i].along));
    }
    lines(
        path,
        title,
        ("t (s)", "distance from the COM along the rod (m)"),
        &series,
        false,
        &SeriesLabelPosition::MiddleLeft,
    )
}

/// The colour of an outcome class in every picture.
#[must_use]
pub const fn outcome_color(class: crate::trajectory::OutcomeKind) -> RGBColor {
    use crate::trajectory::OutcomeKind as O;
    match class {
        O::Balanced | O::Held | O::Rolled | O::Stayed | O::Stopped => RGBColor(44, 160, 44),
        O::Rode => RGBColor(31, 119, 180),
        O::Fell | O::Tipped | O::Jammed => RGBColor(214, 39, 40),
        O::Slid => RGBColor(255, 127, 14),
        O::Unfinished => RGBColor(200, 200, 200),
        O::Failed => RGBColor(0, 0, 0),
    }
}

/// A map of outcomes over two continuous axes: one rectangle per cell (`cells[row][column]` at
/// the centres `xs`, `ys`), coloured by class, with the bisected boundaries as black dots, numeric
/// axes, and a legend of the classes present. `boundaries` are `(x, y)` points; `laws` the
/// analytic boundaries, each a labelled polyline drawn dashed.
///
/// # Errors
/// I/O.
pub fn outcome_raster(
    path: &Path,
    title: &str,
    (x_desc, xs): (&str, &[f64]),
    (y_desc, ys): (&str, &[f64]),
    cells: &[Vec<crate::trajectory::OutcomeKind>],
    boundaries: &[(f64, f64)],
    laws: &[(String, Vec<(f64, f64)>)],
) -> anyhow::Result<()> {
    use crate::trajectory::OutcomeKind as O;
    let color = outcome_color;
    let half = |v: &[f64]| if v.len() > 1 { (v[1] - v[0]).abs() / 2.0 } else { 0.5 };
    let (hx, hy) = (half(xs), half(ys));
    let bounds = |v: &[f64], h: f64| {
        let lo = v.iter().copied().fold(f64::INFINITY, f64::min) - h;
        let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max) + h;
        (lo, hi)
    };
    let ((x0, x1), (y0, y1)) = (bounds(xs, hx), bounds(ys, hy));
    let root = SVGBackend::new(path, (1100, 620)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(12)
        .margin_right(24)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(err)?;
    chart.configure_mesh().disable_mesh().x_desc(x_desc).y_desc(y_desc).draw().map_err(err)?;
    for (j, row) in cells.iter().enumerate() {
        for (i, &c) in row.iter().enumerate() {
            let (x, y) = (xs[i], ys[j]);
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [(x - hx, y - hy), (x + hx, y + hy)],
                    color(c).filled(),
                )))
                .map_err(err)?;
        }
    }
    chart
        .draw_series(boundaries.iter().map(|&b| Circle::new(b, 2, BLACK.filled())))
        .map_err(err)?
        .label("boundary (bisected)")
        .legend(|(x, y)| Circle::new((x + 6, y), 3, BLACK.filled()));
    for (k, (label, points)) in laws.iter().enumerate() {
        // Dark, so that they show on every class's colour.
        let color = [BLACK, RGBColor(110, 0, 130), RGBColor(120, 70, 0)][k % 3];
        let style = color.stroke_width(2);
        chart
            .draw_series(DashedLineSeries::new(points.iter().copied(), 8, 5, style))
            .map_err(err)?
            .label(label.as_str())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], color.stroke_width(2)));
    }
    let mut present: Vec<O> = cells.iter().flatten().copied().collect();
    present.sort_by_key(|c| c.name());
    present.dedup();
    for c in present {
        let col = color(c);
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
            .map_err(err)?
            .label(if c == O::Unfinished { "Unfinished (undecided at max-time)" } else { c.name() })
            .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 12, y + 5)], col.filled()));
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(err)?;
    root.present().map_err(err)
}

/// A heat map of ratios to a bound: one cell per `(column, row)`, coloured by
/// `log10(value)`: green up to 1e-3 of the bound, yellow to orange up to the bound, red
/// beyond it; grey where there is no value.
///
/// # Errors
/// I/O.
pub fn ratio_map(
    path: &Path,
    title: &str,
    columns: &[String],
    rows: &[String],
    values: &[Vec<Option<f64>>],
) -> anyhow::Result<()> {
    let color = |v: Option<f64>| match v {
        None => RGBColor(200, 200, 200),
        Some(r) if r > 1.0 || r.is_nan() => RGBColor(214, 39, 40),
        Some(r) => {
            // -3 (or less) -> green, 0 -> orange.
            let a = ((r.max(1e-30).log10() + 3.0) / 3.0).clamp(0.0, 1.0);
            let mix = |g: f64, o: f64| (g + a * (o - g)).round() as u8;
            RGBColor(mix(44.0, 255.0), mix(160.0, 160.0), mix(44.0, 0.0))
        }
    };
    let colors: Vec<Vec<RGBColor>> =
        values.iter().map(|row| row.iter().map(|&v| color(v)).collect()).collect();
    let legend = [
        ("<= 1e-3 of the bound".to_string(), color(Some(1e-3))),
        ("1e-1 of the bound".to_string(), color(Some(0.1))),
        ("at the bound".to_string(), color(Some(1.0))),
        ("beyond: fails".to_string(), color(Some(2.0))),
        ("no value".to_string(), color(None)),
    ];
    let height = 140 + 22 * rows.len() as u32;
    heat_map(path, title, ("", columns), ("", rows), &colors, &legend, (1100, height))
}

/// A quantity over a map's cells, `values[row][column]` at the column centres `xs` and the row
/// centres `ys`: each cell coloured on a linear scale from the least value (blue) to the largest
/// (yellow), grey where there is none (NaN); the legend gives the two ends and the middle.
///
/// # Errors
/// I/O.
pub fn value_map(
    path: &Path,
    title: &str,
    (x_desc, xs): (&str, &[f64]),
    (y_desc, ys): (&str, &[f64]),
    values: &[Vec<f64>],
) -> anyhow::Result<()> {
    let finite = values.iter().flatten().copied().filter(|v| v.is_finite());
    let (lo, hi) = finite.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
    let color = |v: f64| {
        if !v.is_finite() {
            return RGBColor(200, 200, 200);
        }
        let a = if hi > lo { ((v - lo) / (hi - lo)).clamp(0.0, 1.0) } else { 0.5 };
        let mix = |from: f64, to: f64| (from + a * (to - from)).round() as u8;
        RGBColor(mix(40.0, 250.0), mix(60.0, 220.0), mix(160.0, 40.0))
    };
    let colors: Vec<Vec<RGBColor>> =
        values.iter().map(|row| row.iter().map(|&v| color(v)).collect()).collect();
    let short = |v: &f64| format!("{}", meterstick_catalogue::Short(*v));
    let legend: Vec<(String, RGBColor)> = if lo <= hi {
        let mid = 0.5 * (lo + hi);
        vec![
            (short(&lo), color(lo)),
            (short(&mid), color(mid)),
            (short(&hi), color(hi)),
            ("none".into(), color(f64::NAN)),
        ]
    } else {
        vec![("none".into(), color(f64::NAN))]
    };
    let labels = |v: &[f64]| v.iter().map(short).collect::<Vec<_>>();
    let height = 160 + 26 * ys.len().min(30) as u32;
    heat_map(
        path,
        title,
        (x_desc, &labels(xs)),
        (y_desc, &labels(ys)),
        &colors,
        &legend,
        (1100, height.max(420)),
    )
}

/// Coloured cells `colors[row][column]` with labelled axes and a legend.
fn heat_map(
    path: &Path,
    title: &str,
    (x_desc, x_labels): (&str, &[String]),
    (y_desc, y_labels): (&str, &[String]),
    colors: &[Vec<RGBColor>],
    legend: &[(String, RGBColor)],
    size: (u32, u32),
) -> anyhow::Result<()> {
    let (nx, ny) = (x_labels.len(), y_labels.len());
    let y_area = 12 + 7 * y_labels.iter().map(String::len).max().unwrap_or(4) as u32;
    let root = SVGBackend::new(path, size).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(y_area.max(75))
        // A segmented `0..n` has segments 0..=n; `0..n-1` has the n cells.
        .build_cartesian_2d((0..nx.max(2) - 1).into_segmented(), (0..ny.max(2) - 1).into_segmented())
        .map_err(err)?;
    let label = |labels: &[String], v: &SegmentValue<usize>| match v {
        SegmentValue::CenterOf(i) => labels.get(*i).cloned().unwrap_or_default(),
        _ => String::new(),
    };
    chart
        .configure_mesh()
        .disable_mesh()
        .x_labels(nx)
        .y_labels(ny)
        .x_label_formatter(&|v| label(x_labels, v))
        .y_label_formatter(&|v| label(y_labels, v))
        .x_desc(x_desc)
        .y_desc(y_desc)
        .draw()
        .map_err(err)?;
    for (j, row) in colors.iter().enumerate() {
        for (i, &c) in row.iter().enumerate() {
            let cell = [
                (SegmentValue::Exact(i), SegmentValue::Exact(j)),
                (SegmentValue::Exact(i + 1), SegmentValue::Exact(j + 1)),
            ];
            chart.draw_series(std::iter::once(Rectangle::new(cell.clone(), c.filled()))).map_err(err)?;
            chart.draw_series(std::iter::once(Rectangle::new(cell, WHITE.stroke_width(2)))).map_err(err)?;
        }
    }
    for (name, c) in legend {
        let c = *c;
        chart
            .draw_series(std::iter::empty::<Circle<(SegmentValue<usize>, SegmentValue<usize>), i32>>())
            .map_err(err)?
            .label(name)
            .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 12, y + 5)], c.filled()));
    }
    chart.configure_series_labels().background_style(WHITE).border_style(BLACK).draw().map_err(err)?;
    root.present().map_err(err)
}
