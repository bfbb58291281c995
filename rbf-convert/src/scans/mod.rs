//! Scans to surfaces: a point cloud becomes an implicit surface (`reconstruct.rs`), with its
//! normals checked by the winding number of the other points, whole patches (`patches.rs`) and
//! point by point (`dipoles.rs`), by fits to them (`consensus.rs`) and by lines of sight
//! (`sight.rs`); its spread made finer where two sheets run close (`close_sheets.rs`); and then a mesh that
//! keeps to what the scan shows (`support.rs`).

mod close_sheets;
mod consensus;
mod dipoles;
mod patches;
mod reconstruct;
mod sight;
mod support;
mod surface;

pub use reconstruct::{
    LARGEST_COORDINATE, ReconstructReport, ReconstructSettings, mesh_resolution, reconstruct,
    smoothing_for_noise,
};
pub use support::{scan_mesh, supported_pieces, trimmed};
pub use surface::{ScanSurface, scan_surface};
