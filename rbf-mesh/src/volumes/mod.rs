//! Volumes: voxel grids of a mesh's inside (the voxelizer of Yngve & Turk 2002, §4.1) and
//! their signed distances (§4.2).

mod distance;
mod volume;
mod voxelize;

pub use distance::{signed_distance, squared_distance_transform};
pub use volume::{Volume, classify_blocks, has_other_neighbour};
pub use voxelize::{MAX_SUPERSAMPLING, VoxelMethod, VoxelSettings, check_volume_size, voxelize};
