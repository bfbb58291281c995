//! Questions asked of a mesh: inside or outside (winding numbers), the closest point, points
//! spread over its surface.

mod closest;
mod sample;
mod winding;

pub use sample::sample_surface;
pub use winding::{WindingTree, winding_numbers, winding_numbers_exact};
