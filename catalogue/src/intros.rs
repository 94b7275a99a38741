//! [`Introduction`] and [`INTRODUCTIONS`]: each scene's heading and introduction for a class.

use meterstick_core::scene::SceneKind;

/// A scene's heading and one-paragraph introduction, for a teacher: what the scene shows and what
/// to look for. Kept apart from [`SceneInfo`](crate::SceneInfo) so that a front end that does not show them (the
/// page's wasm modules, which are within a size budget) does not link their text: the page reads
/// them from `pkg/intros.json`, which `web/examples/intros.rs` writes from [`INTRODUCTIONS`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Introduction {
    /// The scene.
    pub kind: SceneKind,
    /// Its heading.
    pub heading: &'static str,
    /// One paragraph: what it shows, what to look for.
    pub intro: &'static str,
}

/// Every scene's [`Introduction`], in the order of [`SCENES`](crate::SCENES).
pub const INTRODUCTIONS: [Introduction; SceneKind::ALL.len()] = [
    Introduction {
        kind: SceneKind::MeterStick,
        heading: "The meter-stick trick",
        intro: "Rest a meter stick on two fingers and slide one finger toward the other: the stick never \
                falls, the fingers meet under its centre of mass. The finger farther from the centre of \
                mass carries less weight, so its friction limit is lower and it slides while the other \
                sticks; as it comes closer its load grows until the sticking finger's friction gives way \
                and the roles swap. Look for the switches marked under the plots: at each stick-to-slip \
                switch the ratio x_stop/x_start is close to mu_k/mu_s (the paper's eq. 21). Moved fast, \
                the stick no longer follows the quasi-static story: it tips and falls.",
    },
    Introduction {
        kind: SceneKind::Incline,
        heading: "A block on an inclined plane",
        intro: "A block is set down at rest on a slope. It stays where it is while tan(angle) <= mu_s; on \
                a steeper slope it slides, accelerating at g (sin a - mu_k cos a) whatever its mass. A \
                block taller than it is wide tips over its lower corner instead once tan(angle) exceeds \
                width/height, before friction gives way. Look for the normal force moving to the lower \
                corner as the slope steepens, and compare the measured acceleration with the formula.",
    },
    Introduction {
        kind: SceneKind::Ladder,
        heading: "A ladder sliding down a wall",
        intro: "A rod leans against a wall with its foot on the floor. Friction at the foot must supply \
                the horizontal push that keeps the foot in place; at a steep angle little is needed and \
                the ladder stands, at a shallow one it slides: the foot moves out, the top slides down \
                the wall. Without friction the top leaves the wall when it has come down to 2/3 of its \
                starting height, and the rod falls free. Look for the moment the top leaves the wall \
                (the wall contact turns hollow) and the measured release height.",
    },
    Introduction {
        kind: SceneKind::ThreeFingers,
        heading: "A rod on three fingers",
        intro: "The meter-stick trick with a third finger. A rod on three supports is statically \
                indeterminate: the rigid-body equations of balance do not say how its weight is shared \
                among them. Finger 1 moves toward finger 2 while finger 3 stays: the contact solver \
                chooses at each step which fingers stick, which slide and which lose contact. Look for \
                the normal-force arrows: the weight shifts between the fingers as finger 1 moves, and \
                a finger that carries nothing lets go.",
    },
    Introduction {
        kind: SceneKind::Cylinder,
        heading: "Rolling or sliding down a slope",
        intro: "A round body is released on a slope. If friction can supply the torque, it rolls without \
                slipping and accelerates at g sin a / (1 + k), slower than a sliding block, where \
                J = k m r^2 (k = 1/2 for a solid cylinder, 1 for a ring). That needs \
                tan(angle) <= mu_s (1 + k) / k; on a steeper slope it slides while friction spins it up, \
                and its centre accelerates at g (sin a - mu_k cos a). Look for the spoke: rolling turns \
                it by exactly the distance travelled, slipping turns it less.",
    },
    Introduction {
        kind: SceneKind::Painleve,
        heading: "Painlev\u{e9}'s paradox: the jamming rod",
        intro: "A tilted rod slides with its lower end on a rough floor. For a uniform rod at angle a, \
                sliding with friction mu above (1 + 3 cos^2 a) / (3 sin a cos a) (2.5 at 30 degrees, \
                4/3 at the least) has no consistent rigid-body answer: friction would drive the end \
                into the floor. Painlev\u{e9} found this in 1895; the way out is an impulse: the end \
                stops dead (it jams) with a finite normal and friction impulse in one step. Look for the \
                jam's time and impulses; with smaller mu the end slides on.",
    },
    #[cfg(feature = "multibody")]
    Introduction {
        kind: SceneKind::BlockOnBlock,
        heading: "A block on a pulled block",
        intro: "A block rests on another block, which is pulled along the floor by a force F (the arrow). \
                A gentle pull that beats the floor's friction drags both together: friction between the \
                blocks carries the top one along at the same acceleration. The top block can only be \
                accelerated by that friction, at most mu_s g; pull harder and it slips, falling behind \
                at mu_k g while the bottom block runs ahead until the top one slides off its back. A tall \
                top block tips over instead. Look for the two measured accelerations.",
    },
    #[cfg(feature = "multibody")]
    Introduction {
        kind: SceneKind::Tablecloth,
        heading: "The tablecloth trick",
        intro: "A board (the tablecloth) is pulled out from under a block. While the board slides beneath \
                it, kinetic friction accelerates the block forward at no more than mu_k g, and only for \
                as long as the board is under it. The harder the pull, the sooner the board is gone, so \
                the less the block moves: compare 10 N with 20 N side by side. A gentle pull drags the \
                block along with the board instead. Look for the block's displacement, measured once it \
                has come to rest behind the board.",
    },
    #[cfg(feature = "multibody")]
    Introduction {
        kind: SceneKind::Stack,
        heading: "Blocks stacked over a table's edge",
        intro: "Blocks of length L are stacked over a table's edge, the k-th from the top reaching \
                s L / (2k) past the one below it: the harmonic overhangs. With s = 1 the centre of mass \
                of the blocks above each block lies exactly over that block's edge, and that of the \
                whole stack over the table's edge: the largest overhang, L/2 (1 + 1/2 + 1/3) = 11/12 L \
                for three blocks, the top block wholly beyond the table. Below overhang 1 the stack holds; past it, it \
                tips and falls. Look at 0.98 against 1.02 side by side: a few percent decide.",
    },
    #[cfg(feature = "multibody")]
    Introduction {
        kind: SceneKind::DiscOnBoard,
        heading: "A cylinder on a pulled board",
        intro: "A solid cylinder lies on a board that a force pulls along the floor (the arrow). Friction \
                at the cylinder's bottom both pushes its centre forward and spins it backward: rolling \
                without slipping on a board that accelerates at A, its centre accelerates at only A/3, \
                so it rolls back along the board. That needs friction m A/3, at most mu_s m g: pulled \
                harder (A > 3 mu_s g) it slides. Look for the spoke turning and the two measured \
                accelerations, a third of one another while it rolls.",
    },
    #[cfg(feature = "spatial")]
    Introduction {
        kind: SceneKind::Puck,
        heading: "A puck on a table or an incline",
        intro: "A puck is launched across a level table or an inclined plane. Coulomb's friction opposes \
                the puck's slip, whatever direction it has: on a level table it slides straight along \
                its heading and stops after v^2 / (2 mu g), the same distance in every direction. Across \
                an incline with mu = tan(angle), friction and the slope's pull cancel along the slope: \
                the path bends down the slope and the speed tends to exactly half the launch speed. \
                Look for the path and the final speed, and turn the heading: the distance does not \
                change (simulators that approximate the friction cone by a pyramid bend the path \
                toward their axes).",
    },
    #[cfg(feature = "spatial")]
    Introduction {
        kind: SceneKind::Billiard,
        heading: "A billiard ball struck with spin",
        intro: "A ball is struck along the table with spin. Its contact point slips, and friction against \
                the slip slows the ball and turns its spin until the slip stops: from then on it rolls. \
                The slip keeps its direction, so a ball with side spin curves on a parabola. It rolls \
                from t = 2 |u0| / (7 mu g) at v = (5 v0 + 2 R omega0 x z) / 7, whatever its mass; the \
                spin about the vertical stays, since a point of contact has no friction against it. \
                Look for the moment it starts rolling and the rolling velocity.",
    },
    #[cfg(feature = "spatial")]
    Introduction {
        kind: SceneKind::Curling,
        heading: "A curling stone that slides and spins",
        intro: "A ring or a flat disc is launched along the table, spinning. Each point of its base slips \
                its own way, and friction opposes each point's slip: spinning makes the stone slide \
                further, sliding makes it stop spinning sooner, and the two stop at the same moment. \
                Near the end the sliding speed over the rim's speed tends to a number of the shape \
                alone: 1 for a ring, 0.653 for a uniform disc (Farkas, Bartels, Unger and Wolf, 2003). \
                Look for the two stopping times and that ratio.",
    },
    #[cfg(feature = "spatial")]
    Introduction {
        kind: SceneKind::MeterStick3d,
        heading: "The meter stick in three dimensions",
        intro: "The paper's trick with a real rod: finger 1 is a pad lying across it, finger 2 a point \
                under its centre line, and finger 1 moves along a path at a heading to the rod. At \
                heading 0 it is the planar meter stick, step for step. At other headings the fingers \
                also slide across the rod, friction pulls it sideways and may turn it, and a heading \
                and its opposite give mirror-image runs. Look for where the fingers meet.",
    },
    #[cfg(feature = "stack-3d")]
    Introduction {
        kind: SceneKind::Stack3d,
        heading: "Blocks stacked over a table's edge, in three dimensions",
        intro: "The harmonic stack again, now with blocks of a width, their overhang reaching out at a                 heading to the table's edge. Each block rests on the one below on the overlap of their                 faces, touching at its corners, and the stack's balance is about the edge along the                 overhang's direction: it still holds at overhang 0.98 and falls at 1.02, whatever the                 heading. At heading 0 it moves as the planar stack. Turn the heading and compare 0.98                 with 1.02.",
    },
];
