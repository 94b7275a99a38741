//! The multibody scenes of docs/scenes.md ("block-on-block", "tablecloth", "stack") and the disc
//! on a pulled board (docs/formulation.md, "The rim-on-face contact"): parameters with their
//! defaults and validity rules, start states, loads, outcome rules and measurements (the loop that
//! runs them: `runs.rs`).

use super::geometry::{Body, Lower, Pair, Table};
use super::system::System;
use crate::scenes::{finite, kinetic_at_most_static, non_negative, positive};

/// A block on a block on a floor, the bottom one pulled (docs/scenes.md, "block-on-block").
/// Body 0 the bottom block, body 1 the top one; pair 0 (bottom, floor), pair 1 (top, bottom).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlockOnBlock {
    /// Top block's mass `m`, kg.
    pub top_mass: f64,
    /// Top block's width `w`, m.
    pub top_width: f64,
    /// Top block's height `h`, m.
    pub top_height: f64,
    /// Bottom block's mass `M`, kg.
    pub bottom_mass: f64,
    /// Bottom block's width `w2`, m.
    pub bottom_width: f64,
    /// Bottom block's height `h2`, m.
    pub bottom_height: f64,
    /// Horizontal force `F` on the bottom block at its centre of mass, along `+x`, N.
    pub force: f64,
    /// `mu_s` between the blocks.
    pub mu_static: f64,
    /// `mu_k` between the blocks.
    pub mu_kinetic: f64,
    /// The floor's coefficient (static = kinetic) under the bottom block.
    pub mu_floor: f64,
    /// `g`, m/s^2.
    pub gravity: f64,
    /// `h`, s.
    pub step: f64,
    /// Slip speed at or below which a touching contact sticks, m/s.
    pub stick_speed: f64,
    /// Largest `|theta|` of the top block before it counts as tipped, rad.
    pub tilt_limit: f64,
    /// The activity rule's margin (docs/formulation.md, "Several bodies"), m.
    pub contact_margin: f64,
    /// Time limit, s.
    pub max_time: f64,
}

impl Default for BlockOnBlock {
    fn default() -> Self {
        Self {
            top_mass: 1.0,
            top_width: 0.1,
            top_height: 0.1,
            bottom_mass: 2.0,
            bottom_width: 0.4,
            bottom_height: 0.1,
            force: 30.0,
            mu_static: 0.5,
            mu_kinetic: 0.4,
            mu_floor: 0.2,
            gravity: 9.81,
            step: 1e-3,
            stick_speed: 1e-5,
            tilt_limit: 0.2,
            contact_margin: 1e-3,
            max_time: 0.3,
        }
    }
}

/// A board pulled from under a block (docs/scenes.md, "tablecloth"). Body 0 the board, body 1
/// the block; pair 0 (board, table), pair 1 (block, board), pair 2 (block, table).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tablecloth {
    /// Board's mass `m_b`, kg.
    pub board_mass: f64,
    /// Board's length, m.
    pub board_length: f64,
    /// Board's thickness, m.
    pub board_thickness: f64,
    /// Block's mass `m`, kg.
    pub block_mass: f64,
    /// Block's width `w`, m.
    pub block_width: f64,
    /// Block's height `h`, m.
    pub block_height: f64,
    /// Distance from the board's trailing (left) end to the block's rear (left) face, m.
    pub offset: f64,
    /// Horizontal force `F` on the board at its centre of mass, along `+x`, N.
    pub force: f64,
    /// `mu_s` block on board.
    pub mu_static: f64,
    /// `mu_k` block on board.
    pub mu_kinetic: f64,
    /// Table's coefficient (static = kinetic) under the board and the block.
    pub mu_floor: f64,
    /// `g`, m/s^2.
    pub gravity: f64,
    /// `h`, s.
    pub step: f64,
    /// Slip speed at or below which a touching contact sticks (and a body counts as at rest), m/s.
    pub stick_speed: f64,
    /// The activity rule's margin, m.
    pub contact_margin: f64,
    /// Time limit, s.
    pub max_time: f64,
}

impl Default for Tablecloth {
    fn default() -> Self {
        Self {
            board_mass: 0.2,
            board_length: 1.0,
            board_thickness: 0.005,
            block_mass: 0.5,
            block_width: 0.05,
            block_height: 0.05,
            offset: 0.1,
            force: 20.0,
            mu_static: 0.5,
            mu_kinetic: 0.4,
            mu_floor: 0.3,
            gravity: 9.81,
            step: 1e-3,
            stick_speed: 1e-5,
            contact_margin: 1e-3,
            max_time: 1.0,
        }
    }
}

/// Identical blocks stacked over a table's edge with harmonic overhangs (docs/scenes.md,
/// "stack"). Body 0 the bottom block; pair 0 (block 0, table), pair `i` (block `i`, block `i-1`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stack {
    /// Number of blocks, 1 to 5.
    pub blocks: usize,
    /// Each block's length `L`, m.
    pub length: f64,
    /// Each block's height, m.
    pub height: f64,
    /// Each block's mass, kg.
    pub mass: f64,
    /// Every contact's static coefficient `mu_s`.
    pub mu_static: f64,
    /// Every contact's kinetic coefficient `mu_k` (at most `mu_s`).
    pub mu_kinetic: f64,
    /// The harmonic overhangs' scale (1: each block's and its load's centre of mass exactly over
    /// the edge below it).
    pub overhang: f64,
    /// `g`, m/s^2.
    pub gravity: f64,
    /// `h`, s.
    pub step: f64,
    /// Slip speed at or below which a touching contact sticks, m/s.
    pub stick_speed: f64,
    /// Largest `|theta|` of a block before the stack counts as fallen, rad.
    pub tilt_limit: f64,
    /// Largest drop of a block's centre of mass before the stack counts as fallen, m.
    pub drop_limit: f64,
    /// The activity rule's margin, m.
    pub contact_margin: f64,
    /// Time limit, s.
    pub max_time: f64,
}

impl Default for Stack {
    fn default() -> Self {
        Self {
            blocks: 3,
            length: 0.2,
            height: 0.05,
            mass: 1.0,
            mu_static: 0.5,
            mu_kinetic: 0.5,
            overhang: 0.98,
            gravity: 9.81,
            step: 1e-3,
            stick_speed: 1e-5,
            tilt_limit: 0.1,
            drop_limit: 0.01,
            contact_margin: 1e-3,
            max_time: 10.0,
        }
    }
}

/// A disc resting on a board pulled along a floor (docs/formulation.md, "The rim-on-face
/// contact", its law). Body 0 the board, body 1 the disc; pair 0 (board, floor), pair 1 (disc,
/// board).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DiscOnBoard {
    /// Board's mass `M`, kg.
    pub board_mass: f64,
    /// Board's length, m.
    pub board_length: f64,
    /// Board's height, m.
    pub board_height: f64,
    /// Disc's mass `m`, kg.
    pub disc_mass: f64,
    /// Disc's radius `r`, m.
    pub disc_radius: f64,
    /// The disc's start along `x` from the board's centre, m.
    pub offset: f64,
    /// Horizontal force `F` on the board at its centre of mass, along `+x`, N.
    pub force: f64,
    /// `mu_s` disc on board.
    pub mu_static: f64,
    /// `mu_k` disc on board.
    pub mu_kinetic: f64,
    /// The floor's coefficient (static = kinetic) under the board.
    pub mu_floor: f64,
    /// `g`, m/s^2.
    pub gravity: f64,
    /// `h`, s.
    pub step: f64,
    /// Slip speed at or below which a touching contact sticks, m/s.
    pub stick_speed: f64,
    /// The activity rule's margin, m.
    pub contact_margin: f64,
    /// Time limit, s.
    pub max_time: f64,
}

impl Default for DiscOnBoard {
    fn default() -> Self {
        Self {
            board_mass: 2.0,
            board_length: 1.0,
            board_height: 0.02,
            disc_mass: 1.0,
            disc_radius: 0.05,
            offset: 0.0,
            force: 20.0,
            mu_static: 0.5,
            mu_kinetic: 0.4,
            mu_floor: 0.1,
            gravity: 9.81,
            step: 1e-3,
            stick_speed: 1e-5,
            contact_margin: 1e-3,
            max_time: 0.3,
        }
    }
}

/// The common validity rules: finite, `h <= max_time`, each box's inertia finite and positive.
fn common(step: f64, max_time: f64, boxes: &[(&str, f64, f64, f64)]) -> Result<(), String> {
    if step > max_time {
        return Err(format!("step {step} is longer than max_time {max_time}"));
    }
    for &(name, w, h, m) in boxes {
        let b = Body::block(w, h, m);
        if !(b.inertia.is_finite() && b.inertia > 0.0 && (m / b.inertia).is_finite()) {
            return Err(format!(
                "{name}: its inertia m (w^2 + h^2) / 12 = {} is not finite and positive",
                b.inertia
            ));
        }
    }
    Ok(())
}

impl BlockOnBlock {
    /// Checks the validity rules of docs/scenes.md ("block-on-block", "Validity").
    ///
    /// # Errors
    /// The first rule broken, naming its parameter.
    pub fn validate(&self) -> Result<(), String> {
        finite(&[
            ("top_mass", self.top_mass),
            ("top_width", self.top_width),
            ("top_height", self.top_height),
            ("bottom_mass", self.bottom_mass),
            ("bottom_width", self.bottom_width),
            ("bottom_height", self.bottom_height),
            ("force", self.force),
            ("mu_static", self.mu_static),
            ("mu_kinetic", self.mu_kinetic),
            ("mu_floor", self.mu_floor),
            ("gravity", self.gravity),
            ("step", self.step),
            ("stick_speed", self.stick_speed),
            ("tilt_limit", self.tilt_limit),
            ("contact_margin", self.contact_margin),
            ("max_time", self.max_time),
        ])?;
        positive(&[
            ("top_mass", self.top_mass),
            ("top_width", self.top_width),
            ("top_height", self.top_height),
            ("bottom_mass", self.bottom_mass),
            ("bottom_width", self.bottom_width),
            ("bottom_height", self.bottom_height),
            ("step", self.step),
            ("tilt_limit", self.tilt_limit),
            ("max_time", self.max_time),
        ])?;
        non_negative(&[
            ("force", self.force),
            ("mu_static", self.mu_static),
            ("mu_kinetic", self.mu_kinetic),
            ("mu_floor", self.mu_floor),
            ("gravity", self.gravity),
            ("stick_speed", self.stick_speed),
            ("contact_margin", self.contact_margin),
        ])?;
        kinetic_at_most_static(self.mu_static, self.mu_kinetic)?;
        if self.top_width > self.bottom_width {
            return Err(format!(
                "top_width {} is wider than bottom_width {}: the top block must fit on the bottom one",
                self.top_width, self.bottom_width
            ));
        }
        common(
            self.step,
            self.max_time,
            &[
                ("top block", self.top_width, self.top_height, self.top_mass),
                ("bottom block", self.bottom_width, self.bottom_height, self.bottom_mass),
            ],
        )
    }

    /// The start: both blocks level and at rest, the bottom one's centre at `(0, h2/2)`, the top
    /// one's centred over it.
    pub(super) fn start(&self) -> Vec<[f64; 3]> {
        vec![[0.0, self.bottom_height / 2.0, 0.0], [0.0, self.bottom_height + self.top_height / 2.0, 0.0]]
    }

    /// The scene's bodies, pairs and loads.
    pub(super) fn system(&self) -> System {
        System {
            bodies: vec![
                Body::block(self.bottom_width, self.bottom_height, self.bottom_mass),
                Body::block(self.top_width, self.top_height, self.top_mass),
            ],
            table: Table { lo: f64::NEG_INFINITY, hi: f64::INFINITY },
            pairs: vec![
                Pair { upper: 0, lower: Lower::Table, mu_static: self.mu_floor, mu_kinetic: self.mu_floor },
                Pair {
                    upper: 1,
                    lower: Lower::Body(0),
                    mu_static: self.mu_static,
                    mu_kinetic: self.mu_kinetic,
                },
            ],
            forces: vec![[self.force, 0.0], [0.0, 0.0]],
            gravity: self.gravity,
            step: self.step,
            stick_speed: self.stick_speed,
            margin: self.contact_margin,
        }
    }
}

impl Tablecloth {
    /// Checks the validity rules of docs/scenes.md ("tablecloth", "Validity").
    ///
    /// # Errors
    /// The first rule broken, naming its parameter.
    pub fn validate(&self) -> Result<(), String> {
        finite(&[
            ("board_mass", self.board_mass),
            ("board_length", self.board_length),
            ("board_thickness", self.board_thickness),
            ("block_mass", self.block_mass),
            ("block_width", self.block_width),
            ("block_height", self.block_height),
            ("offset", self.offset),
            ("force", self.force),
            ("mu_static", self.mu_static),
            ("mu_kinetic", self.mu_kinetic),
            ("mu_floor", self.mu_floor),
            ("gravity", self.gravity),
            ("step", self.step),
            ("stick_speed", self.stick_speed),
            ("contact_margin", self.contact_margin),
            ("max_time", self.max_time),
        ])?;
        positive(&[
            ("board_mass", self.board_mass),
            ("board_length", self.board_length),
            ("board_thickness", self.board_thickness),
            ("block_mass", self.block_mass),
            ("block_width", self.block_width),
            ("block_height", self.block_height),
            ("step", self.step),
            ("max_time", self.max_time),
        ])?;
        non_negative(&[
            ("offset", self.offset),
            ("force", self.force),
            ("mu_static", self.mu_static),
            ("mu_kinetic", self.mu_kinetic),
            ("mu_floor", self.mu_floor),
            ("gravity", self.gravity),
            ("stick_speed", self.stick_speed),
            ("contact_margin", self.contact_margin),
        ])?;
        kinetic_at_most_static(self.mu_static, self.mu_kinetic)?;
        if self.offset + self.block_width > self.board_length {
            return Err(format!(
                "offset {} + block_width {} is beyond board_length {}: the block must start on the board",
                self.offset, self.block_width, self.board_length
            ));
        }
        if self.contact_margin >= self.board_thickness {
            return Err(format!(
                "contact_margin {} is not below board_thickness {}: the block would touch the table through the board",
                self.contact_margin, self.board_thickness
            ));
        }
        common(
            self.step,
            self.max_time,
            &[
                ("board", self.board_length, self.board_thickness, self.board_mass),
                ("block", self.block_width, self.block_height, self.block_mass),
            ],
        )
    }

    /// The start: the board's centre at `(0, t_b/2)`, the block's rear face `offset` from the
    /// board's left end, both level and at rest.
    pub(super) fn start(&self) -> Vec<[f64; 3]> {
        let block_x = -self.board_length / 2.0 + self.offset + self.block_width / 2.0;
        vec![
            [0.0, self.board_thickness / 2.0, 0.0],
            [block_x, self.board_thickness + self.block_height / 2.0, 0.0],
        ]
    }

    /// The scene's bodies, pairs and loads.
    pub(super) fn system(&self) -> System {
        System {
            bodies: vec![
                Body::block(self.board_length, self.board_thickness, self.board_mass),
                Body::block(self.block_width, self.block_height, self.block_mass),
            ],
            table: Table { lo: f64::NEG_INFINITY, hi: f64::INFINITY },
            pairs: vec![
                Pair { upper: 0, lower: Lower::Table, mu_static: self.mu_floor, mu_kinetic: self.mu_floor },
                Pair {
                    upper: 1,
                    lower: Lower::Body(0),
                    mu_static: self.mu_static,
                    mu_kinetic: self.mu_kinetic,
                },
                Pair { upper: 1, lower: Lower::Table, mu_static: self.mu_floor, mu_kinetic: self.mu_floor },
            ],
            forces: vec![[self.force, 0.0], [0.0, 0.0]],
            gravity: self.gravity,
            step: self.step,
            stick_speed: self.stick_speed,
            margin: self.contact_margin,
        }
    }
}

impl Stack {
    /// Checks the validity rules of docs/scenes.md ("stack", "Validity").
    ///
    /// # Errors
    /// The first rule broken, naming its parameter.
    pub fn validate(&self) -> Result<(), String> {
        finite(&[
            ("length", self.length),
            ("height", self.height),
            ("mass", self.mass),
            ("mu_static", self.mu_static),
            ("mu_kinetic", self.mu_kinetic),
            ("overhang", self.overhang),
            ("gravity", self.gravity),
            ("step", self.step),
            ("stick_speed", self.stick_speed),
            ("tilt_limit", self.tilt_limit),
            ("drop_limit", self.drop_limit),
            ("contact_margin", self.contact_margin),
            ("max_time", self.max_time),
        ])?;
        positive(&[
            ("length", self.length),
            ("height", self.height),
            ("mass", self.mass),
            ("step", self.step),
            ("tilt_limit", self.tilt_limit),
            ("drop_limit", self.drop_limit),
            ("max_time", self.max_time),
        ])?;
        non_negative(&[
            ("mu_static", self.mu_static),
            ("mu_kinetic", self.mu_kinetic),
            ("overhang", self.overhang),
            ("gravity", self.gravity),
            ("stick_speed", self.stick_speed),
            ("contact_margin", self.contact_margin),
        ])?;
        kinetic_at_most_static(self.mu_static, self.mu_kinetic)?;
        if !(1..=5).contains(&self.blocks) {
            return Err(format!("blocks {} is outside 1..=5", self.blocks));
        }
        // The bottom block must reach back over the table: its left end left of the edge.
        if self.overhang / (2.0 * self.blocks as f64) >= 1.0 {
            return Err(format!(
                "overhang {}: the bottom block would start beyond the table's edge",
                self.overhang
            ));
        }
        common(self.step, self.max_time, &[("block", self.length, self.height, self.mass)])
    }

    /// Each block's start `x` (bottom first): block `k` from the top (`k = 1..n`) reaches
    /// `overhang L / (2 k)` beyond the right end of the one below it, the bottom one beyond the
    /// table's edge at `x = 0`.
    #[must_use]
    pub fn start_x(&self) -> Vec<f64> {
        let n = self.blocks;
        let mut right = 0.0;
        let mut xs = Vec::with_capacity(n);
        for i in 0..n {
            let k = n - i;
            right += self.overhang * self.length / (2.0 * k as f64);
            xs.push(right - self.length / 2.0);
        }
        xs
    }

    /// The start: block `i` (bottom first) at `(start_x[i], (i + 1/2) height)`, level, at rest.
    pub(super) fn start(&self) -> Vec<[f64; 3]> {
        self.start_x()
            .into_iter()
            .enumerate()
            .map(|(i, x)| [x, (i as f64 + 0.5) * self.height, 0.0])
            .collect()
    }

    /// The scene's bodies, pairs and loads.
    pub(super) fn system(&self) -> System {
        let (mu_static, mu_kinetic) = (self.mu_static, self.mu_kinetic);
        let mut pairs = vec![Pair { upper: 0, lower: Lower::Table, mu_static, mu_kinetic }];
        pairs.extend((1..self.blocks).map(|i| Pair {
            upper: i,
            lower: Lower::Body(i - 1),
            mu_static,
            mu_kinetic,
        }));
        System {
            bodies: vec![Body::block(self.length, self.height, self.mass); self.blocks],
            table: Table { lo: f64::NEG_INFINITY, hi: 0.0 },
            pairs,
            forces: vec![[0.0; 2]; self.blocks],
            gravity: self.gravity,
            step: self.step,
            stick_speed: self.stick_speed,
            margin: self.contact_margin,
        }
    }
}

impl DiscOnBoard {
    /// The bodies' names, in body order (the validity messages' words).
    const NAMES: [&'static str; 2] = ["board", "disc"];

    /// Checks the validity rules: every parameter finite; masses, sizes, `step`, `max_time`
    /// positive; `force`, the coefficients, `gravity`, `stick_speed`, `contact_margin`
    /// non-negative; `mu_k <= mu_s`; the disc over the board (`|offset| <= board_length / 2`);
    /// `step <= max_time`; both inertias finite and positive; the disc resting on the board, never
    /// under it.
    ///
    /// # Errors
    /// The first rule broken, naming its parameter.
    pub fn validate(&self) -> Result<(), String> {
        finite(&[
            ("board_mass", self.board_mass),
            ("board_length", self.board_length),
            ("board_height", self.board_height),
            ("disc_mass", self.disc_mass),
            ("disc_radius", self.disc_radius),
            ("offset", self.offset),
            ("force", self.force),
            ("mu_static", self.mu_static),
            ("mu_kinetic", self.mu_kinetic),
            ("mu_floor", self.mu_floor),
            ("gravity", self.gravity),
            ("step", self.step),
            ("stick_speed", self.stick_speed),
            ("contact_margin", self.contact_margin),
            ("max_time", self.max_time),
        ])?;
        positive(&[
            ("board_mass", self.board_mass),
            ("board_length", self.board_length),
            ("board_height", self.board_height),
            ("disc_mass", self.disc_mass),
            ("disc_radius", self.disc_radius),
            ("step", self.step),
            ("max_time", self.max_time),
        ])?;
        non_negative(&[
            ("force", self.force),
            ("mu_static", self.mu_static),
            ("mu_kinetic", self.mu_kinetic),
            ("mu_floor", self.mu_floor),
            ("gravity", self.gravity),
            ("stick_speed", self.stick_speed),
            ("contact_margin", self.contact_margin),
        ])?;
        kinetic_at_most_static(self.mu_static, self.mu_kinetic)?;
        if self.offset.abs() > self.board_length / 2.0 {
            return Err(format!(
                "offset {} is beyond half the board_length {}: the disc must start over the board",
                self.offset, self.board_length
            ));
        }
        common(
            self.step,
            self.max_time,
            &[("board", self.board_length, self.board_height, self.board_mass)],
        )?;
        let disc = Body::disc(self.disc_radius, self.disc_mass);
        if !(disc.inertia.is_finite() && disc.inertia > 0.0 && (self.disc_mass / disc.inertia).is_finite()) {
            return Err(format!(
                "disc_radius {}: the disc's inertia m r^2 / 2 = {} is not finite and positive",
                self.disc_radius, disc.inertia
            ));
        }
        self.system().check_pairs(&Self::NAMES)
    }

    /// The start: the board's centre at `(0, board_height / 2)`, the disc's at
    /// `(offset, board_height + r)` resting on its top face, both at rest.
    pub(super) fn start(&self) -> Vec<[f64; 3]> {
        vec![[0.0, self.board_height / 2.0, 0.0], [self.offset, self.board_height + self.disc_radius, 0.0]]
    }

    /// The scene's bodies, pairs and loads: a floor without ends.
    pub(super) fn system(&self) -> System {
        System {
            bodies: vec![
                Body::block(self.board_length, self.board_height, self.board_mass),
                Body::disc(self.disc_radius, self.disc_mass),
            ],
            table: Table { lo: f64::NEG_INFINITY, hi: f64::INFINITY },
            pairs: vec![
                Pair { upper: 0, lower: Lower::Table, mu_static: self.mu_floor, mu_kinetic: self.mu_floor },
                Pair {
                    upper: 1,
                    lower: Lower::Body(0),
                    mu_static: self.mu_static,
                    mu_kinetic: self.mu_kinetic,
                },
            ],
            forces: vec![[self.force, 0.0], [0.0, 0.0]],
            gravity: self.gravity,
            step: self.step,
            stick_speed: self.stick_speed,
            margin: self.contact_margin,
        }
    }
}
