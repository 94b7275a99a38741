//! The core's stack-3d contacts (`meterstick_core::spatial::face_patch`) against the independent
//! f64 reference's (`meterstick_reference::spatial::stack_contacts`), both written from
//! docs/scenes.md, "stack-3d", "Contacts": the start stacks at overhang 0.98 and 1.02, and a few
//! hundred deterministic pseudo-random stacks (tilts up to 0.1 rad, yaws off the heading, offsets,
//! gaps about the margin, 2 and 3 blocks, headings -60 to 60 deg), among them blocks of one width
//! edge on edge and corners within round-off of the lower face's sides. Each block's contacts
//! match as sets: the same count, every point, normal and gap within 1e-12.
#![allow(clippy::unwrap_used, clippy::panic, clippy::print_stdout, clippy::float_cmp)]

use meterstick_core::spatial::{Beneath, FaceContact, FacePatch, State, face_patch};
use meterstick_reference::spatial::{Stack3d, StackBlock, StackContact, stack_contacts};

const TOL: f64 = 1e-12;

/// The most contacts a block's face can have on another's (an octagon).
const MOST: usize = 8;

fn close(a: [f64; 3], b: [f64; 3]) -> bool {
    (0..3).all(|i| (a[i] - b[i]).abs() <= TOL)
}

fn core_state(b: &StackBlock) -> State<f64> {
    State { position: b.x, orientation: b.q, velocity: b.v, angular_velocity: b.omega }
}

/// Every block's contacts by the core and by the reference, matched as sets; the contacts seen.
fn compare(p: &Stack3d, blocks: &[StackBlock], what: &str) -> usize {
    let half = [0.5 * p.length, 0.5 * p.width, 0.5 * p.height];
    let states: Vec<State<f64>> = blocks.iter().map(core_state).collect();
    let reference = stack_contacts(p, blocks);
    for (i, upper) in states.iter().enumerate() {
        let beneath = match i.checked_sub(1) {
            Some(l) => Beneath::Block { state: &states[l], half },
            None => Beneath::Table,
        };
        let core: FacePatch<f64, MOST> = face_patch(upper, &half, beneath, p.margin).unwrap();
        let theirs: Vec<&StackContact> = reference.iter().filter(|c| c.upper == i).collect();
        assert!(theirs.iter().all(|c| c.lower == i.checked_sub(1)));
        assert_eq!(core.len(), theirs.len(), "{what}, block {i}: core {core:?}\nreference {theirs:?}");
        let same = |c: &FaceContact<f64>, r: &StackContact| {
            close(c.point, r.point) && close(c.normal, r.normal) && (c.gap - r.gap).abs() <= TOL
        };
        for c in &core {
            let n = theirs.iter().filter(|r| same(c, r)).count();
            assert_eq!(n, 1, "{what}, block {i}: core's {c:?} matches {n} of the reference's {theirs:?}");
        }
    }
    reference.len()
}

/// The start (docs/scenes.md, "stack-3d", "Start"): level, the `k`-th block from the top centred
/// at `R_k - L/2` along `d`, `R_k = s (L/2) (1/k + ... + 1/n)`. Each face rests flat (gap 0,
/// normal `z`) on its overlap with the face below. On a block, the overlap is `-L/2 <= u <= L/2 -
/// o`, `|v| <= W/2` in the block's own `u` along `d` and `v` along `e` (`o` its offset over the
/// block below): its four vertices are among the contacts, the rest (where round-off puts one
/// equal side a hair past the other) on its sides. On the table, the face's corners with `x < 0`
/// are among the contacts, every contact has `x <= 0`, and those on no side of the face are on
/// the edge `x = 0`.
#[test]
fn the_start_stacks_contacts_are_the_references() {
    let mut seen = 0;
    for blocks in 2..=5 {
        for overhang in [0.98, 1.02] {
            for heading_deg in [-60.0f64, -45.0, -10.0, 0.0, 15.0, 30.0, 60.0] {
                let p = Stack3d { blocks, overhang, heading: heading_deg.to_radians(), ..Stack3d::default() };
                let what = format!("start, {blocks} blocks, s = {overhang}, {heading_deg} deg");
                let start = p.start();
                seen += compare(&p, &start, &what);
                let (l, w) = (0.5 * p.length, 0.5 * p.width);
                let (s, c) = p.heading.sin_cos();
                let contacts = stack_contacts(&p, &start);
                let centre_along =
                    |i: usize| (blocks - i..=blocks).map(|j| 1.0 / j as f64).sum::<f64>() * overhang * l - l;
                for i in 0..blocks {
                    let here = centre_along(i);
                    let z = i as f64 * p.height;
                    let world = |u: f64, v: f64| [(here + u) * c - v * s, (here + u) * s + v * c, z];
                    let own = |k: &StackContact| {
                        let (dx, dy) = (k.point[0] - here * c, k.point[1] - here * s);
                        (dx * c + dy * s, -dx * s + dy * c)
                    };
                    let mine: Vec<&StackContact> = contacts.iter().filter(|k| k.upper == i).collect();
                    assert!(mine.len() >= 4, "{what}, block {i}: {mine:?}");
                    for k in &mine {
                        assert!(
                            k.gap.abs() <= 1e-15
                                && close(k.normal, [0.0, 0.0, 1.0])
                                && (k.point[2] - z).abs() <= 1e-15,
                            "{what}: {k:?}"
                        );
                    }
                    let (hi, corners) = if i == 0 {
                        (
                            l,
                            [(-l, -w), (l, -w), (l, w), (-l, w)]
                                .into_iter()
                                .filter(|&(u, v)| world(u, v)[0] < 0.0)
                                .collect(),
                        )
                    } else {
                        let hi = l - (here - centre_along(i - 1));
                        (hi, vec![(-l, -w), (hi, -w), (hi, w), (-l, w)])
                    };
                    for k in &mine {
                        let (u, v) = own(k);
                        let edge = i == 0 && k.point[0].abs() <= TOL;
                        let on_side =
                            (u + l).abs() <= TOL || (u - hi).abs() <= TOL || (v.abs() - w).abs() <= TOL;
                        let inside = (-l - TOL..=hi + TOL).contains(&u)
                            && v.abs() <= w + TOL
                            && (i > 0 || k.point[0] <= TOL);
                        assert!((on_side || edge) && inside, "{what}, block {i}: {k:?} at ({u}, {v})");
                    }
                    for (u, v) in corners {
                        let vertex = world(u, v);
                        assert!(
                            mine.iter().any(|k| close(k.point, vertex)),
                            "{what}, block {i}: no {vertex:?}"
                        );
                    }
                }
            }
        }
    }
    println!("start stacks: {seen} contacts matched");
}

/// SplitMix64: a fixed sequence of pseudo-random numbers.
struct Random(u64);

impl Random {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in `[lo, hi)`.
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }

    fn pick<T: Copy>(&mut self, of: &[T]) -> T {
        of[(self.next() % of.len() as u64) as usize]
    }
}

fn about(axis: [f64; 3], angle: f64) -> [f64; 4] {
    let (s, c) = (0.5 * angle).sin_cos();
    [c, s * axis[0], s * axis[1], s * axis[2]]
}

fn mul(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

/// A block of the stack at heading `psi`: `along` and `across` its axes `d`, `e` from the
/// origin, its bottom at `bottom`; turned by `psi + yaw` about `z`, then tilted by `tilt` about
/// the horizontal axis of its own frame at `tilt_heading` (rad) from its `x`.
#[allow(clippy::too_many_arguments)]
fn block(
    p: &Stack3d,
    along: f64,
    across: f64,
    bottom: f64,
    yaw: f64,
    tilt: f64,
    tilt_heading: f64,
) -> StackBlock {
    let (s, c) = p.heading.sin_cos();
    let x = [along * c - across * s, along * s + across * c, bottom + 0.5 * p.height];
    let axis = [tilt_heading.cos(), tilt_heading.sin(), 0.0];
    let q = mul(about([0.0, 0.0, 1.0], p.heading + yaw), about(axis, tilt));
    StackBlock { x, q, v: [0.0; 3], omega: [0.0; 3] }
}

#[test]
fn random_stacks_contacts_are_the_references() {
    let mut random = Random(0x005e_ed00_03d5_7ac4);
    let (mut cases, mut seen, mut empty_faces, mut five_or_more) = (0, 0, 0, 0);
    for case in 0..400 {
        let blocks = random.pick(&[2usize, 3]);
        let any_heading = random.uniform(-60.0, 60.0);
        let heading = random.pick(&[0.0, any_heading]).to_radians();
        let p = Stack3d { blocks, heading, ..Stack3d::default() };
        let (margin, hb) = (p.margin, p.height);
        // How a block sits on the one below: edge on edge, near the lower face's sides by
        // round-off, or anywhere.
        let kind = random.pick(&["edge on edge", "near the side", "anywhere"]);
        let mut stack = Vec::new();
        let (mut along, mut bottom, mut across) = (random.uniform(-0.12, 0.05), 0.0, 0.0);
        let (mut yaw, mut tilt, mut tilt_heading);
        for i in 0..blocks {
            let gap = random.uniform(-1.5 * margin, 1.5 * margin);
            (across, yaw, tilt, tilt_heading) = match kind {
                // One width, aligned, tilted about the block's own `y` (its sides stay over the
                // lower block's, to round-off at a heading).
                "edge on edge" => (across, 0.0, random.uniform(-0.02, 0.02), core::f64::consts::FRAC_PI_2),
                // A side within a few round-offs of the lower face's, either side of the band
                // `64 eps (L + W)` (4.3e-15 m) and clear of its edge by far more than round-off:
                // 1e-15 to 3e-15 m or 6e-15 to 1.8e-14 m either way.
                "near the side" => (
                    across
                        + random.pick(&[-1.0, 1.0]) * random.pick(&[1e-15, 6e-15]) * random.uniform(1.0, 3.0),
                    0.0,
                    random.uniform(-0.01, 0.01),
                    core::f64::consts::FRAC_PI_2,
                ),
                _ => (
                    random.uniform(-0.03, 0.03),
                    random.uniform(-0.3, 0.3),
                    {
                        let tilt = random.uniform(0.0, 0.1);
                        tilt * random.pick(&[1e-4, 0.1, 1.0])
                    },
                    random.uniform(-core::f64::consts::PI, core::f64::consts::PI),
                ),
            };
            // A tilt lowers the face's lowest corner by about `(L/2) |tilt|`: half the time
            // the block is raised by that, its lowest corner near `gap`.
            let lift = random.pick(&[0.0, 1.0]) * 0.5 * p.length * tilt.abs();
            let base = if i == 0 { 0.0 } else { bottom + hb };
            stack.push(block(&p, along, across, base + gap + lift, yaw, tilt, tilt_heading));
            bottom = base + gap + lift;
            along += random.uniform(-0.06, 0.06);
        }
        let n = compare(
            &p,
            &stack,
            &format!("case {case}: {kind}, {blocks} blocks at {:.1} deg", heading.to_degrees()),
        );
        let contacts = stack_contacts(&p, &stack);
        for i in 0..blocks {
            let on_face = contacts.iter().filter(|c| c.upper == i).count();
            empty_faces += usize::from(on_face == 0);
            five_or_more += usize::from(on_face >= 5);
        }
        seen += n;
        cases += 1;
    }
    println!(
        "{cases} random stacks: {seen} contacts matched, {empty_faces} faces without contacts, {five_or_more} with five or more"
    );
    // The draw reaches contacts, their absence, and overlaps beyond quadrilaterals.
    assert!(
        seen > 4 * cases && empty_faces > cases / 10 && five_or_more > cases / 20,
        "{seen} contacts, {empty_faces} empty faces, {five_or_more} of five or more"
    );
}
