//! # rbf-mesh
//!
//! Triangle meshes for variational implicit surfaces: [`TriMesh`] with the checks a user needs
//! before trusting a mesh ([`TriMesh::check`]: holes, non-manifold edges and vertices,
//! orientation, components, genus, degenerate faces), and reading and writing OBJ, PLY and STL
//! with errors that name the file and the line or byte.
//!
//! The polygonizers follow §7.1 of Greg Turk and James F. O'Brien, "Modelling with Implicit
//! Surfaces that Interpolate", ACM Transactions on Graphics 21(4), 2002 (Turk & O'Brien 2002);
//! the voxelizer and signed distance transform are those of §4.1–§4.2 of Gary Yngve and Greg Turk,
//! "Robust Creation of Implicit Surfaces from Polygonal Meshes", IEEE Transactions on
//! Visualization and Computer Graphics 8(4), 2002 (Yngve & Turk 2002).
//!
//! ```
//! use rbf_mesh::TriMesh;
//! // A tetrahedron, faces counter-clockwise from outside.
//! let m = TriMesh::new(
//!     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
//!     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
//! )
//! .unwrap();
//! let r = m.check();
//! assert!(r.is_watertight() && r.components == 1 && r.euler_characteristic == 2);
//! assert!((m.volume() - 1.0 / 6.0).abs() < 1e-15);
//! ```

mod error;
mod files;
mod meshes;
mod polygonize;
mod queries;
mod volumes;

pub use error::{Location, MeshError};
pub use files::{
    Matrix, PointCloud, declared_cloud_size, mesh_bytes, npy_f64_bytes, read_mesh, read_mesh_bytes,
    read_npy_matrix, read_point_cloud, read_point_cloud_bytes, write_mesh,
};
pub use meshes::{MeshReport, TriMesh};
pub use polygonize::{
    BlockSkip, PolygonizeSettings, PolygonizeStats, Resolution, SurfaceBox,
    polygonize_continuation, polygonize_grid, surface_extent, surface_seeds,
};
pub use queries::{
    DipoleTree, WindingTree, closest_on_triangle, dipole_winding_numbers, sample_surface,
    winding_numbers, winding_numbers_exact,
};
pub use volumes::{
    MAX_SUPERSAMPLING, Volume, VoxelMethod, VoxelSettings, check_volume_size, classify_blocks,
    has_other_neighbour, signed_distance, squared_distance_transform, voxelize,
};
