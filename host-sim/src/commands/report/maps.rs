//! The report's success map: the meter stick's outcome over finger speed x `mu_k/mu_s`
//! (`mu_s = 0.6`) on one grid in three implementations, compared cell by cell.

use std::fmt::Write as _;
use std::path::Path;

use meterstick_core::scene::MeterStickParams;

use crate::map::{self, Grid, Map};
use crate::scenes::{Implementation, SceneParams};

/// The implementations of the success map: the core f32 6x6 (the firmware's, drawn), the core
/// f64 8x8 and the reference.
pub const MAP_CONFIGS: [Implementation; 3] =
    [Implementation::CORE_F32_REDUCED, Implementation::CORE_F64_FULL, Implementation::Reference];

/// One grid, the map of each of [`MAP_CONFIGS`].
#[derive(Debug, Clone)]
pub struct SuccessMaps {
    /// The grid.
    pub grid: Grid,
    /// The maps, in the order of [`MAP_CONFIGS`].
    pub maps: [Map; 3],
}

/// Where the three maps disagree.
#[derive(Debug, Clone, Default)]
pub struct Comparison {
    /// The cells whose outcomes differ, described.
    pub disagreements: Vec<String>,
    /// Of those, cells with a neighbour (left, right, above, below) of another outcome in f64.
    pub at_boundary: usize,
}

impl SuccessMaps {
    /// Computes the three maps: 48 x 16 cells over 0.05 .. 1.25 m/s (2 x 2 when `quick`).
    ///
    /// # Errors
    /// A cell that cannot run.
    pub fn compute(quick: bool) -> anyhow::Result<Self> {
        let cells = if quick { [2, 2] } else { [48, 16] };
        let grid = Grid::speed_by_mu_ratio((0.05, 1.25), cells, 0.0)?;
        let base = SceneParams::MeterStick(MeterStickParams { mu_static: 0.6, ..MeterStickParams::paper() });
        let [f32_map, f64_map, ref_map] = MAP_CONFIGS.map(|c| map::compute(&base, &grid, c));
        Ok(Self { grid, maps: [f32_map?, f64_map?, ref_map?] })
    }

    /// Cells of the grid.
    #[must_use]
    pub fn cells(&self) -> usize {
        self.maps[0].xs.len() * self.maps[0].ys.len()
    }

    /// Writes the f32 map's files in `out/map/` and `out/success_map.csv` (every cell in the
    /// three), and returns where they disagree.
    ///
    /// # Errors
    /// I/O or plotting.
    pub fn write(&self, out: &Path) -> anyhow::Result<Comparison> {
        let maps = &self.maps;
        map::write(&maps[0], &out.join("map"))?;
        let mut map_csv = String::from("speed_m_s,mu_k_over_mu_s");
        for c in MAP_CONFIGS {
            let _ = write!(map_csv, ",{}", c.to_string().replace(' ', "_"));
        }
        map_csv += "\n";
        let mut cmp = Comparison::default();
        let (xs, ys) = (&maps[0].xs, &maps[0].ys);
        let f64_outcomes = &maps[1].outcomes;
        for (j, y) in ys.iter().enumerate() {
            for (i, x) in xs.iter().enumerate() {
                let o = maps.each_ref().map(|m| m.outcomes[j][i]);
                writeln!(map_csv, "{x},{y},{},{},{}", o[0], o[1], o[2])?;
                if o[0] != o[1] || o[1] != o[2] {
                    cmp.disagreements
                        .push(format!("v = {x:.4} m/s, mu_k/mu_s = {y:.3}: {} / {} / {}", o[0], o[1], o[2]));
                    let neighbours = [(j, i.wrapping_sub(1)), (j, i + 1), (j.wrapping_sub(1), i), (j + 1, i)];
                    cmp.at_boundary += usize::from(neighbours.iter().any(|&(b, a)| {
                        f64_outcomes.get(b).and_then(|row| row.get(a)).is_some_and(|&n| n != o[1])
                    }));
                }
            }
        }
        std::fs::write(out.join("success_map.csv"), &map_csv)?;
        Ok(cmp)
    }
}
