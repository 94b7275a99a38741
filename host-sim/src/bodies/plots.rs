//! A run's plots: every body's position, velocity and angle over time.

use meterstick_core::scene::SceneKind;

use super::{BodiesRow, BodiesRun};
use crate::plot::{self, Series, SeriesLabelPosition};

/// Body `i`'s name in `docs/scenes.md`'s words.
fn body_name(kind: SceneKind, i: usize) -> String {
    match (kind, i) {
        (SceneKind::BlockOnBlock, 0) => "bottom block".into(),
        (SceneKind::BlockOnBlock, _) => "top block".into(),
        (SceneKind::Tablecloth | SceneKind::DiscOnBoard, 0) => "board".into(),
        (SceneKind::Tablecloth, _) => "block".into(),
        (SceneKind::DiscOnBoard, _) => "disc".into(),
        (SceneKind::Puck, _) => "puck".into(),
        (SceneKind::Billiard, _) => "ball".into(),
        (_, 0) => "block 1 (bottom)".into(),
        _ => format!("block {}", i + 1),
    }
}

/// One series per body and run of `quantity` over time: the first run's solid, the others'
/// dashed, each body in the same colour in every run.
fn body_series(runs: &[&BodiesRun], quantity: &str, value: impl Fn(&BodiesRow, usize) -> f64) -> Vec<Series> {
    let bodies = runs.first().map_or(0, |r| r.last.q.len().max(r.last.spatial.len()));
    let mut series = Vec::new();
    for (k, run) in runs.iter().enumerate() {
        for body in 0..bodies {
            series.push(Series {
                label: format!("{} {quantity} ({})", body_name(run.scene, body), run.label),
                points: run.rows.iter().map(|r| (r.t, value(r, body))).collect(),
                dashed: k > 0,
            });
        }
    }
    series
}

/// A run's plots in `dir`: every body's position (`positions.svg`: `x`, and `y` in a second
/// panel), velocity (`velocities.svg`: `vx`, `vy`) and angle (`angles.svg`) over time, core
/// solid, reference dashed; of bodies in three dimensions, [`write_spatial_plots`]'s. Gives the
/// name of the third plot (`angles.svg` or `path.svg`).
pub(super) fn write_plots(
    name: &str,
    runs: &[&BodiesRun],
    dir: &std::path::Path,
) -> anyhow::Result<&'static str> {
    if runs.first().is_some_and(|r| !r.last.spatial.is_empty()) {
        write_spatial_plots(name, runs, dir)?;
        return Ok("path.svg");
    }
    let legend = SeriesLabelPosition::UpperLeft;
    for (file, title, panels) in [
        ("positions.svg", "positions", [("x (m)", 0, "x"), ("y (m)", 1, "y")]),
        ("velocities.svg", "velocities", [("vx (m/s)", 3, "vx"), ("vy (m/s)", 4, "vy")]),
    ] {
        let panels = panels.map(|(axis, index, quantity)| {
            let series =
                body_series(runs, quantity, |r, b| if index < 3 { r.q[b][index] } else { r.v[b][index - 3] });
            (axis, series, legend.clone())
        });
        plot::panels(&dir.join(file), &format!("{name}: {title}"), "t (s)", &panels)?;
    }
    let angles = body_series(runs, "angle", |r, b| r.q[b][2].to_degrees());
    plot::lines(
        &dir.join("angles.svg"),
        &format!("{name}: angles"),
        ("t (s)", "angle (deg)"),
        &angles,
        false,
        &legend,
    )?;
    Ok("angles.svg")
}

/// The plots of a scene in three dimensions in `dir`: every body's position (`positions.svg`: `x`,
/// `y`, `z`), speed and angular speed (`velocities.svg`) over time, and its path seen from above
/// (`path.svg`: `y` over `x`), core solid, reference dashed.
fn write_spatial_plots(name: &str, runs: &[&BodiesRun], dir: &std::path::Path) -> anyhow::Result<()> {
    let legend = SeriesLabelPosition::UpperLeft;
    let at = |r: &BodiesRow, b: usize| r.spatial.get(b).copied();
    let norm = |v: [f64; 3]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let positions = [("x (m)", 0, "x"), ("y (m)", 1, "y"), ("z (m)", 2, "z")].map(|(axis, i, quantity)| {
        let series = body_series(runs, quantity, |r, b| at(r, b).map_or(f64::NAN, |s| s.position[i]));
        (axis, series, legend.clone())
    });
    plot::panels(&dir.join("positions.svg"), &format!("{name}: positions"), "t (s)", &positions)?;
    let speeds = [
        (
            "speed (m/s)",
            body_series(runs, "speed", |r, b| at(r, b).map_or(f64::NAN, |s| norm(s.velocity))),
            legend.clone(),
        ),
        (
            "angular speed (rad/s)",
            body_series(runs, "angular speed", |r, b| at(r, b).map_or(f64::NAN, |s| norm(s.angular))),
            legend.clone(),
        ),
    ];
    plot::panels(&dir.join("velocities.svg"), &format!("{name}: speeds"), "t (s)", &speeds)?;
    let bodies = runs.first().map_or(0, |r| r.last.spatial.len());
    let mut path = Vec::new();
    for (k, run) in runs.iter().enumerate() {
        for body in 0..bodies {
            path.push(Series {
                label: format!("{} ({})", body_name(run.scene, body), run.label),
                points: run
                    .rows
                    .iter()
                    .filter_map(|r| at(r, body))
                    .map(|s| (s.position[0], s.position[1]))
                    .collect(),
                dashed: k > 0,
            });
        }
    }
    plot::lines(
        &dir.join("path.svg"),
        &format!("{name}: path from above"),
        ("x (m)", "y (m)"),
        &path,
        false,
        &legend,
    )
}
