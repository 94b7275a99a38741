//! The scenes and their parameter flags, as the page names them: the core's catalogue
//! (`core/src/scene/catalogue.rs`), which `host-sim`'s command line is generated from too, so that
//! a page URL `?scene=meter-stick&speed=0.1&x1=-0.35` and `host-sim scene --speed 0.1 --x1 -0.35`
//! describe the same run.

pub use meterstick_core::scene::catalogue::{FLAGS, Flag, SceneKind, flag_index, flag_of};
