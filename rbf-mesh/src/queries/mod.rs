//! Questions asked of a mesh: inside or outside (winding numbers, also of oriented points), the
//! closest point, points spread over its surface.

mod closest;
mod clusters;
mod dipoles;
mod sample;
mod winding;

pub use closest::closest_on_triangle;
pub use dipoles::{DipoleTree, dipole_winding_numbers};
pub use sample::sample_surface;
pub use winding::{WindingTree, winding_numbers, winding_numbers_exact};
