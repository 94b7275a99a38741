//! The scenes and their parameter flags, as the page names them: the catalogue
//! (`catalogue/src/lib.rs`), which `host-sim`'s command line is generated from too, so that
//! a page URL `?scene=meter-stick&speed=0.1&x1=-0.35` and `host-sim scene --speed 0.1 --x1 -0.35`
//! describe the same run.

pub use meterstick_catalogue::{Catalogued, FLAGS, Flag, flag_index, flag_of};
pub use meterstick_core::scene::SceneKind;
