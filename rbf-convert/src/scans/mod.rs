//! Scans to surfaces: a point cloud becomes an implicit surface (`reconstruct.rs`), with its
//! normals checked by fits to the other points (`consensus.rs`), and then a mesh that keeps to
//! what the scan shows (`support.rs`).

mod consensus;
mod reconstruct;
mod support;

pub use reconstruct::{ReconstructReport, ReconstructSettings, mesh_resolution, reconstruct};
pub use support::{scan_mesh, supported_pieces, trimmed};
